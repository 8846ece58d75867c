// Teng & Bidarra (2017) in grow_patches: breadth-first bridging of two fronts by one patch
// (PatchGrowParams::bridge_fronts, their Algorithm 2) and cell initialisation with patches tagged
// initial on the main streets (PatchGrowParams::cell_init, their section 3.2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/error.hpp"
#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"
#include "patch_fixtures.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::avenue_grid;
using streetgen::test::wkt;

namespace {

constexpr double kPi = 3.14159265358979323846;

PatchEdge edge(Point a, Point b, PatchEdgeRole role) {
  PatchEdge e;
  e.line = {a, b};
  e.role = role;
  e.road_class = "street";
  return e;
}

// A patch of two junctions `d` metres apart on the x axis, joined by an inner street, each with a
// connector straight on outwards (west of the first, east of the second) and one to the north.
Patch two_junction_patch(double d) {
  Patch p;
  p.id = 7;
  p.edges.push_back(edge({0, 0}, {-100, 0}, PatchEdgeRole::connector));
  p.edges.push_back(edge({0, 0}, {0, 100}, PatchEdgeRole::connector));
  p.edges.push_back(edge({d, 0}, {d + 100, 0}, PatchEdgeRole::connector));
  p.edges.push_back(edge({d, 0}, {d, 100}, PatchEdgeRole::connector));
  p.edges.push_back(edge({0, 0}, {d, 0}, PatchEdgeRole::inner));
  return p;
}

// Two streets of an existing network ending face to face, `gap` metres apart along the direction
// `angle`, around the origin; their ends are the seeds (two fronts).
struct TwoFronts {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-1000 -1000, 1000 -1000, 1000 1000, -1000 1000, -1000 -1000))");
  Point v, w;
  GrowInput input(double gap, double angle, double patch_d) {
    const Point u{std::cos(angle), std::sin(angle)};
    v = -0.5 * gap * u;
    w = 0.5 * gap * u;
    GrowInput in;
    in.patches = {two_junction_patch(patch_d)};
    in.region = region.get();
    in.existing = {{v - 300.0 * u, v}, {w, w + 300.0 * u}};
    in.seeds = {v, w};
    return in;
  }
};

GrowParams bridge_params(bool on, double max_turn = 180.0) {
  GrowParams p;
  p.patch.max_turn = max_turn;
  p.use_patches = true;
  p.seed = 1;
  p.snap = 10.0;
  p.max_edges = 3;  // the bridging patch's three streets, then the growth stops
  p.patch.bridge_fronts = on;
  p.patch.prune_without_own_dead_ends = false;  // (the example has no dead end: its fronts would go)
  return p;
}

// Patch streets (not the fallback's) from the node at `a` to a node within `tol` of `b`.
int patch_edges_between(const GrowResult& r, Point a, Point b, double tol) {
  int n = 0;
  for (const GrownEdge& e : r.edges) {
    if (e.example < 0) continue;
    n += (distance(e.a, a) < 1e-6 && distance(e.b, b) <= tol) || (distance(e.b, a) < 1e-6 && distance(e.a, b) <= tol);
  }
  return n;
}

}  // namespace

