// Lanes and markings of a section (issue 5, items 1-2): a cross-section planned from the axis'
// lane count, one-way flag and OSM lane tags, then laid on the section's surface by splitting it
// along offset curves of its centre line (offset curves, not translations: polylines bend), so
// that the lanes of a section tile its surface exactly, narrowed sections included.
#pragma once
#include "core/no_postgres.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/ewkb.hpp"
#include "core/geos_context.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

// What an axis says about its lanes. `tags` holds the OSM tags that matter here (lanes,
// lanes:*, turn:lanes*, cycleway*, busway*); others are ignored.
struct LaneInput {
  std::optional<int> lanes;  // motor-vehicle lanes in both directions (OSM `lanes`)
  bool oneway = false;       // one-way in the direction of the axis
  std::map<std::string, std::string> tags;
};

struct LaneSpec {
  std::string type;       // driving, bus, cycle, parking
  std::string direction;  // forward (along the axis), backward, both
  double width = 0.0;     // m
  std::string turn;       // from turn:lanes*, e.g. "left;through"; empty when unknown
};

struct LaneNote {
  std::string kind;  // lane_tag_ignored, lane_tags_contradict, lanes_do_not_fit
  std::string detail;
};

// The cross-section, left to right looking along the axis (right-hand traffic: forward lanes on
// the right). The widths add up to `roadway_width`. Never throws on bad tags: what it cannot use
// is ignored and noted.
struct LanePlan {
  std::vector<LaneSpec> lanes;
  std::vector<LaneNote> notes;
  // Where the roadway's centre lies, m to the left of the axis: the traffic lanes are centred on
  // the axis (where OSM draws a way), street parking widens the roadway on its side only.
  double centre_offset = 0.0;
};

struct LaneRules {
  double cycle_width = 1.5;        // m, a cycle lane in the roadway
  double bus_width = 3.0;          // m
  double min_driving_width = 2.0;  // m: narrower, the lane count does not fit the roadway
  double estimate_lane_width = 2.75;  // m: lane count from width when nothing says it (not noted)
  double parking_parallel_width = 2.0;       // m of roadway a parking lane takes, by orientation
  double parking_diagonal_width = 4.5;
  double parking_perpendicular_width = 5.0;
};

LanePlan plan_lanes(const LaneInput& input, double roadway_width, const LaneRules& rules = {});

// The roadway that street parking takes on each side, m (left, right), as plan_lanes reads the
// tags: what an estimated roadway width adds to its traffic lanes.
std::pair<double, double> street_parking_widths(const LaneInput& input, const LaneRules& rules = {});

struct LaneResult {
  std::int64_t axis_id = 0;
  std::int64_t part = 0;
  int index = 0;  // 1.. from the left edge of the roadway, looking along the axis
  LaneSpec spec;
  GeomPtr surface;  // polygon, or multipolygon where a narrowed section cuts a lane in two
  Bytes ewkb;       // instead of surface, when the run hands outputs over as EWKB (SurfaceOutput)
};

struct MarkingResult {
  std::int64_t axis_id = 0;
  std::int64_t part = 0;
  std::string kind;   // centre_line, lane_separator, stop_line
  int position = 0;   // lines: the lane boundary (between lanes position and position + 1); stop lines: 0 start, 1 end
  std::string style;  // solid, dashed
  GeomPtr line;       // linestring or multilinestring
  Bytes ewkb;         // instead of line, when the run hands outputs over as EWKB (SurfaceOutput)
};

// Lanes and markings of one section: `centre` is its centre line between the border lines,
// `surface` its polygon: the centre line buffered by half the width with flat ends, or, with
// `clip`, anything else (a narrowed section): markings are then clipped to it. Stop lines where
// the section meets a junction (`junction_at_start` / `_at_end`) across the lanes that drive
// into it, `stop_setback_start` / `_end` m inside the section (behind a pedestrian crossing
// where there is one; negative: the default 0.3 m).
void section_lanes(GeosContext& ctx, std::int64_t axis_id, std::int64_t part, const Polyline& centre,
                   const GEOSGeometry* surface, bool clip, const LanePlan& plan, bool junction_at_start,
                   bool junction_at_end, std::vector<LaneResult>& lanes, std::vector<MarkingResult>& markings,
                   double stop_setback_start = -1.0, double stop_setback_end = -1.0);

// Signed distance of p from the polyline: positive on its left.
double signed_offset(const Polyline& line, Point p);

}  // namespace streetgen::core
