// Example-based growth of a road network (Yu & Steed, "Example-based Road Network Synthesis"):
// from unfinished nodes, find example nodes whose incident edge angles match under a rotation
// (node matching), choose the one whose surroundings look most like the output's surroundings
// (neighbourhood matching by a weighted line-segment Hausdorff distance), copy its incident edges
// as proposals and adapt them to local constraints (legal region, obstacles, snapping, no
// crossing, dead ends stay dead ends).
//
// The example is read as the paper's planar graph: every polyline is cut at its vertices into
// straight segments, so nodes are junctions, dead ends and shape points. Output edges are
// straight segments between output nodes in the same way.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geos_context.hpp"
#include "core/growth/patches.hpp"
#include "core/raster/grid_field.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct ExampleEdge {
  Polyline line;
  std::string road_class;  // levels: with match_levels, only edges of one class match each other
  std::int64_t id = 0;     // the example row it came from (traceability: GrownEdge::example_id)
  int example = 0;         // which example (0-based) when several are blended
};

// Teng & Bidarra's parametric growth: at an unfinished node of target degree k (drawn from
// [min_degree, max_degree]), new streets leave along a lattice of directions 360°/max(4, k) apart
// (aligned with the node's first street, or with the guide), straight on first, each turned by up
// to angle_deviation, with a length drawn from length ± length_deviation (never below min_length).
struct ParametricParams {
  double length = 50.0;            // metres
  double length_deviation = 10.0;  // metres
  double min_length = 20.0;        // metres
  int min_degree = 2;
  int max_degree = 4;
  double angle_deviation = 10.0;   // degrees
  std::string road_class = "main";
};