// Two fronts 120 m apart on a line at 30 degrees, a library patch whose junctions are 126 m apart
// (within the 10 m snap): with max_turn 180 (Teng & Bidarra's free rotation) the patch is turned
// and placed with its junctions on both fronts, its inner street joining them, the connectors along
// their streets left out, one new street north of each (turned too).
TEST(TengBidarra, BridgeJoinsTwoFrontsWithAFittingPatch) {
  TwoFronts f;
  const double angle = kPi / 6.0;
  GrowInput in = f.input(120.0, angle, 126.0);
  GrowResult r = grow_example(f.geos, in, bridge_params(true));
  EXPECT_EQ(r.stats.fronts_bridged, 1u);
  EXPECT_EQ(r.stats.bridge_turns[2], 1u) << "turned by 30 degrees";
  EXPECT_EQ(r.stats.bridge_pairs, 1u);
  EXPECT_GE(r.stats.bridge_tries, 1u);
  ASSERT_EQ(r.edges.size(), 3u);
  EXPECT_EQ(patch_edges_between(r, f.v, f.w, 10.0), 1) << "one patch street from front to front";
  // The other two leave the fronts at about 90 degrees to the line between them (the patch turned by
  // 30 degrees; the far one's end merged 6 m back into its front, so that street turns by 3.4
  // degrees), none doubles the fronts' own streets.
  int turned = 0;
  for (const GrownEdge& e : r.edges) {
    const double a = std::atan2(e.b.y - e.a.y, e.b.x - e.a.x);
    const double off = std::abs(std::remainder(a - angle, kPi));
    if (std::abs(off - 0.5 * kPi) < 5.0 * kPi / 180.0) ++turned;
    EXPECT_TRUE(std::abs(off) < 1e-6 || std::abs(off - 0.5 * kPi) < 5.0 * kPi / 180.0) << "edge at " << a * 180.0 / kPi;
  }
  EXPECT_EQ(turned, 2);
  // Off (the default): no bridge; the front takes the depth-first draw.
  GrowResult off = grow_example(f.geos, in, bridge_params(false));
  EXPECT_EQ(off.stats.fronts_bridged, 0u);
  EXPECT_EQ(off.stats.bridge_pairs, 0u);
  // max_turn 5 (the default): the patch would be turned by 30 degrees from the library's frame.
  GrowResult stiff = grow_example(f.geos, in, bridge_params(true, 5.0));
  EXPECT_EQ(stiff.stats.fronts_bridged, 0u);
  EXPECT_EQ(patch_edges_between(stiff, f.v, f.w, 10.0), 0);
  // Fronts along the library's own axis: bridged within max_turn 5, no turn.
  TwoFronts g;
  GrowInput along = g.input(120.0, 0.0, 126.0);
  GrowResult straight = grow_example(g.geos, along, bridge_params(true, 5.0));
  EXPECT_EQ(straight.stats.fronts_bridged, 1u);
  EXPECT_EQ(straight.stats.bridge_turns[0], 1u);
  EXPECT_EQ(patch_edges_between(straight, g.v, g.w, 10.0), 1);
}

// The same fronts, but the library's junctions are 145 m apart: 25 m off, beyond the 10 m snap.
// Nothing fits: no bridge is placed, and no patch street joins the two fronts.
TEST(TengBidarra, BridgeRefusedWhenNoPairFitsTheDistance) {
  TwoFronts f;
  GrowInput in = f.input(120.0, kPi / 6.0, 145.0);
  GrowResult r = grow_example(f.geos, in, bridge_params(true));
  EXPECT_EQ(r.stats.bridge_pairs, 1u);
  EXPECT_EQ(r.stats.fronts_bridged, 0u);
  EXPECT_EQ(patch_edges_between(r, f.v, f.w, 10.0), 0);
  // A fitting pair in line of sight but blocked: a street across the gap between the fronts.
  GrowInput blocked = f.input(120.0, kPi / 6.0, 120.0);
  const Point n{-std::sin(kPi / 6.0), std::cos(kPi / 6.0)};
  blocked.existing.push_back({-200.0 * n, 200.0 * n});
  GrowResult b = grow_example(f.geos, blocked, bridge_params(true));
  EXPECT_EQ(b.stats.fronts_bridged, 0u);
  EXPECT_EQ(patch_edges_between(b, f.v, f.w, 10.0), 0);
}

