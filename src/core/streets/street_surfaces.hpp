// StreetGen street surfaces from road axes (Cura et al. 2015, steps 2-7): a radius per corner
// from speed, arc centres on polylines, border points, section surfaces and intersection
// surfaces, with the paper's fallbacks, plus linear transitions where only the width changes.
#pragma once
#include "core/no_postgres.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ewkb.hpp"
#include "core/geos_context.hpp"
#include "core/streets/lanes.hpp"
#include "core/streets/polyline.hpp"
#include "core/streets/topology.hpp"

namespace streetgen::core {

struct SurfaceSettings {
  double snap_tolerance = 0.5;         // m: endpoints closer than this are one node
  double turn_speed_ratio = 0.35;      // turning speed at a corner / speed on the street
  double lateral_acceleration = 3.0;   // m/s^2, comfortable (about 0.3 g)
  double min_radius = 0.15;            // m: the paper's fallback (a Paris lane separator stone)
  double max_radius = 25.0;            // m
  double misplaced_factor = 3.0;       // an arc farther than this x (half width + r) from the node is misplaced
  double min_border_distance = 0.5;    // m: every junction reaches at least this far along its axes
  double transition_length_per_metre = 5.0;  // m of transition per metre of width change
  double min_transition_length = 5.0;        // m
  double max_transition_deflection_deg = 30.0;  // width transitions only where the axis runs on
  double crossing_width = 3.0;         // m: a pedestrian crossing along the axis (0: no crossings)
  double crossing_max_speed_kmh = 50.0;  // crossings only on streets this slow or slower
  // false: the street surfaces only (topology, corners, sections, junctions); no lanes,
  // markings, crossings or sidewalks, which take most of a city's time.
  bool details = true;
};

// Kinematic rule of thumb: a vehicle turns at turn_speed_ratio x the street speed with a lateral
// acceleration a, so r = (ratio * v)^2 / a, clamped to [min_radius, max_radius]. With the
// defaults: 30 km/h -> 2.8 m, 40 -> 5.0 m, 50 -> 7.9 m (the paper reads 3, 4.9, 7.6 m in Paris).
double radius_for_speed(const SurfaceSettings& settings, double speed_kmh);

struct SurfaceAxis {
  std::int64_t id = 0;
  Polyline line;
  double roadway_width = 0.0;
  double speed_kmh = 0.0;
  int layer = 0;
  std::optional<double> radius_override;
  LaneInput lane_input;  // lanes, one-way, lane tags: the cross-section of its sections
  double sidewalk_left = 0.0;   // m, looking along the axis; 0: none on that side
  double sidewalk_right = 0.0;
};

struct EdgeEnd {
  std::int64_t axis_id = 0;
  std::int64_t part = 0;  // the part's key: where it starts along the axis, mm
  bool at_end = false;    // false: the part's start
};
inline bool operator==(const EdgeEnd& a, const EdgeEnd& b) {
  return a.axis_id == b.axis_id && a.part == b.part && a.at_end == b.at_end;
}

struct CornerOverride {
  std::int64_t node_id = 0;
  EdgeEnd a;
  EdgeEnd b;
  double radius = 0.0;
};

struct NodeResult {
  std::int64_t id = 0;
  Point position;
  int layer = 0;
  int degree = 0;
  std::vector<std::int64_t> axis_ids;  // sorted, distinct: every axis with a point in the node
};

struct SectionResult {
  std::int64_t axis_id = 0;
  std::int64_t part = 0;   // where it starts along the axis, mm of abscissa
  std::int64_t from_node = 0;
  std::int64_t to_node = 0;
  Polyline centre_line;          // the whole part, node to node
  double start_border = 0.0;     // abscissas of the border lines on centre_line
  double end_border = 0.0;
  GeomPtr surface;               // null when the junctions take the whole part
  std::string status;            // ok, narrowed (shares an overlap with a nearby axis), absorbed, duplicate
};

struct CornerResult {
  std::int64_t node_id = 0;
  EdgeEnd a;  // the corner is swept counter-clockwise from a to b
  EdgeEnd b;
  double radius_wanted = 0.0;
  double radius = 0.0;         // used; 0 for a sharp corner
  // ok, radius_reduced (axis too short), min_radius (arc misplaced), sharp (no arc fits: curb
  // lines meet at a point), clamped (they meet beyond the junction's reach), no_corner (they
  // never meet), convex (outer side of a bend: no curb corner), transition (width change)
  std::string status;
  std::optional<Point> centre;
  std::array<Point, 3> arc{};  // start (on a's border), middle, end (on b's border): a circular arc
  Polyline arc_points;         // the arc segmentised (or the sharp corner point)
};

struct IntersectionResult {
  std::int64_t node_id = 0;
  GeomPtr surface;
  std::string status;  // ok, transition, repaired (a small defect made valid), fallback
};

// A sidewalk: the band beside a section's roadway (side left or right, between its border
// lines) or around a junction (side "around", following the curb arcs), minus every roadway on
// its layer and the sidewalks built before it (sections' before junctions', in key order), so
// that sidewalks never overlap a roadway or each other.
struct SidewalkResult {
  std::int64_t axis_id = 0;  // a section's (with part); 0 for a junction's
  std::int64_t part = 0;
  std::int64_t node_id = 0;  // a junction's; 0 for a section's
  std::string side;          // left, right, around
  double width = 0.0;        // m
  GeomPtr surface;           // polygon or multipolygon
  Bytes ewkb;                // instead of surface, when the run hands outputs over as EWKB (SurfaceOutput)
};

// A pedestrian crossing (zebra area) across a section's roadway at its border line with a
// junction: position 0 at the section's start, 1 at its end.
struct CrossingResult {
  std::int64_t axis_id = 0;
  std::int64_t part = 0;
  int position = 0;
  std::int64_t node_id = 0;  // the junction it leads across to
  double width = 0.0;        // m along the axis
  GeomPtr surface;
  Bytes ewkb;                // instead of surface, when the run hands outputs over as EWKB (SurfaceOutput)
};

// CPU seconds spent in each phase of one run, and a few counts (reported at DEBUG1 by the SQL
// entry and printed by bench/surfaces, for profiling).
struct SurfaceRunStats {
  double topology = 0;   // snapping, splitting, lane plans
  double corners = 0;    // corner arcs and border points per node
  double sections = 0;   // section surfaces and their separation
  double lanes = 0;      // lanes and markings
  double junctions = 0;  // intersection and transition surfaces and their separation
  double sidewalks = 0;  // sidewalks and crossings
  // How the sidewalks were made: junctions claimed corner by corner (a band along each curb)
  // or by a buffer of the whole junction (narrowed, repaired or transition junctions, corners
  // whose bands overlap); claims of any kind that met nothing and needed no overlay.
  long junction_sidewalks_by_corner = 0;
  long junction_sidewalks_by_buffer = 0;
  long junction_corners_by_buffer = 0;  // (of junctions claimed by corner: a corner without a band of its own)
  long sidewalks_without_overlay = 0;
  // Sidewalk claims (a street side's, or a junction corner's or buffer), and the most of them
  // whose geometry was held at once (build_sidewalks: the claims round the current one's turn).
  long sidewalk_claims = 0;
  long sidewalk_claims_held_peak = 0;
  double sidewalk_claim_builds = 0;  // CPU seconds of the claims' first build, for their boxes (of `sidewalks`)
  // Junctions with sections over their box, and how each was settled: every section only
  // touching it (exact test), touching but for rounding (an area bound under kGivenAway), or by
  // a GEOS overlay (union and difference).
  long junctions_touching = 0;
  long junctions_touching_but_for_rounding = 0;
  long junction_overlays = 0;
  // Pairs of sections of different axes (and of junctions) near enough to overlap: settled by
  // the exact tests (touching, or but for rounding) or by a GEOS intersection.
  long section_pairs_touching = 0;
  long section_pair_overlays = 0;
  long junction_pairs_touching = 0;
  long junction_pair_overlays = 0;
};

struct SurfaceResult {
  std::vector<NodeResult> nodes;
  std::vector<SectionResult> sections;
  std::vector<CornerResult> corners;
  std::vector<IntersectionResult> intersections;
  std::vector<TopologyIssue> issues;
  std::vector<LaneResult> lanes;        // of every section with a surface
  std::vector<MarkingResult> markings;
  std::vector<SidewalkResult> sidewalks;
  std::vector<CrossingResult> crossings;
  SurfaceRunStats stats;
};

// How the run hands over the outputs that no later phase reads (lanes, markings, crossings,
// sidewalks). By default as GEOS geometries (`surface`, `line`). With `ewkb_srid` set, as EWKB
// with that SRID (`ewkb`; the geometry is null), written as soon as each is built: a caller that
// only stores them holds them in less memory while the rest of a whole city is built (a point
// is 16 bytes in EWKB against 24 in GEOS, without GEOS' objects around it; Reisterstown's
// backend peak 110 -> 88 MB with the rest of that change).
struct SurfaceOutput {
  std::optional<int> ewkb_srid;
};

// Checks the inputs (finite, positive widths and speeds; throws invalid_argument naming the axis)
// and computes everything. Set-based: one call for a whole city.
SurfaceResult street_surfaces(GeosContext& ctx, const std::vector<SurfaceAxis>& axes,
                              const std::vector<CornerOverride>& corner_overrides, const SurfaceSettings& settings,
                              const SurfaceOutput& output = {});

// street_surfaces in two steps, for a caller that writes the lanes and markings out and frees
// them before the junctions, sidewalks and crossings are built: they are then not held beside
// the sidewalks' claims (the engine's memory peak). The constructor checks the inputs as
// street_surfaces does; through_lanes() runs topology, corners, sections, lanes and markings,
// after which lanes() and markings() are complete and the caller may take them; finish() runs
// the rest and returns the result, with whatever lanes and markings were left.
class SurfaceRun {
 public:
  SurfaceRun(GeosContext& ctx, std::vector<SurfaceAxis> axes, std::vector<CornerOverride> corner_overrides,
             const SurfaceSettings& settings, const SurfaceOutput& output = {});
  ~SurfaceRun();
  SurfaceRun(const SurfaceRun&) = delete;
  SurfaceRun& operator=(const SurfaceRun&) = delete;

  void through_lanes();
  std::vector<LaneResult>& lanes();
  std::vector<MarkingResult>& markings();
  SurfaceResult finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace streetgen::core