// How the example of a step is chosen when several are given (Yu & Steed's blending).
struct BlendParams {
  enum class Mode { none, gradient, points } mode = Mode::none;
  double angle = 0.0;         // gradient: degrees; 0 runs from the region's west (first example) to its east (last)
  std::vector<Point> points;  // points: one per example; weight exp(-d^2 / (2 sigma^2))
  double sigma = 0.0;         // metres; 0: a quarter of the region's extent diagonal
};
// Patch growth (Nishida et al. 2016, section 4.3): at a front, a patch is drawn with probability
// proportional to exp(-d / scale), d the smallest Hausdorff distance between one of its connectors
// (placed with its inner end on the front) and one of the front's streets, among the patches that
// pass the legality checks (region, obstacles, no crossing, angles, degrees).
struct PatchGrowParams {
  double scale = 0.1;         // metres; Nishida's eq. 2 reads d in metres (scale 1): 0.1 measured closer (README)
  double max_distance = 0.0;  // metres: patches farther than this are not drawn; 0: 0.25 x the mean street length
  double angle_window = 30.0; // degrees: connectors compared with a street leave within this of its direction
  int tries = 24;             // legality checks per front before the statistical fallback
  int max_uses = 0;           // uses per patch when the patch sets none; 0: unlimited
  double rotation = 0.0;      // degrees: every patch turned by this (Nishida: one rotation per growth)
  double clearance = 0.0;     // metres: new patch streets keep this far from streets they do not meet;
                              // 0: 4 % of the mean street length
  bool levels = true;         // patches tagged arterial grow first, then the others from seeds along the
                              // arterial streets (Nishida's section 4.4); false: all patches at once
  // Interpolation of two styles (Nishida et al. 2016, section 5): with GrowInput::patches_b, a
  // front draws its patch from the second library with probability t (else the first; when none of
  // the drawn one is legal, the other is tried with its own probability), and the statistical
  // fallback takes the two styles' length and curvature statistics interpolated with weight t.
  // GrowParams::blend (gradient or points, one point per library: Gaussian fall-off from each
  // style's seed) makes t vary over the region.
  double t = 0.0;
  // Dangling-edge post-process (Nishida et al.): after growth, a street ending in a dead end is cut
  // back to its junction unless the dead end is the example's (the end of a patch's dead-end
  // edge), the street ends at the region's edge, an obstacle, water or a slope too steep (a step
  // on is illegal), or it is a bridge or the existing network.
  bool prune_dangling = false;
  // An example without a dead end of its own (its library's own dead ends 0 of its street ends, the
  // crop's aside: new-york) grows none either: the post-process above runs after the joins whatever
  // prune_dangling says. New-york's growths kept 2.8 dead ends inside the window on average (seeds
  // 1-120; 110 of 120 growths had one or more), which compare_networks cannot weigh against the
  // example's none (a relative difference from 0 is left out of the per-pair median). With it, its
  // per-pair median 1.93 / 2.30 / 2.35 -> 1.49 / 1.57 / 1.76 % (medians over seeds 1-60 / 61-120 /
  // 121-180), pairs over 5 % 3 / 1 / 3 -> 0 / 0 / 0, the 4-way share within 5 points on 52 / 49 / 47
  // -> 55 / 54 / 54 of 60 seeds; the other examples have dead ends of their own and grow as before
  // (README "No dead ends where the example has none").
  bool prune_without_own_dead_ends = true;
  // The statistical fallback's streets bend by the example streets' curvature (Nishida et al.:
  // procedural growth from the length and curvature distributions): each takes the curvature of
  // an example street drawn at random, times its length, as a circular arc; false: straight. Off
  // by default: on, bench/patches' realism was worse on seeds 1-3 (per-pair median 3.10 -> 3.23 %,
  // values past 15 % 9 -> 11: canberra's blocks and 4-way share; README).
  bool fallback_curvature = false;
  // Before that: a street ending where the example's do not is extended to the closest node, or
  // straight on to the first street, ahead of it within half a mean street (Nishida et al.'s local
  // constraint, section 4.3.4).
  bool connect_dangling = true;
  // Joins under the example's junctions (patches34; with connect_dangling, not in a city of
  // cul-de-sacs): a join that makes a junction (onto a node of degree 2, or a street split) is
  // refused while the network's junctions farther than 50 m from the region's boundary, less those
  // the cut-backs to come will take (the corner fronts and crop ends still dead ends whose street
  // leaves a T), would pass the example's per area by more than half a junction; the dead end is
  // then cut back with the corner fronts, or stays. A dead end whose street leaves a crossing joins
  // as before (its cut would lose the crossing). The joins made 16-33 of strasbourg's T's inside
  // the hull shrunk by 50 m (its junctions 134-168 against the example's 140, 4-way share -15 to
  // -22 %; bench/patches, README).
  bool dangling_junctions = true;
  // Dead ends' joins under the example's small blocks (with connect_dangling, on a weakly ordered
  // example: φ from 0.15 and under 0.6, not a city of cul-de-sacs; barcelona, strasbourg): a dead
  // end's join to a node or street ahead that would close a block whose perimeter is under the
  // example's 20th percentile (its blocks' perimeters, dead-end streets left out) is refused; the
  // dead end then stays or is cut back with the others. Each join splits a block: barcelona's grown
  // blocks were 2-8,000 m² where its example has large ones, its median block -9.0 / -8.8 / -9.2 %
  // (seeds 1-60 / 61-120 / 121-180, past 15 % on 4 / 6 / 9 seeds), its example's own tiles 2-3 %
  // of the time. With the floor -5.1 / -4.8 / -5.5 % (1 / 0 / 1 seeds), its per-pair median 1.96 /
  // 1.92 / 1.93 -> 1.76 / 1.87 / 1.72 %, its φ -8.8 / -10.7 / -7.0 -> -7.4 / -11.7 / -7.5 % (past
  // 15 % on 63 -> 73 of 180 seeds, its example's tiles 20-38 % of draws); strasbourg's per-pair
  // median 2.77 / 2.91 -> 2.77 / 2.78 %. The 20th percentile chosen on barcelona's seeds 1-20
  // against the 15th and 25th (README "Dead ends' joins and small blocks").
  bool dangling_block_floor = true;
  // Teng & Bidarra's rule of use for terminal patches (one connector, as extract_patches tags them
  // `terminal`: they add no front, so the street they end cannot go on; the tag itself is not read):
  // at a dead-end front a terminal patch is drawn only where
  // little room is left ahead of it, that is a street or node of the growth within this many mean
  // streets ahead (the cone of the dead ends' joins) or the region's edge, an obstacle or water on
  // the straight line that long. Junction fronts (local seeds on main streets) are not ruled.
  // 0: off (drawn anywhere, as any patch).
  double terminal_room = 0.0;
  // After the joins (with connect_dangling): a T-junction whose lone street meets a T facing it
  // across the through street, within a mean street straight on, is joined to it, so both become
  // crossings, while the network has fewer 4-way junctions than the example's share (the example's
  // cross streets run on across; growth leaves them as pairs of T's); then an arterial T (three
  // main streets) with no T facing it goes on straight to the first street ahead (split there).
  bool continue_across = true;
  // With continue_across: a local T (its lone street a grown street) with no T facing it goes on
  // straight to the node or street ahead within a mean street as an arterial T does, while the
  // network has fewer 4-way junctions than the example's share, and while its street length farther
  // than 50 m from the region's boundary stays under the example's per area (the example's farther
  // than 50 m from its hull over that shrunk hull's area); where that makes a junction (a split
  // street, a node of degree 2), only while its junctions there stay within half a junction of the
  // example's per area. Growth leaves grid streets ending at a T a block short of the next one
  // (new-york's 4-way share -14 to -17 pp; bench/patches, README, patches28).
  bool continue_local_tees = true;
  // With continue_across: after the post-growth cuts (cut_corner_fronts, straighten_corners,
  // prune_dangling), the facing joins once more, within two mean streets. A dead end cut back off a
  // crossing leaves a T whose missing arm often faces a T across the block, and T's of long blocks
  // face each other farther than one mean street (new-york's blocks are 80 by 270 m, its mean street
  // 142 m). Joined while the network's 4-way share is under the example's, as continue_across's.
  bool facing_after_cuts = true;
  // With continue_across, in a city of crossings (as align_stems: an ordered example, one style, more
  // than half of its junctions crossings): the facing joins take a T within 50 degrees of the heading
  // (angle_window otherwise), and after the cuts within four mean streets (two otherwise). Where two
  // patches' grids meet, each side's streets end on a seam street of its own, the two 30-60 m apart,
  // and the ends facing each other across that strip are offset by more than angle_window (new-york's
  // 4-way share -6.5 -> -5.5 pp on seeds 1-30, -7.6 -> -6.6 on 31-60; tokyo's and strasbourg's φ
  // fell with it ungated; bench/patches, README "Where the T's come from").
  bool wide_facing = true;
  // Wide facing joins on a weakly ordered example (as weak_order_corners: φ from 0.05 and under 0.6,
  // not a city of cul-de-sacs; barcelona, strasbourg, quito): the facing joins take a T within 35
  // degrees of the heading (angle_window otherwise), and after the cuts within four mean streets
  // (two otherwise). The joins stopped short of the example's share of crossings among junctions
  // (strasbourg: 0.343 over the region, seeds 1-30, against its joins' target 0.400), for want of
  // T's facing each other within 30 degrees: its 4-way share was -7.0 / -7.7 % at the mean over
  // seeds 1-60 / 61-120, past 15 % on 15 / 15 of them. With it -0.3 / -1.3 % (4 / 13), its per-pair
  // median 2.88 / 2.89 -> 2.56 / 2.73 %, barcelona's 1.67 / 1.78 -> 1.69 / 1.61 %, quito's 2.30 /
  // 1.98 -> 2.09 / 2.00 %. 40 and 50 degrees cost more φ (quito's, strasbourg's); on tokyo
  // (ordered, not a city of crossings) 35 degrees raised the per-pair median 1.53 -> 1.68 % (README
  // "Wide facing joins on a weakly ordered example").
  bool weak_order_facing = true;
  // Islands joined (after every other pass): a part of the network that no street links to the rest
  // (the part with the most grown street, or one holding the existing network) is joined to it by
  // the shortest legal street from one of its nodes to a node within a mean street of it. When no
  // such join is left, a part with a mean street or more is joined within five mean streets (a
  // neighbourhood or a main street beyond a void the length cap left), and the near joins go on. A
  // part still apart with less street than a mean street is removed; larger ones stay (beyond an
  // obstacle, or farther). Growths of seeds 1-60 of the six examples had 86 such parts (41 of them
  // barcelona's, most 5-400 m long and 7-27 m from the rest: pieces the cut-backs and the cap left
  // apart), 10 of them left 100-401 m away, all joined now; README "Islands joined".
  bool join_islands = true;
  // With continue_across, in a city of crossings (as wide_facing): a T whose facing T (within the
  // same cone and reach) lies beyond one or two streets, so that no plain join reaches it, is joined
  // to it across them, each street split where the join crosses it: two T's and the streets crossed
  // become crossings, a junction more per street crossed. The example's cross streets run on through
  // the avenues where growth left a T a block or two short of the T facing it (new-york's 4-way share
  // -5.5 -> -3.7 pp on seeds 1-30, -6.6 -> -4.4 on 31-60; bench/patches, README "Where the T's come
  // from").
  bool facing_through = true;
  // On an ordered example (tokyo, new-york), the joins continue_across makes between facing T's,
  // and those from a dead end (connect_dangling) or a straightened corner's kept street
  // (straight_corners) to a node ahead, first slide the nodes they join along their streets so that
  // the join runs along the grid's axis instead of across the block at the nodes' offset: a T along
  // its through street (its lone street turning at most 10 degrees and ending at most 5 off the
  // grid), a shape node along its straight street, a bend along its street more square to the join;
  // the two T's of a facing join half the offset each, the node ahead all of it. Where the slid join
  // is refused, the join is tried unslid. Tokyo's φ -13.3 / -12.8 / -12.9 -> -8.8 / -8.6 / -8.8 %
  // (medians over seeds 1-60 / 61-120 / 121-180); README "Joins slid onto the grid".
  bool slide_onto_grid = true;
  // With slide_onto_grid: a dead end's join to a node ahead (connect_dangling) that, slid as far as
  // the nodes' streets allow, would still run more than 20 degrees off the grid's direction is not
  // made; the dead end tries the next node ahead, then the street straight ahead, else stays for the
  // cut-backs. A dead end joined across to a node that cannot slide (a crossing, a dead end, a T
  // with no room) made a diagonal street of the two grids' streets it joined: with simplify, the
  // metrics read each street from junction to junction, and tokyo's joins held the largest share of
  // its φ gap among the grown (non-patch) streets, which hold all of it (its patch streets alone are
  // more ordered than the example). Tokyo, seeds 1-60: φ -9.2 -> -7.4 % at the median, past 15 % on
  // 8 -> 5 seeds; new-york's as before. 5 / 10 / 15 / 20 / 25 degrees measured (README "Dead ends
  // join along the grid"). Joins the other rules make (facing T's, corners straightened) are left:
  // refused too, they left tokyo more corners (30 a growth against 19 with this, 16 without) and φ
  // no better.
  bool grid_joins = true;
  // On an ordered example (as slide_onto_grid; not under a guide or direction raster, whose warp
  // has no one grid), once the growth is done its junctions and dead ends settle: each with a join
  // or statistical street off the grid moves to the least-squares point of the lines its streets
  // ask for, so that those run along the grid while its patch streets keep their direction. A patch
  // street asks for its own line through its far end (4 times the weight), a join or statistical
  // street within 30 degrees of the grid for the grid's line through its far end; one more than 30
  // degrees off asks for nothing. Five rounds over the nodes; no node moves more than half a snap
  // distance from where growth left it, and a move is made only where the moved streets stay legal,
  // touch no other street, keep the clearance, min_angle and min_length. The streets' shape points
  // and the existing network's nodes stay, and so does the topology. The joins and the fallback held
  // most of tokyo's φ gap. Tokyo, seeds 1-60 / 61-120: φ −6.6 / −7.2 → −4.4 / −4.7 %
  // at the median, per-pair median 1.63 / 1.75 → 1.53 / 1.66 %; new-york φ −2.8 / −2.6 → −2.3 /
  // −2.1 %, per-pair median 1.49 / 1.59 → 1.36 / 1.49 %; the junctions are unchanged (README "Nodes
  // settle onto the grid").
  bool settle_onto_grid = true;
  // Settling on a weakly ordered example (with settle_onto_grid; φ from 0.15, not a city of
  // cul-de-sacs, as weak_order_seams), whose patches are grids turned every way: a node's grid is
  // the one its patch streets make around it (their length-weighted four-fold mean direction, the
  // patch streets within one mean street of the node), and a node whose patch streets around agree
  // on less than 0.6 of it stays. Barcelona, seeds 31-120: φ −10.9 → −7.6 % at the median, past
  // 15 % on 39 → 27 seeds, per-pair median 1.81 → 1.69 %, the whole goal met on 53.3 → 66.7 % of
  // the growths; strasbourg's φ moves inside its noise (README "Nodes settle onto local grids").
  bool weak_order_settle = true;
  // Patch streets that double a street, in a city of crossings (as wide_facing): a placed patch's
  // street every point of which lies within 1.25 x snap of the network is left out, not only within
  // snap (Nishida's redundancy). Where two patches' grids meet, each brings the seam street of its
  // own side, and the second runs beside the first a little farther than snap (new-york: 64 m, its
  // blocks 80 m across): the strip between them holds the T's of both sides' cross streets, which
  // end on different streets. New-york's 4-way share -3.7 -> -3.2 pp on seeds 1-30, -4.4 -> -2.9
  // on 31-60, its per-pair median 2.93 -> 2.55 / 3.01 -> 2.60 %; 1.1 / 1.35 / 1.5 x snap measured
  // (README "Streets that double a street"). Ungated it gained on barcelona but lost on quito, tokyo
  // and canberra.
  bool wide_redundant = true;
  // Corners (with connect_dangling): at a dead-end front with a node or street ahead within a mean
  // street, a patch that would leave the front as a corner (its only new street there turning more
  // than 45 degrees from the front's street, the others left out as redundant) is illegal, and such
  // a front gets no statistical fallback: after growth it is joined to a node or street ahead within
  // a mean street, else its street is cut back to its junction while the network has more dead ends
  // than the example's share. Not in the arterial phase, nor for a city of cul-de-sacs (own dead
  // ends over 15 % of the example's street ends). Growth left hundreds of such corners where
  // patches met their neighbours a few metres off, and a corner between two streets of a grid reads
  // as one diagonal street (bench/patches: orientation order, README).
  bool avoid_corners = true;
  // Crop ends (with avoid_corners, and in a city of cul-de-sacs, which keeps its corner fronts): a
  // patch's dead-end edge that ends on the example's crop (marked cut: within a quarter of the mean
  // street of its library's hull) is no dead end of the example, but placed inside the region it is
  // one. After the joins, those still dead-ended are cut back to their junction with the corner
  // fronts, under the same budget (while the network has more dead ends than the example's share of
  // its street ends); not where a step on is illegal (the region's edge, an obstacle, water).
  // Strasbourg's grown dead ends were mostly such copies (seeds 1-3: 13-18 of 17-22 inside the hull
  // shrunk by 50 m; bench/patches, README).
  bool cut_crop_ends = true;
  // Seams (patches31; only where the example is ordered, its orientation order φ at least 0.6, and
  // while the output's φ is under the example's): a patch end that merges into a node within snap
  // turns the patch's street there, and the patches' seams were where tokyo lost its grid (README).
  // seam_turn (degrees; 0: off): at a front, a draw whose merges would turn one of the patch's
  // streets (its chord) by more than this is refused at first; when that refused one and no other
  // was placed, the draws are tried again without the rule (the front keeps a patch rather than
  // falling back to statistical streets). seam_slide: a dead end of the network (an earlier
  // connector's guess at where its neighbouring junction is) that a patch vertex merges into slides
  // along its own street to meet it (the street keeps its bearing), so only the offset across it
  // turns the patch's street.
  double seam_turn = 5.0;
  bool seam_slide = true;
  // Seams of a weakly ordered example (with seam_turn or seam_slide): the seam rules also where the
  // example's φ is at least 0.15 (barcelona 0.28, strasbourg 0.19; not quito 0.073), not in a city
  // of cul-de-sacs. Barcelona's φ was past 15 % on 29 of seeds 1-60, 20 with it; its values past 15
  // % 42 -> 30 (README "Seams of a weakly ordered example").
  bool weak_order_seams = true;
  // Corners straightened (patches32; only where the example is ordered, φ at least 0.6, and the
  // output's φ more than 10 % under it): after the joins and the cut-backs, a corner of grown streets
  // (a node of degree 2 turning by more than 45 degrees) has one street go on straight to the node or
  // street ahead (within angle_window and a mean street) and the other dropped back to its junction
  // (kept where that would cost a crossing and the node ahead is a T: the corner becomes a T, the T a
  // crossing). Not where the junction left would become a corner, nor where a dead end would come or
  // go, nor while a change would take the network's share of crossings among its junctions more than
  // 12.5 % under the example's. A corner between two streets of a grid reads as one diagonal street:
  // tokyo's 80-120 corners a growth held most of its orientation-order gap (bench/patches, README).
  bool straight_corners = true;
  // Corners straightened in turn (tok44; with straight_corners): in its second round (the changes
  // that lower the share of crossings), a corner's street may be dropped even where that leaves its
  // junction a corner, and that corner is straightened in its turn, in the same round. Tokyo's
  // corners refused for their junction were most of those left (45 a growth after the straightening,
  // 30 with this); a T made instead adds a street the density counts (README "Where φ comes from").
  bool corner_cascade = true;
  // Corners straightened before the cut-backs too (with straight_corners): cut_corner_fronts stops at
  // the example's dead-end share of the street ends, and the T's the straightening makes afterwards
  // are street ends the cut-backs did not count, so the output's share came out under its example's
  // (quito -7.7 %, barcelona -4.9 %, tokyo -3.3 % at the median over seeds 1-60). Straightened first,
  // the corners' T's are in the count; the corners the cut-backs leave are straightened after them as
  // before (README "Corners before the cut-backs").
  bool corners_before_cuts = true;
  // The level rule (the local phase places no patch whose main streets double none there) spares a
  // patch tagged roundabout while the growth has none: a roundabout on main streets in the example
  // then comes in the local phase with them. The arterial phase starts from few fronts and its few
  // roundabout draws were refused (junction mix, clearance, the region), so 9 of canberra's 120
  // growths (seeds 1-120, its hull) had no roundabout where its example has nine; with it none, its
  // whole realism goal on 25.0 / 33.3 -> 33.3 / 35.0 % of seeds 1-60 / 61-120. Barcelona's growths
  // have a roundabout early (3 of 120 differ); quito's and strasbourg's draws are refused for
  // clearance (README "The first roundabout").
  bool first_roundabout_in_local_phase = true;
  // The growth's first roundabout leaves out its spokes (connectors, dead ends) that would come
  // nearer the network than the clearance, and the inner streets that then hang, instead of being
  // refused: the examples' roundabout patches are large (strasbourg's ring is 145 m across, its
  // patch 300 m) and their draws were refused for clearance most of the time. Its ring and the
  // streets that stay must still be legal, and one spoke besides the front's street must stay.
  // Seeds 1-120 without a roundabout: quito 13 -> 2, strasbourg 29 -> 23; the whole realism goal
  // quito 42.5 -> 49.2 %, canberra 34.2 -> 37.5 %, strasbourg 35.0 -> 31.7 % (README "Spokes
  // left out of the first roundabout").
  bool roundabout_spokes_dropped = true;
  // The growth's first roundabout, refused for clearance at its front, is tried again 40, 80 and
  // 120 m ahead, joined to the front by a straight street that carries the front's street on (its
  // patch's connector there, drawn longer). Strasbourg's ring is 145 m across and its draws at the
  // fronts were refused for the clearance of the ring itself (124 of 235 draws over seeds 1-120;
  // its spokes 110, which roundabout_spokes_dropped leaves out); ahead of the front there is room.
  // Seeds 1-120 without a roundabout: strasbourg 23 -> 11; its whole realism goal 31.7 -> 30.8 %,
  // quito's 49.2 -> 47.5 %, canberra's and barcelona's the same (the growths that change move as
  // redraws do; README "The first roundabout ahead of its front").
  bool roundabout_shift = true;
  // The growth's first roundabout keeps its ring whole: the ring's vertices do not merge into nodes
  // of the network within snap, as the patch's other vertices do. Merged, a ring vertex bent the
  // ring or closed it on a street already there, and the doubled ring streets were left out: read
  // from the geometry (a compact face, at most 200 m across, bounded at least half by roundabout
  // streets; bench/patches/run.sh "rings"), 135 of the 480 growths of barcelona, canberra, quito
  // and strasbourg (seeds 1-120) had no ring, 121 of them with a roundabout patch used. With the ring
  // kept, its clearance and crossings are checked as placed: 97 (quito 36 -> 25, strasbourg 43 ->
  // 27, canberra 50 -> 41, barcelona 6 -> 4); the whole realism goal quito 47.5 -> 52.5 %,
  // strasbourg 30.8 -> 34.2 %, barcelona 80.0 -> 77.5 %, canberra 37.5 -> 34.2 % (README "Rings
  // read from the geometry").
  bool roundabout_ring_kept = true;
  // Corners of a weakly ordered example (with straight_corners): straightened also where the
  // example's φ is at least 0.05 (barcelona 0.28, strasbourg 0.19, quito 0.073), not only 0.6
  // (tokyo, new-york), but not in a city of cul-de-sacs (canberra), and there a change that adds a
  // junction only within the example's junctions per area (README "Corners of a weakly ordered
  // example", "Corners of quito"). Barcelona's φ was past 15 % on 18 of seeds 1-30, quito's on 36
  // of seeds 1-60 (27 with it).
  bool weak_order_corners = true;
  // Corner T's (weak_order_corners on a weakly ordered example, not an ordered one): a corner's
  // straightening keeps its other street, so that the corner becomes a T (and the node ahead a
  // junction), while two more junctions keep the network's (inside the budget margin) within the
  // example's per area; past that the other street is dropped as before, and only where the output's
  // φ is more than kCornerOrderGap under the example's (the drops are for φ, the T's for the
  // junctions: where φ is near, the T's alone). Dropping took street length and left quito's
  // junctions 5-6 % under its example's at the median over seeds (inside the hull shrunk by 250 m
  // 6.84 a km against 7.28; its ring had the example's). With it, seeds 1-60 / 61-120 / 121-180:
  // per-pair median 2.60 → 2.30 / 2.88 → 2.18 / 2.90 → 2.15 %, intersections −6.4 / −5.2 / −6.0 →
  // −0.9 %, φ −4.7 → −8.3 / −5.8 → −9.4 / −4.4 → −8.2 %; seeds over 5 % per pair 17 → 5 of 180.
  // Barcelona and strasbourg are mostly at or over their examples' junctions per area (per-pair
  // medians 0.1-0.2 points lower); ordered examples and canberra as before (README "Corners to T's").
  bool corner_tees = true;
  // Grid fallback (grid41; an ordered example, φ at least 0.6, one style): a statistical street
  // turns onto the example's grid axis (mod 90 degrees, turned as the patches are) when the street it
  // leaves is within 15 degrees of it, and its free end snaps to a node or street only within half a
  // snap distance of its own line (else it goes straight on to a street ahead within snap, or is
  // refused). Tokyo's statistical streets had 40 % of their length more than 10 degrees off its grid
  // (its patch streets 5 %): they turned from the street they left and snapped sideways (bench/patches,
  // README "Grid rules for tokyo's φ").
  bool fallback_grid = true;
  // With fallback_grid: while the output is less ordered than its example (φ, as network_stats
  // computes it), a statistical street turns onto the grid axis also when the street it leaves is
  // more than 15 degrees off it. A patch copied from a district of the example that lies askew to
  // its grid (tokyo's south-east, about 30 degrees off) left fronts along its own axis, and the
  // statistical streets carried that axis on, street after street: tokyo's growths past 15 % on φ
  // were those whose askew districts had grown to up to twice the example's share of the length.
  // Tokyo, seeds 1-120: φ past 15 % on 9 -> 1 seeds, its per-pair median 1.84 -> 1.68 %; README
  // "Askew districts are not carried on".
  bool fallback_grid_askew = true;
  // Dangling corners (grid41; an ordered example, as fallback_grid): connect_dangling first joins
  // only what leaves no corner (a node of two streets turning by more than 45 degrees) at either end;
  // a dead end left with only such joins is then cut back to its junction where that junction stays
  // a junction or goes on straight, else joined as before. A corner merges two streets of a grid into
  // one diagonal chain: tokyo grew 35 a growth inside the hull shrunk by 50 m, its example has 4.
  bool dangling_corners = true;
  // Short dead ends cut back (connect_dangling on a weakly ordered example: φ from 0.15 to under
  // 0.6, not a city of cul-de-sacs): a dead end no farther from its junction than the joins reach
  // (half a mean street) is cut back to that junction instead of joined, where that leaves no corner
  // (as dangling_corners). Each join of a dead end splits a block: barcelona's growths had more
  // blocks of 2-6k m² than its example and its block area was 11.7-12.7 % under at the median over
  // seeds. With it, seeds 1-60 / 61-120: barcelona's block area −11.7 → −9.0 / −12.7 → −8.8 %, its
  // intersections +2.8 → +0.2 / +0.7 %, per-pair median 2.14 → 1.96 / 2.01 → 1.92 %, values past
  // 15 % 30 → 22 / 35 → 30; strasbourg's per-pair median 3.19 → 2.77 / 3.26 → 2.91 %, block area
  // −8.0 → −5.9 / −3.1 → −1.7 % (README "Short dead ends cut back").
  bool cut_short_ends = true;
  // Stratified redraw (local phase, or one level; not for a city of cul-de-sacs): a front's first
  // draw (eq. 2's choice were every patch legal) refused for a conflict that grows with street
  // length (clearance, crossing, angle) is followed by the draws of its size class first (terciles
  // of the mean connector length), then the others, each in its key order. Legality refuses long
  // streets more often (they pass near more of the network), so without it the placed patches were
  // smaller than eq. 2's draws (barcelona's first draws by tercile 39/34/27 %, placed 54/32/15 %)
  // and the network denser than the example (bench/patches, README). A city of cul-de-sacs is left
  // out: its growth dies out like a branching process, and the larger patches made it stop earlier
  // on two of three seeds (canberra seeds 4-6: street density -29 % to -50 %).
  bool size_redraw = true;
  // Front crossings (patches33; a city of cul-de-sacs, local phase or one level): a patch whose
  // junction lands on a front that already holds streets (connectors of earlier patches reached it)
  // and so makes it a node of degree 4 or more, while the patch's own junction there has fewer than
  // 4 streets, is refused while the output's share of crossings among its junctions is at or above
  // the example's (one more would not bring it nearer); the front draws on. The junction-mix check
  // held only for the nodes a patch merges into, not for its front: such fronts made 8-10 of the 12-13
  // crossings canberra_south_large grew inside the hull shrunk by 50 m (seeds 1-3, the example 7;
  // copies of its crossings 0-1). With it, continue_across joins a pair of T's only while both new
  // crossings bring the count nearer to the example's. Not for the other examples: the output's share
  // passes the example's early in the growth and the joins after it lose crossings (strasbourg: 4-5
  // draws refused a growth, its final share 16-26 % under the example's). bench/patches, README.
  bool front_crossings = true;
  // Crossings inside the crop (a city of cul-de-sacs): continue_across's joins aim at the example's
  // share of crossings among its junctions farther than crop_margin inside its hull (the share the
  // front crossings keep), not the whole example's, whose crop ring is a sample of a few junctions.
  // Canberra_south_large's whole example 0.0213, inside 0.0194: a join makes two crossings, and
  // growths at 6 took one more pair to 8 inside the hull shrunk by 50 m (the example 7). 4-way share
  // +14.1 -> +2.4 % at the median over seeds 1-120, seeds past 15 % 61 -> 20, per-pair median 2.45
  // -> 2.30 % (README "Crossings inside the crop").
  bool interior_crossings = true;
  // Stems aligned (a city of crossings: an ordered example, φ at least 0.6, one style, more than
  // half its junctions crossings; new-york, not tokyo): a front's draw favours the patches whose
  // vertices land (within half a snap distance) on a T of the network and leave it where its lone
  // street would go on across, making it a crossing: each such vertex weighs as a Hausdorff distance
  // three scales shorter. New-york's T's were avenue pieces ending at a line where the patch beyond
  // put its avenues elsewhere (about 45 a growth against the example's 26). Its 4-way share −7.5 →
  // −6.5 points on seeds 1-30, −8.85 → −7.6 on 31-60 (README "Stems aligned").
  bool align_stems = true;
  // Ends on lines (a city of crossings, as align_stems): a front's draw also favours the patches
  // whose ends (patch vertices of one street: connectors' and dead ends', the front aside) land
  // within a quarter snap distance of the line of a network street across theirs (within 10 degrees
  // of square, its nearest point within 1.5 mean streets): each such end weighs as a Hausdorff
  // distance three scales shorter. A row of new-york's blocks put its avenues at the sums of its own patches' connector
  // lengths, so the rows did not agree where the avenues run, and an avenue of the next row met a
  // street halfway along its block. Its 4-way share −3.22 → −1.36 points on seeds 1-30, −2.88 →
  // −2.27 on 31-60, −3.14 → −2.82 on 61-90 (README "Ends on lines").
  bool align_lines = true;
  // Front dead ends (patches36; a city of cul-de-sacs, local phase or one level): a patch that would
  // bring dead ends of its own (dead-end edges of the example, not the crop's, ending on a new
  // vertex) is refused while the output's share of such dead ends among its junctions and those
  // dead ends is at or above the example's dead-end share; the front draws on, and when the rule
  // left it without a patch its draws are tried again without the rule. Drawn by their Hausdorff
  // distance alone, canberra_south_large's patches brought more cul-de-sacs per junction than the
  // example has: its dead-end share +10 % (seeds 1-9, 122-176 of its 128-181 dead ends inside the
  // hull shrunk by 50 m copies of the example's dead-end edges, which the joins leave alone); joining
  // them afterwards split blocks the example keeps whole (patches34). bench/patches, README.
  bool front_dead_ends = true;
  // Spread order (a city of cul-de-sacs, one style): while the output is more ordered than its
  // example (φ as network_stats computes it, both without the entropy's sampling bias), a front's
  // draw leaves out the patches already used and draws ten times flatter (the scale times 10).
  // Patches are placed as the example drew them (not turned), and the draw picks the best fit by
  // far (scale 0.1 m): canberra_south_large reused a few patches at the same bearings (its ten most
  // used took a fifth of the placements) and grew more ordered than its weakly ordered example (φ
  // 0.037): +36 % at the median over seeds 1-120, +37 % over 121-240; with the rule +8 / +8 %.
  // Always on (max_uses 1, scale 1) it drew blocks 7 % larger; in every example (no gate) the φ of
  // barcelona, strasbourg and quito fell from −12 / −5 / −7 % to −17 / −22 / −20 % at the median
  // over seeds 1-30, their outputs being more ordered than their examples while they grow (README
  // "Spread order").
  bool spread_order = true;
  // Refill (patch growth, after the local phase): when the queue empties while the grown streets
  // are shorter than `refill` x the example's street length per area of its hull x the region's
  // area, a random legal point farther from every street than the example's own widest gap (its
  // parks stay parks) is drawn and the street point nearest to it becomes a front (the void grows
  // from its edge, as Nishida et al. seed local streets along streets); where that grows nothing, a
  // seed patch inside the void (not across water or an obstacle). Until the length is reached or
  // no such point is found. Without it canberra's local phase died out like a branching process
  // (street density -16 to -64 %); 0.85 measured best of 0.7 / 0.85 / 1 before the length cap.
  // With the cap, whose cut-back of the open connectors leaves a growth at 0.91-0.97 x, 0.95 makes
  // up most of that in the voids the cap left at the region's edge: seeds 1-60, per-pair median
  // (mean over the six examples) 2.60 → 2.40 %, values past 15 % 242 → 239, the share of the window
  // farther than 100 m from every street barcelona 11.8 → 8.0 %, quito 8.6 → 5.7 % (seeds 1-30;
  // README "Refill to the cap"). 0: off.
  double refill = 0.95;
  // Length cap (patch growth, local phase or one level): the growth stops once its streets are
  // `length_cap` x the example's street length per area of its hull x the region's area long, and
  // the open connectors still queued are cut back to their junctions (artefacts of the stop, not
  // dead ends of the design). Breadth first from the seeds, the growth otherwise filled the whole
  // region at the density of the example's built-up parts, while the example's hull also holds
  // land it leaves empty (parks, yards, the crop's irregular edge): strasbourg grew 1.04-1.25 x its
  // example's length, barcelona 1.17-1.19 x, quito 1.16 x before its joins (bench/patches, README).
  // 0: off.
  double length_cap = 1.0;
  // The cap after the joins (with length_cap): the joins, continuations and mends made after the
  // growth stopped add street length the cap did not count. Tokyo's growths ended at 1.036 x their
  // cap (median over seeds 1-60, up to 1.065), its street density +4.3 % inside the window; the
  // other examples at 0.95-1.01 x. A growth that ends more than `regrow_past_cap` over its cap is
  // grown once more with the cap lowered by that overshoot (the same seed: the same draws until the
  // lower cap stops it; regrow_checkpoint), and the one of the two that ends nearer the cap is kept.
  // Grown again from the start, the growth cost twice where it applies (bench/patches' speed part,
  // tokyo's 2,770 m square: 298 km in 2.45 s against 311 km in 1.30 s without; the issue asks 300
  // km in under 3 s); regrow_checkpoint saves most of that.
  // Seeds 1-180: tokyo's per-pair median 2.10 → 1.77 %, its pairs over 5 % 6 → 3, street density
  // +4.3 → +1.3 %, intersections +1.1 → −2.6 % (its growth has fewer junctions per km than the
  // example); quito 2.20 → 2.05 %, but its values past 15 % 106 → 114 (φ, inside its example's own
  // noise, 93 → 99); barcelona 1.74 → 1.76 % (2 seeds regrown); the other three never end 3 % over.
  // At 0.01 quito's regrown seeds (48 of 120) came out worse on balance (+0.10 points a pair;
  // README "The cap after the joins"). 0: off.
  double regrow_past_cap = 0.03;
  // The second growth resumes from a copy of the first taken when its grown length first reached
  // this share of the cap, in the local phase (the two growths are the same until the lower cap
  // stops the second), instead of growing again from the start. It can when the lowered cap is
  // above every length the first growth was checked at before the copy: overshoots up to 1 / 0.9,
  // 11 %; otherwise, or when the cap was first reached in a refill, the second grows from the
  // start. Either way the second growth is the same. Tokyo's 2,770 m square (298 km): 1.54-1.59 s
  // against 2.61-2.73 s from the start; its 8,300 m square's backend peaks at 61 MB against 50 MB
  // (README "The regrowth from a checkpoint"). 0: always from the start.
  double regrow_checkpoint = 0.9;
  // Arterial refill (levels, after the arterial phase, before the local one): the arterial phase
  // copies the example's arterial network outwards from the seed patch, so it covers only the part
  // of the region the example's arterials reach from there (measured: 6-39 % of the example's
  // arterial length on five of six examples, strasbourg 11-39 %), and the local phase then built
  // the junctions the example has on arterials with its fallback (strasbourg: +31 to +76 %
  // intersections). While the grown main streets are shorter than `arterial_refill` x the
  // example's main-street length per area of its hull x the region's area, an arterial seed patch
  // is placed at a random legal point farther from every arterial than the example's widest space
  // between its own arterials (not across water or an obstacle from the nearest arterial), and
  // the arterial phase grows on from it. Not for a city of cul-de-sacs (its local phase filled the
  // land between the new arterials: canberra street density +29 to +42 %). 0.5 measured better
  // than 0.85 (bench/patches, README). 0: off.
  double arterial_refill = 0.5;
  // Arterial phase: a front's street that a patch made is compared whole with the connectors (up
  // to its junction), not over 3 mean streets of all levels: an arterial connector is longer than
  // that (tokyo 279 m on average against a 149 m cap), so the example's own neighbouring patch,
  // whose connector is that street reversed, fell outside max_distance by reach.
  bool arterial_whole_streets = true;
  // Arterial phase: two streets leaving the same vertex of a patch keep the angle between them that
  // the example has, whatever min_angle (the example's dual carriageways part at 10-15 degrees:
  // strasbourg's own neighbouring patch was refused for it); min_angle still holds against the
  // streets already there and between patch vertices merged into one node.
  bool arterial_own_angles = true;
  // Arterial fallback (levels; Nishida et al.'s procedural growth at an arterial front, section
  // 4.3.3): a dead-end front of the arterial phase where no arterial patch is legal grows growth I's
  // parametric rule with the arterial level's own street length statistics and junction mix (and
  // its road class), under the usual local constraints, while the grown main streets are shorter
  // than `arterial_fallback` x the example's main-street length per area of its hull x the region's
  // area. Without it an arterial library too small for the region leaves its arterials' open ends
  // as dead ends where the phase stops. 0: off (the arterial phase has no fallback).
  double arterial_fallback = 0.0;
  // The arterial fallback continues a front's street straight on only (the junctions are the
  // patches', which take over again at its new end): its lattice's branches at right angles to the
  // front's street crossed the example's arterials' directions (barcelona's orientation order -41 %).
  bool arterial_fallback_straight = true;
  // The arterial fallback waits until the arterial phase's queue has emptied: only the fronts still
  // dead ends then get it (and the fronts its streets bring, at once), so the patches take the
  // space first. Not in a city of cul-de-sacs (its arterials are few and end in its local streets).
  bool arterial_fallback_deferred = true;
  // The deferred pass also continues the arterial streets the example's crop cut (patch dead-end
  // edges ending on its hull: copied, they end in the open where the example's street went on).
  bool arterial_fallback_crop_ends = true;
  // At most this many fallback streets in a row from a front the deferred pass queued again (the
  // arterial patches may take over in between, which starts the count again); 0: no limit.
  int arterial_fallback_steps = 0;
  // Local seeds along the arterial streets the statistical fallback made (Nishida et al., section
  // 4.4): each such street is cut into fragments of the local level's mean street length and the
  // local phase starts at every cut, not only at the street's ends; where no local patch is legal
  // at a cut, the local fallback grows from it (a degree-2 node otherwise gets none).
  bool fallback_local_seeds = false;
  // Arterials run on (levels, after every other pass): an arterial street that ends at a node
  // farther than 50 m inside the region, where only local streets go on, is continued by the
  // cheapest route of local streets to a main street ahead of or beside its end: straight on
  // (turning at most 30 degrees at each node), or by a jog (two sharper turns, at most a local mean
  // street apart, then on the way it ran); or straight on to the region's 50 m margin; no longer
  // than the example's widest space between its main streets. Those streets take the arterial's
  // class, cheapest routes first, while the main streets stay within the example's main-street
  // length per area of its hull x the region's area. Nothing moves; only road_class changes.
  // Patches meet with their avenues staggered, and the arterial phase stops where no arterial patch
  // is legal: a growth's avenues ended into local streets 2.1-22 times inside the hull shrunk by
  // 50 m (seeds 1-10) where the example's end 0-4 times (README "Arterials run on").
  bool promote_arterials = true;
  // With promote_arterials, after its routes: an arterial street that still ends into local
  // streets inside the margin, whose main street reaches back within a local mean street to a
  // junction of three or more main streets (through nodes of two), takes the local level's
  // commonest class there. That stub is a patch's avenue past the junction that no route
  // continued; the avenue then ends on the junction, as the example's end on main streets. Each
  // is one avenue end fewer (seeds 1-30: new-york 7.0 -> 2.5 a growth against its example's 1,
  // strasbourg 6.2 -> 4.1 against 1; README "Stubs past a main junction"). Only classes change.
  bool demote_arterial_stubs = true;
  // Teng & Bidarra (2017, section 3.3, Algorithm 2): breadth-first bridging. At a front of one
  // street (local phase, or one level), before the depth-first draw: the other open fronts (nodes of
  // one street, not yet finished) in line of sight within the library's largest pair distance plus
  // snap are paired with the library's pairs of junctions (connector inner ends, the vertices a
  // front receives; pair distances computed once per library) whose distance is within snap of the
  // fronts' distance; each solution (both orientations) is rated 1 - |d_patch - d_graph| / d_graph,
  // and the best rated legal one (every check of place_patch_at, the seam rule where it applies, up
  // to `tries`) is placed turned so its two junctions land on the two fronts (the mismatch taken up
  // by the merge within snap, and by seam_slide where it applies), turned at most max_turn; at each
  // end the connector nearest the front's street (within angle_window, and within max_distance of it
  // by the Hausdorff distance as the depth-first draw compares them) doubles it and is left out.
  // Off by default: it failed the merge rule (bench/patches, README, patches37).
  bool bridge_fronts = false;
  // Teng & Bidarra (2017, section 3.2, "Patches on main streets"): how the local phase starts.
  // seeds: from the example's local junctions along the arterial patches (Nishida's section 4.4).
  // initial: each cell the main streets bound is initialised with patches tagged initial (a straight
  // main street and a local attachment) at seed points spaced along the grown main streets (the
  // example's spacing of local junctions along its main streets), sides alternating (the other side
  // where one is refused): the patch is translated to the seed (a shape node of the street) and turned
  // so that its main street lies along the grown one (only patches within max_turn of it; the seam
  // rule where it applies), its main streets left out; local growth goes on from its connectors.
  // Needs levels (main streets grown first). Default seeds: initial failed the merge rule (README,
  // patches37).
  enum class CellInit { seeds, initial };
  CellInit cell_init = CellInit::seeds;
  // Both (bridge_fronts, cell_init initial): a patch is turned at most this far (degrees) from the
  // library's frame (the warp at the front; for an initial patch mod 180, its main street's two
  // directions being one street). Teng & Bidarra turn patches freely (180); measured on the six
  // examples, 60-90 % of the bridges and 40-75 % of the initial patches were then turned by 20
  // degrees or more, and the grids lost their orientation order (bench/patches, README).
  double max_turn = 5.0;
  double cell_spacing = 1.0;  // cell_init initial's seed spacing over the example's (above)
};