// cell_init initial on the avenue grid, its library turned by 30 degrees (so the grown main streets
// run at 30 and 120 degrees): initial patches are placed on the main streets, each turned so its
// main street lies along the grown one: where a local street leaves a straight main street it does
// so at 90 degrees. The example's own local seeds are not used.
TEST(TengBidarra, CellInitPlacesInitialPatchesAlongTheMainStreets) {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-600 -600, 1200 -600, 1200 1200, -600 1200, -600 -600))");
  GrowInput in;
  in.patches = extract_patches(geos, avenue_grid(), PatchParams{}).patches;
  std::size_t initial = 0;
  for (const Patch& p : in.patches) initial += std::find(p.tags.begin(), p.tags.end(), "initial") != p.tags.end();
  ASSERT_GT(initial, 0u);
  in.region = region.get();
  in.seeds = {{300.0, 300.0}};
  GrowParams p;
  p.use_patches = true;
  p.seed = 2;
  p.max_edges = 3000;
  p.patch.rotation = 30.0;
  p.patch.cell_init = PatchGrowParams::CellInit::initial;
  GrowResult r = grow_example(geos, in, p);
  ASSERT_GT(r.edges.size(), 100u);
  EXPECT_GT(r.stats.initial_seed_points, 3u);
  EXPECT_GT(r.stats.initial_placed, 3u);
  EXPECT_LE(r.stats.initial_placed, r.stats.initial_seed_points);
  EXPECT_GT(r.stats.initial_spacing, 50.0);
  EXPECT_LT(r.stats.initial_spacing, 400.0);
  EXPECT_EQ(r.stats.local_seeds, 0u);
  // Nodes where a straight main street (two avenue segments within 5 degrees of straight on) meets
  // local streets: every such local street leaves at 90 degrees to it (within 5 degrees).
  std::map<std::int64_t, std::vector<std::pair<double, bool>>> leaving;  // node -> (angle, main)
  for (const GrownEdge& e : r.edges) {
    const bool main = e.road_class == "avenue";
    leaving[e.from_node].emplace_back(std::atan2(e.b.y - e.a.y, e.b.x - e.a.x), main);
    leaving[e.to_node].emplace_back(std::atan2(e.a.y - e.b.y, e.a.x - e.b.x), main);
  }
  int on_main = 0, square = 0;
  for (const auto& [node, out] : leaving) {
    std::vector<double> main, local;
    for (const auto& [a, m] : out) (m ? main : local).push_back(a);
    if (main.size() != 2 || local.empty()) continue;
    if (std::abs(std::remainder(main[0] - main[1], 2.0 * kPi)) < kPi - 5.0 * kPi / 180.0) continue;
    for (double a : local) {
      ++on_main;
      square += std::abs(std::abs(std::remainder(a - main[0], kPi)) - 0.5 * kPi) < 5.0 * kPi / 180.0;
    }
  }
  EXPECT_GE(on_main, static_cast<int>(r.stats.initial_placed));
  EXPECT_GE(square, static_cast<int>(0.95 * on_main));
  // The main streets run at 30 and 120 degrees (the turned library), so 90 degrees to them is not
  // the axes: an unturned patch would leave them at 60 or 30 degrees.
  int axis_aligned_main = 0, mains = 0;
  for (const GrownEdge& e : r.edges) {
    if (e.road_class != "avenue") continue;
    ++mains;
    const double a = std::atan2(e.b.y - e.a.y, e.b.x - e.a.x);
    axis_aligned_main += std::abs(std::remainder(a, 0.5 * kPi)) < 5.0 * kPi / 180.0;
  }
  ASSERT_GT(mains, 10);
  EXPECT_EQ(axis_aligned_main, 0);
  // Deterministic by seed; the default (seeds) uses the example's local seeds and no initial patch.
  GrowResult again = grow_example(geos, in, p);
  ASSERT_EQ(again.edges.size(), r.edges.size());
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    EXPECT_EQ(distance(again.edges[i].a, r.edges[i].a), 0.0);
    EXPECT_EQ(distance(again.edges[i].b, r.edges[i].b), 0.0);
  }
  p.patch.cell_init = PatchGrowParams::CellInit::seeds;
  GrowResult seeds = grow_example(geos, in, p);
  EXPECT_EQ(seeds.stats.initial_placed, 0u);
  EXPECT_EQ(seeds.stats.initial_seed_points, 0u);
  EXPECT_GT(seeds.stats.local_seeds, 0u);
}

// max_turn outside [0, 180] degrees and a cell_spacing that is not > 0 are rejected (22023 in SQL).
TEST(TengBidarra, BadParametersAreRejected) {
  TwoFronts f;
  GrowInput in = f.input(120.0, 0.0, 120.0);
  auto message = [&](const GrowParams& params) -> std::string {
    try {
      grow_example(f.geos, in, params);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
      return e.what();
    }
    return "accepted";
  };
  GrowParams p = bridge_params(true);
  EXPECT_EQ(message(p), "accepted");
  p.patch.max_turn = 181.0;
  EXPECT_NE(message(p).find("max_turn must be in [0, 180]"), std::string::npos);
  p.patch.max_turn = NAN;
  EXPECT_NE(message(p).find("max_turn must be in [0, 180]"), std::string::npos);
  p = bridge_params(true);
  p.patch.cell_spacing = 0.0;
  EXPECT_NE(message(p).find("cell_spacing must be a finite number > 0"), std::string::npos);
  p.patch.cell_spacing = INFINITY;
  EXPECT_NE(message(p).find("cell_spacing must be a finite number > 0"), std::string::npos);
}