struct GrowParams {
  double epsilon = 30.0;       // degrees: largest angle between a matched pair of incident edges
  double radius = 0.0;         // metres: neighbourhood radius r; 0: 3 x mean example segment length
  bool rotation = true;        // false: θ = 0 (grids keep their orientation)
  std::uint64_t seed = 0;      // the only source of randomness
  std::size_t max_edges = 10000;
  bool match_levels = true;    // match incident edges of the same road class only
  double snap = 0.0;           // metres: snap distance for free ends; 0: 0.55 x mean example segment length (patches: 0.45)
  double min_angle = 20.0;     // degrees: smallest angle between two edges at a node
  std::size_t candidates = 16; // node matches compared by neighbourhood matching per step
  bool parametric = false;     // grow by parameters only (no example): grow_parametric
  bool fallback = true;        // example growth: a step no example node matches grows parametrically
  double coherence = 1.0;      // probability that a node first tries the example node its edge was copied
                               // to (coherent copying, as in texture synthesis); 0: random candidates only
  bool keep_frame = true;
  bool fill = false;           // fronts all dead before the region is covered: grow on from new seeds (SQL grow_example: on)
                               // farther than max(r, the examples' widest empty space) from every edge
  double crop_margin = -1.0;   // metres: an example dead end this close to its hull's edge is a street
                               // the crop cut and grows on; < 0: the mean example segment length      // a node matches under the θ of the match that made it (free θ only if none)
  ParametricParams shape;      // the parametric growth's parameters (with an example: derived from it)
  double guide_reach = 0.0;    // metres: the guide sets θ within this distance of it; 0: everywhere
  BlendParams blend;
  bool use_patches = false;    // grow_patches: GrowInput::patches instead of node matching
  PatchGrowParams patch;
  // Terrain and water (Nishida et al. 2016, sections 4.3.2 and 4.3.4), with GrowInput::dem and
  // GrowInput::water.
  double max_slope = 12.0;        // percent: no new street is steeper (GrowInput::dem); a proposal of
                                  // statistical growth that is bends towards the contour, else is discarded
  double bridge_distance = 300.0; // metres: an arterial that meets water crosses at most this much of it to
                                  // the far bank (a bridge edge); 0: no bridges
  double bridge_turn = 30.0;      // degrees: a bridge may turn this far from the street's direction to cross
                                  // shorter
};

struct GrowInput {
  std::vector<ExampleEdge> example;
  const GEOSGeometry* region = nullptr;  // Polygon or MultiPolygon, valid, non-empty
  std::vector<const GEOSGeometry*> obstacles;  // polygonal; may be empty
  std::vector<Point> seeds;              // start nodes; inside the region, outside obstacles, or on
                                         // a node of `existing` (then the region may just touch it)
  std::vector<Polyline> existing;        // a network to extend: respected and joined, never emitted
  std::vector<Polyline> guide;           // direction control: θ follows the tangent of the nearest guide
                                         // point (undirected) instead of node matching; may be empty
  std::vector<Patch> patches;            // use_patches: the patch library (extract_patches)
  std::vector<Patch> patches_b;          // use_patches: a second style's library (PatchGrowParams::t); empty:
                                         // none. With patches, the guide warps the growth: each patch is turned
                                         // so the library's dominant direction follows the nearest tangent
  // Blending by a weight raster: band k is the weight of example k (>= 0), sampled bilinearly at
  // the node; where every band is nodata, or all weights are 0, blend (gradient or points) decides,
  // and without one every example is equally likely. Empty: no weight raster.
  GridField weights;
  // Direction control by a raster of angles in degrees clockwise from north (azimuths, as
  // ST_Azimuth), undirected (a and a + 180 are one direction), sampled by axial bilinear
  // interpolation; it sets θ like the guide does, and where it is nodata the guide (if any) and
  // then node matching decide. Empty: no direction raster.
  GridField direction;
  // Water: polygonal; no street but a bridge crosses it (arterials, params.bridge_distance). Seeds
  // must lie outside it. May be empty.
  std::vector<const GEOSGeometry*> water;
  // A DEM (one band of heights in the coordinates' unit, NaN unknown): streets keep under
  // params.max_slope where it is known. Empty: no DEM.
  GridField dem;
};