namespace {

// A library of one crossing (four 100 m connectors) and four terminal patches, one per heading: a
// connector back along the front's street and two 40 m dead ends across it.
std::vector<Patch> crossing_and_terminals() {
  std::vector<Patch> library;
  Patch cross;
  cross.id = 1;
  for (Point to : {Point{100, 0}, Point{0, 100}, Point{-100, 0}, Point{0, -100}}) {
    cross.edges.push_back(edge({0, 0}, to, PatchEdgeRole::connector));
  }
  library.push_back(cross);
  for (int k = 0; k < 4; ++k) {
    const double a = 0.5 * kPi * k;
    const Point back{100.0 * std::cos(a + kPi), 100.0 * std::sin(a + kPi)};
    const Point side{40.0 * std::cos(a + 0.5 * kPi), 40.0 * std::sin(a + 0.5 * kPi)};
    Patch t;
    t.id = 10 + k;
    t.edges.push_back(edge({0, 0}, back, PatchEdgeRole::connector));
    t.edges.push_back(edge({0, 0}, side, PatchEdgeRole::dead_end));
    t.edges.push_back(edge({0, 0}, -1.0 * side, PatchEdgeRole::dead_end));
    library.push_back(t);
  }
  return library;
}

// The junctions of the terminal patches placed in a growth: the nodes where two of their dead ends
// meet.
std::vector<Point> terminal_junctions(const GrowResult& r) {
  std::map<std::pair<double, double>, int> arms;
  for (const GrownEdge& e : r.edges) {
    if (e.example_id < 10) continue;
    ++arms[{e.a.x, e.a.y}];
    ++arms[{e.b.x, e.b.y}];
  }
  std::vector<Point> out;
  for (const auto& [key, n] : arms) {
    if (n >= 2) out.push_back({key.first, key.second});
  }
  return out;
}

}  // namespace

// Teng & Bidarra's rule of use for terminal patches (one connector: they add no front): with
// terminal_room 2, a terminal patch ends a dead-end front only where a node, a street or the
// region's edge lies within two mean streets (200 m here) ahead of it. The seed's crossing leaves
// four fronts with nothing ahead (the next ring of the lattice does not exist yet when they are
// drawn): without the rule terminal patches end some of them, with it none. Further out, where the
// lattice fills in, they are drawn again. The streets go on where there is room, so the growth is
// longer.
TEST(TengBidarra, TerminalPatchesOnlyWhereLittleRoomIsLeft) {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-1000 -1000, 1000 -1000, 1000 1000, -1000 1000, -1000 -1000))");
  GrowInput in;
  in.patches = crossing_and_terminals();
  in.region = region.get();
  in.seeds = {{0.0, 0.0}};
  GrowParams p;
  p.use_patches = true;
  p.max_edges = 2000;
  p.fallback = false;  // patches alone: each front takes the crossing or a terminal patch
  // A front draws the crossing and the terminal patch alike: the rules that weigh the draws by the
  // example's own mix are off (the spread rule of a city of cul-de-sacs, which would take each of
  // the five patches once only; the dead-end rule, which refuses terminal patches while the growth
  // has the library's share of dead ends; a city of crossings' bonus for the crossing's streets
  // that go on across a T or along a line).
  p.patch.spread_order = false;
  p.patch.front_dead_ends = false;
  p.patch.align_stems = false;
  p.patch.align_lines = false;
  auto first_ring = [](const std::vector<Point>& junctions) {
    return std::count_if(junctions.begin(), junctions.end(), [](Point q) { return std::hypot(q.x, q.y) < 101.0; });
  };
  long open_off = 0, open_on = 0, longer = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    p.seed = seed;
    p.patch.terminal_room = 0.0;
    GrowResult off = grow_example(geos, in, p);
    p.patch.terminal_room = 2.0;
    GrowResult on = grow_example(geos, in, p);
    EXPECT_EQ(off.stats.terminal_refused, 0u);
    EXPECT_GT(on.stats.terminal_refused, 0u);
    EXPECT_GT(terminal_junctions(on).size(), 0u) << "seed " << seed << ": drawn where the lattice fills in";
    open_off += first_ring(terminal_junctions(off));
    open_on += first_ring(terminal_junctions(on));
    double length_off = 0.0, length_on = 0.0;
    for (const GrownEdge& e : off.edges) length_off += distance(e.a, e.b);
    for (const GrownEdge& e : on.edges) length_on += distance(e.a, e.b);
    longer += length_on > length_off;
    EXPECT_EQ(streetgen::test::crossings_without_node(on), 0);
    if (seed == 1) streetgen::test::expect_same_graph(grow_example(geos, in, p), on);  // deterministic
  }
  EXPECT_GT(open_off, 0) << "without the rule, terminal patches end streets with nothing ahead";
  EXPECT_EQ(open_on, 0) << "with it, only where little room is left";
  EXPECT_GE(longer, 5) << "of 6 seeds, the growth with the rule is longer";
  // A negative or not finite room is rejected (22023 in SQL).
  for (double bad : {-1.0, double(NAN)}) {
    p.patch.terminal_room = bad;
    try {
      grow_example(geos, in, p);
      ADD_FAILURE() << "terminal_room " << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
      EXPECT_NE(std::string(e.what()).find("terminal_room must be a finite number >= 0"), std::string::npos);
    }
  }
}