struct GrownEdge {
  std::int64_t id = 0;
  std::int64_t from_node = 0;
  std::int64_t to_node = 0;
  std::string road_class;
  std::int64_t example_id = 0;
  Point a, b;
  int example = 0;  // which example it was copied from (0-based); -1: grown parametrically
  bool bridge = false;  // an arterial across water (GrowInput::water)
};

// Why a drawn patch was not placed (place_patch), counted per draw in the arterial phase.
enum PatchRefusal : int {
  kRefNone, kRefRedundant, kRefCorner, kRefLevel, kRefIllegal, kRefClipped, kRefMaxEdges, kRefClearance,
  kRefDegree, kRefJunctionMix, kRefAngle, kRefCrossing, kRefSelfCrossing, kRefSeam, kPatchRefusals
};
// Their names at DEBUG1: every edge doubles a street; a corner left at a dead-end front; an arterial
// street in the local phase; an inner or dead-end edge outside the region, on an obstacle, over water
// or too steep; every connector clipped away; max_edges; clearance from the network; a junction over
// max_degree; a busier junction than the example's mix allows; an angle under min_angle; a crossing
// with the network; a crossing within the patch after merges; a merge turning a street (seam_turn).
inline constexpr const char* kPatchRefusalNames[kPatchRefusals] = {
    "none", "redundant", "corner", "level", "illegal edge", "clipped away", "max_edges", "clearance",
    "degree", "junction mix", "angle", "crossing", "self-crossing", "seam"};

struct GrowStats {
  std::size_t steps = 0;           // unfinished nodes processed
  std::size_t unmatched = 0;       // steps where no example node matched
  std::size_t fallback = 0;        // of those, steps grown parametrically instead
  std::size_t fallback_curved = 0; // patch growth: statistical streets bent by a drawn curvature
  std::size_t fallback_grid_turned = 0;  // fallback_grid: statistical streets turned onto the grid axis
  std::size_t fallback_askew_turned = 0;  // fallback_grid_askew: of those, more than 15 degrees off it
  std::size_t fallback_snaps_off_line = 0;  // fallback_grid: free-end snaps refused off the street's line
  std::size_t dangling_corners_cut = 0;  // dangling_corners: dead ends cut back instead of joined at a corner
  std::size_t short_ends_cut = 0;        // cut_short_ends: short dead ends cut back instead of joined
  std::size_t guided = 0;          // steps whose θ the guide or the direction raster set
  std::size_t directed = 0;        // of the steps, those where the direction raster had a value
  std::size_t weighted = 0;        // steps whose example the weight raster chose
  std::size_t coherent = 0;        // steps that copied the example node their edge was copied to
  std::size_t proposals = 0;
  std::size_t accepted = 0;
  std::size_t snapped = 0;         // proposals ending on an existing node or edge
  std::size_t clipped = 0;         // proposals shortened by the region or an obstacle
  std::size_t rejected = 0;
  std::size_t reseeds = 0;         // new seeds placed where the fronts had died before covering the region
  std::size_t restarts = 0;        // growths that died within their first 20 edges and began again
  double refill_target = 0.0;      // metres: PatchGrowParams::refill's street length for the region
  double refill_gap = 0.0;         // metres: a refill seed lies farther than this from every street
  double refill_before = 0.0;      // metres of grown streets when the queue first emptied
  std::size_t refill_islands = 0;  // refill fronts at a void's edge that grew nothing, seeded inside the void instead
  double cap_length = 0.0;         // metres: PatchGrowParams::length_cap's street length for the region (0: off)
  std::size_t cap_step = 0;        // the step at which the growth reached it (0: never)
  std::size_t cap_fronts_cut = 0;  // open connectors cut back when it was reached
  double cap_first_length = 0.0;   // metres: PatchGrowParams::regrow_past_cap: the first growth's length (0: not regrown)
  double cap_first_cap = 0.0;      // metres: and its cap
  bool cap_regrown_kept = false;   // the second growth was kept (cap_length is then its lowered cap)
  bool cap_resumed = false;        // the second growth resumed from the first's checkpoint (regrow_checkpoint)
  // PatchGrowParams::arterial_refill: the main-street length aimed at, the example's widest space
  // between its main streets, the grown main streets when the arterial phase first stopped and at
  // its end, the arterial seeds placed.
  double arterial_refill_target = 0.0, arterial_refill_gap = 0.0;
  double arterial_refill_before = 0.0, arterial_refill_after = 0.0;
  std::size_t arterial_reseeds = 0;
  // PatchGrowParams::promote_arterials: arterial streets ending into local streets inside the
  // region's 50 m margin, those continued to a main street or the margin, the local streets' metres
  // that took the arterial's class, the chains left for the main-street budget.
  std::size_t arterial_ends = 0, arterials_promoted = 0, arterials_over_budget = 0;
  double promoted_length = 0.0;
  // PatchGrowParams::demote_arterial_stubs: the stubs that took the local class, their metres.
  std::size_t arterial_stubs_demoted = 0;
  double demoted_length = 0.0;
  std::size_t pruned = 0;          // output segments cut back from fronts that could neither grow nor join
  std::size_t patches_placed = 0;  // patch growth: fronts (and seeds) where a patch was glued
  std::size_t patch_candidates = 0;  // patches within max_distance, summed over fronts
  std::size_t patch_illegal = 0;   // drawn patches that failed a legality check
  std::size_t terminal_refused = 0;  // PatchGrowParams::terminal_room: terminal patches' connectors within reach refused for the room ahead
  std::size_t front_crossings_refused = 0;  // PatchGrowParams::front_crossings: draws refused for a crossing at the front
  double example_crossing_share = 0.0;      // patch growth: the patch streets' crossings among their junctions
  double crossing_target = 0.0;  // continue_across: the share of crossings among junctions its joins aimed at
  double example_order = 0.0;    // straight_corners: the example's φ (network_stats' orientation order)
  // A city of crossings (align_stems, counted also with it off): fronts where a candidate patch
  // would go on across a T's lone street, and T's the placed patches were so drawn to go on across.
  std::size_t stem_fronts = 0;
  std::size_t stems_continued = 0;
  // PatchGrowParams::align_lines: fronts where a candidate patch had a connector end on the line of
  // a street across it, and such ends of the placed patches.
  std::size_t line_fronts = 0;
  std::size_t line_ends_placed = 0;
  std::size_t spread_fronts = 0;            // PatchGrowParams::spread_order: fronts drawn with the rule on
  std::size_t roundabouts_placed = 0;  // placements of patches tagged roundabout (some of a ring may have merged into the network)
  double roundabout_ahead = 0.0;  // PatchGrowParams::roundabout_shift: metres the first was placed ahead of its front
  std::size_t roundabout_spokes_dropped = 0;  // PatchGrowParams::roundabout_spokes_dropped: streets the placed first roundabout left out
  std::size_t front_dead_ends_refused = 0;  // PatchGrowParams::front_dead_ends: draws refused for their own dead ends
  std::size_t front_dead_ends_relaxed = 0;  // fronts whose draws were tried again without that rule
  std::size_t own_dead_ends_grown = 0;      // patch growth: the example's own dead ends copied, when the growth stopped
  std::size_t junctions_grown = 0;          // and the output's junctions then (before the joins and cut-backs)
  double example_dead_end_share = 0.0;      // patch growth: the patch library's own dead ends among its street ends
  std::size_t patch_edges = 0;     // output segments copied from patches
  std::size_t patches_dropped = 0; // library patches that cross themselves (never used)
  std::size_t patches_b_placed = 0;  // interpolation: of patches_placed, those from the second library
  std::size_t dangling_pruned = 0;   // prune_dangling: output segments cut back from dangling streets
  std::size_t dead_ends_kept = 0;    // prune_dangling: dead ends left (the example's, or blocked)
  std::size_t dangling_dense = 0;  // PatchGrowParams::dangling_junctions: joins refused (a junction over the example's)
  std::size_t dangling_small_blocks = 0;  // PatchGrowParams::dangling_block_floor: joins refused (a block under the floor)
  std::size_t dangling_connected = 0;  // connect_dangling: streets extended to a node or street ahead
  std::size_t continued_across = 0;    // continue_across: T-junctions joined to the T facing them
  std::size_t faced_after_cuts = 0;    // facing_after_cuts: those of them joined after the cuts
  std::size_t wide_facing_joins = 0;   // wide_facing: facing joins only its wider cone or reach found
  std::size_t facing_through_joins = 0;    // facing_through: facing joins across streets
  std::size_t facing_through_crossed = 0;  // and the streets they crossed (each split: a crossing more)
  std::size_t slid_onto_grid = 0;          // slide_onto_grid: nodes slid for a join along the grid
  std::size_t joins_off_grid = 0;          // grid_joins: dead ends' joins ahead refused off the grid
  std::size_t islands_joined = 0;          // join_islands: parts of the network joined to the rest
  std::size_t islands_joined_far = 0;      // of them, beyond a mean street (a part of a mean street or more)
  std::size_t islands_left = 0;            // and those left apart (none within reach, or no legal join)
  std::size_t islands_dropped = 0;         // and those removed (less street than a mean street)
  std::size_t settled_onto_grid = 0;       // settle_onto_grid (and weak_order_settle): nodes moved
  std::size_t short_segments_dropped = 0;  // segments under 0.5 m dropped at the end (drop_short_segments)
  std::size_t wide_redundant_dropped = 0;  // wide_redundant: patch streets left out that snap would have kept
  std::size_t local_tees_continued = 0;  // continue_local_tees: local T's gone on to the node or street ahead
  std::size_t local_tees_long = 0;       // continue_local_tees: joins refused for the example's street length per area
  std::size_t local_tees_dense = 0;      // continue_local_tees: joins refused for the example's junctions per area
  // Seams (DEBUG1): the patch streets glued, and those whose chord a merge turned, by turn (under
  // 2, 2-5, 5-10, 10-20, 20 degrees and more; count and metres); fronts where seam_turn refused a
  // draw, those of them where no other draw was legal and the draws were tried again without it,
  // dead ends slid (seam_slide).
  double patch_length = 0.0;
  std::size_t seam_count[5] = {};
  double seam_length[5] = {};
  std::size_t seam_refused = 0, seam_relaxed = 0, seam_slid = 0;
  std::size_t corners_avoided = 0;     // avoid_corners: fronts where a patch was refused for leaving a corner
  std::size_t corners_cut = 0;         // avoid_corners: of those, dead ends cut back after the joins
  std::size_t corners_straightened = 0;  // straight_corners: corners gone on straight, the other street dropped
  std::size_t corners_completed = 0;     // straight_corners: corners gone on to a T, the other street kept
  std::size_t corner_tees = 0;           // corner_tees: of those, the T's kept for the junctions (not a crossing's)
  std::size_t corners_in_turn = 0;       // corner_cascade: junctions a straightening left corners, straightened in turn
  std::size_t corners_over_density = 0;  // weak_order_corners: changes refused, a junction more than the example's per area
  std::size_t crop_ends_cut = 0;       // cut_crop_ends: copied crop dead ends cut back after the joins
  std::size_t arterial_patches_placed = 0;  // levels: patches placed in the arterial phase
  // Levels: each front of the arterial phase (a node with streets) once, by what became of it.
  std::size_t arterial_fronts = 0;
  std::size_t arterial_front_finished = 0;      // already finished (a patch's junction) when its turn came
  std::size_t arterial_front_no_direction = 0;  // no arterial connector within angle_window of its streets
  std::size_t arterial_front_used_up = 0;       // only connectors of patches at their usage limit
  std::size_t arterial_front_reach = 0;         // none whose reach is within max_distance of the street's
  std::size_t arterial_front_hausdorff = 0;     // none within max_distance by the Hausdorff distance
  std::size_t arterial_front_refused = 0;       // candidates, but every draw tried was illegal
  // Levels: the connectors of the patches placed in the arterial phase (but the one on the front),
  // by where they went: a new front, clipped (region, obstacle, water, slope), merged into a node,
  // dropped (doubling a street, or clipped to nothing); and their dead-end edges.
  std::size_t arterial_conn_front = 0, arterial_conn_clipped = 0, arterial_conn_merged = 0, arterial_conn_dropped = 0;
  std::size_t arterial_dead_ends = 0;
  std::size_t arterial_refusals[kPatchRefusals] = {};  // illegal draws of the arterial phase, by reason
  // Patch size (DEBUG1): at fronts, the drawn patches by size class (terciles of the library's mean
  // connector length, arterial and local patches apart): the class of the first draw (Nishida's eq. 2
  // if every patch were legal), draws tried, refused (by reason) and placed.
  std::size_t size_first[3] = {}, size_tried[3] = {}, size_placed[3] = {};
  std::size_t size_redraws = 0;  // size_redraw: fronts whose later draws were put in the first draw's size class first
  std::size_t size_refusals[3][kPatchRefusals] = {};
  double size_cut[2] = {0.0, 0.0};  // the local patches' terciles (m)
  std::size_t arterial_fallback = 0;          // levels: statistical steps at arterial fronts (PatchGrowParams::arterial_fallback)
  double arterial_fallback_budget = 0.0;      // metres of main street the arterial fallback grows up to
  std::size_t fallback_local_seeds = 0;       // levels: local seeds cut along the fallback's arterial streets
  std::size_t fallback_local_seeds_grown = 0; // of them, fronts where the local fallback grew (no patch was legal)
  std::size_t arterial_fallback_passes = 0;   // arterial_fallback_deferred: passes over the fronts left dead ends
  std::size_t arterial_fallback_fronts = 0;   // arterial_fallback_deferred: fronts left dead ends queued again
  std::size_t arterial_fallback_crop_ends = 0;  // of them, ends of arterial streets the example's crop cut
  // Teng & Bidarra: PatchGrowParams::bridge_fronts: fronts joined to another front by one patch,
  // the solutions tried (placements attempted), the library's junction pairs; cell_init initial: seed
  // points along the main streets, initial patches placed there, the spacing used (m).
  std::size_t fronts_bridged = 0, bridge_tries = 0, bridge_pairs = 0;
  std::size_t bridge_turns[3] = {};
  std::size_t bridge_crossing_ends = 0;  // of the bridges' two junctions each, those with 4 or more streets in their patch  // bridges placed by their turn from the library's frame: under 5, 5-20, 20+ degrees
  std::size_t initial_seed_points = 0, initial_placed = 0;
  std::size_t initial_turns[3] = {};  // initial patches placed by their turn from the library's frame (mod 180): under 5, 5-20, 20+
  double initial_spacing = 0.0;
  std::size_t local_seeds = 0;     // levels: fronts on arterial streets where the local phase began
  std::size_t local_seeds_used = 0;  // of those, where the example's own local patch was glued
  std::size_t ended_on_arterial = 0;  // levels: local streets whose new end was put on an arterial street
  std::size_t bridges = 0;         // bridge edges across water
  std::size_t bridges_failed = 0;  // bridge attempts that failed (no far bank within bridge_distance, too
                                   // close to another bridge, crossing, crowded, too steep)
  std::size_t bent = 0;            // statistical proposals bent towards the contour (DEM)
  std::size_t too_steep = 0;       // statistical proposals discarded: no bend under max_slope
  double radius = 0.0;             // the r and snap distance used
  double snap = 0.0;
  double dead_end_share = 0.0;     // the (first) example's dead ends among its street ends (not near the crop)
  double small_block = 0.0;        // the (first) example's small-block perimeter (m; 0: the rule is off)
  std::size_t example_contracted = 0;  // example segments under the minimum edge contracted (contract_short_segments)
  std::size_t small_cycles_refused = 0;  // joins refused for closing a cycle shorter than that
  double median_block = 0.0;        // the (first) example's median block perimeter (m; 0: the rule is off)
  std::size_t median_joins_refused = 0;  // failed fronts' joins (close_front) refused for closing a cycle under it
  // of close_front's nearest-node joins, those refused off the front's heading (while less ordered)
  std::size_t fronts_off_heading_refused = 0;
  std::size_t sibling_joins_refused = 0; // joins refused for closing a triangle with two sibling edges
  // The junction mix (DEBUG1, growth13): where dead ends and 4-way junctions are made or lost.
  std::size_t dead_end_proposals = 0;  // proposals copied from an example dead end
  std::size_t dead_end_made = 0;       // of those, made as a dead-end edge
  // of those, refused: angle or length, clipped to nothing, stopped short under min length, crowded
  std::size_t dead_end_lost[4] = {};
  // Joins onto a node by what made them (a free end's snap, a contact, a failed front's join) and
  // the node's degree before (0-3, 4+): degree 2 makes a T, 3 a 4-way.
  std::size_t node_joins[3][5] = {};
  std::size_t splits[3] = {};          // joins splitting an edge (a new T), by the same cause
  std::size_t mix_refused[5] = {};     // node joins refused by the example's junction mix, by degree
  std::size_t new_ts_refused = 0;      // new T's (joins onto degree 2, splits) refused: short of crossings, or dense
  std::size_t dense_ts_refused = 0;    // of those, refused as the output had the example's junctions per metre
  std::size_t fronts_failed = 0;       // fronts whose every draw failed
  std::size_t fronts_ahead_node = 0, fronts_ahead_split = 0, fronts_near_node = 0;  // closed by close_front
  std::size_t fronts_dead_end = 0, fronts_pruned = 0;  // left a dead end, or cut back
  // Of the fronts left dead ends, those cut back when the growth had finished, the output then no
  // longer short of the example's dead ends (trim_kept_fronts in grow_example.cpp).
  std::size_t fronts_trimmed = 0;
  // Fronts whose step kept only a turning street (a corner, turning by more than 45°): kept while the
  // output was as ordered as its example, taken back (then a street straight on made, or the front
  // tried again). straight_front in grow_example.cpp.
  std::size_t front_corners_kept = 0, front_corners_taken_back = 0, front_corners_straight = 0;
  // Steps that copied an example node of degree k (0-3, 4+) by v's degree after the step (0-3, 4+).
  std::size_t copy_result[5][5] = {};
  // Rejected proposals by reason: angle or length, clipped or steep, stopped in its first half, snap
  // to a node refused, snap to an edge refused, crowded free end, contact's node join refused, no new
  // T near a junction, contact too near, split refused.
  std::size_t reject_reason[10] = {};
  std::size_t dead_ends_joined[3] = {};  // joins onto a copied dead end's end, by cause (as node_joins)
};

struct GrowResult {
  std::vector<GrownEdge> edges;
  GrowStats stats;
};

// Throws invalid_argument for an example (unless params.parametric) without two distinct nodes, a region that is empty,
// invalid or not polygonal, obstacles that are not polygonal, no seed, a seed outside the region
// or inside an obstacle, and parameters out of range. Polls interrupts once per step.
// Several examples (ExampleEdge::example) need params.blend or a weight raster; a guide needs at
// least one segment. A weight raster needs one band per example and finite weights >= 0, a
// direction raster finite angles and one band; either must overlap the region's extent. So must
// a DEM (one band, finite heights or NaN); water must be polygonal and leave some of the region.
// Sets up the terrain and water checks of every step (legality of new streets, bending along the
// contour, bridges).
GrowResult grow_example(GeosContext& geos, const GrowInput& input, const GrowParams& params);

// The cuts after the joins (corner fronts, crop ends): whether cutting one more dead end brings the
// network nearer the example's dead-end share, from `dead` dead ends of `street_ends` to the counts
// after the cut: the count stops at the one nearest the share's target, not the first at or under it
// (strasbourg: a target of 5.6 dead ends keeps 6, not 5). Only while over the target; a tie keeps it.
bool cut_nears_dead_end_budget(long dead, long street_ends, long dead_after, long street_ends_after, double share);

// PatchGrowParams::front_dead_ends: whether a draw that brings dead ends of the example's own is
// refused, the output holding `own_dead_ends` such dead ends and `junctions` nodes of 3 or more
// streets: while their share, own_dead_ends / (own_dead_ends + junctions), is at `example_share` or
// above, by half a dead end (as the front crossings' test).
bool front_dead_end_refused(long own_dead_ends, long junctions, double example_share);

// The example as grow_example's node matching reads it: every segment (between consecutive
// vertices, two-way streets mapped twice counted once) between two junctions (nodes of degree 3
// or more as given) and shorter than `factor` x the mean segment is contracted, its two end nodes
// made one at their mean position with their other segments re-attached, until none is left (at
// most 8 rounds: a contracted node can bring two nodes closer). A crossing drawn in OSM as two
// T-junctions a few metres apart becomes one node of degree 4. Segments to shape points and dead
// ends are kept. Edges that collapse to a point are dropped. mean_length is the mean segment length
// of the example as given (the scale grow_example keeps); contracted counts the segments merged.
struct ContractedExample {
  std::vector<ExampleEdge> edges;
  double mean_length = 0.0;
  std::size_t contracted = 0;
};
ContractedExample contract_short_segments(const std::vector<ExampleEdge>& example, double factor);

}  // namespace streetgen::core
