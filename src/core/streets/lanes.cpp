#include "core/streets/lanes.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace streetgen::core {
namespace {

constexpr int kQuadrantSegments = 8;  // as the section buffers
constexpr double kStopLineSetback = 0.3;  // m inside the section: half a wide stop line

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

const std::string* tag(const LaneInput& in, const std::string& key) {
  auto it = in.tags.find(key);
  return it == in.tags.end() ? nullptr : &it->second;
}

// A lane count tag: a whole number 0..20; anything else is noted and ignored.
std::optional<int> count_tag(const LaneInput& in, const std::string& key, std::vector<LaneNote>& notes) {
  const std::string* v = tag(in, key);
  if (v == nullptr) return std::nullopt;
  std::string s = *v;
  s.erase(0, s.find_first_not_of(' '));
  s.erase(s.find_last_not_of(' ') + 1);
  bool digits = !s.empty() && s.size() <= 2 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits || std::stoi(s) > 20) {
    notes.push_back({"lane_tag_ignored", key + "=" + *v + " is not a lane count"});
    return std::nullopt;
  }
  return std::stoi(s);
}

bool known_turn(const std::string& lane) {
  static const std::set<std::string> known = {"",        "none",       "left",          "slight_left", "sharp_left",
                                              "through", "right",      "slight_right",  "sharp_right", "reverse",
                                              "merge_to_left", "merge_to_right", "slide_left", "slide_right"};
  std::stringstream s(lane);
  std::string token;
  while (std::getline(s, token, ';')) {
    if (known.count(token) == 0) return false;
  }
  return true;
}

std::vector<std::string> split_lanes(const std::string& v) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : v) {
    if (c == '|') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// Which side a cycleway/busway tag puts a lane on: 'lane' in the roadway, 'opposite_lane' a
// contraflow lane (on the left of a one-way). Values that put nothing in the roadway are known
// and silent; others are noted.
enum class Extra { none, lane, opposite_lane, unknown };
Extra extra_value(const std::string& v) {
  static const std::set<std::string> nothing = {
      "no",       "none",     "track",        "opposite_track", "separate", "shared_lane", "share_busway",
      "opposite_share_busway", "opposite", "shoulder", "crossing", "sidepath", "use_sidepath", "shared", "yes",
      "designated", "asl", "sidewalk"};
  if (v == "lane" || v == "exclusive" || v == "advisory") return Extra::lane;
  if (v == "opposite_lane") return Extra::opposite_lane;
  if (nothing.count(v) != 0) return Extra::none;
  return Extra::unknown;
}

struct SideExtras {
  bool left = false, right = false;
  bool opposite = false;  // contraflow on the left of a one-way
};

SideExtras side_extras(const LaneInput& in, const std::string& base, std::vector<LaneNote>& notes) {
  SideExtras out;
  auto read = [&](const std::string& key, bool left, bool right) {
    const std::string* v = tag(in, key);
    if (v == nullptr) return;
    switch (extra_value(*v)) {
      case Extra::lane:
        out.left = out.left || left;
        out.right = out.right || right;
        break;
      case Extra::opposite_lane:
        if (in.oneway) {
          out.opposite = true;
        } else {
          notes.push_back({"lane_tag_ignored", key + "=opposite_lane on a two-way road"});
        }
        break;
      case Extra::none:
        break;
      case Extra::unknown:
        notes.push_back({"lane_tag_ignored", key + "=" + *v + " is not a known value"});
        break;
    }
  };
  // `cycleway=lane` on a one-way: a lane on the right (the usual side); on a two-way, both.
  read(base, !in.oneway, true);
  read(base + ":both", true, true);
  read(base + ":left", true, false);
  read(base + ":right", false, true);
  return out;
}

// Street parking on one side of the roadway (OSM street parking scheme, `parking:<side>=lane`,
// and the older `parking:lane:<side>=parallel|diagonal|perpendicular`): the width it takes in
// the roadway, 0 when none. `half_on_kerb` puts half of it in the roadway; lay-bys
// (`street_side`) and kerbs take nothing, nor does separately mapped parking (`separate`) unless
// the importer measured the bays along that side (`parking:<side>:separate_width`, a streetgen
// key: they line at least half of it). Widths from
// `parking:<side>:width` when tagged, else by orientation (LaneRules). OSM draws a way along
// the middle of its traffic lanes (the `placement` default), so parking widens the roadway on
// its side only.
double parking_width(const LaneInput& in, const std::string& side, const LaneRules& rules, std::vector<LaneNote>& notes) {
  auto first = [&](std::initializer_list<std::string> keys) -> const std::string* {
    for (const std::string& k : keys) {
      if (const std::string* v = tag(in, k)) return v;
    }
    return nullptr;
  };
  auto by_orientation = [&](const std::string* o) {
    if (o != nullptr && *o == "perpendicular") return rules.parking_perpendicular_width;
    if (o != nullptr && *o == "diagonal") return rules.parking_diagonal_width;
    return rules.parking_parallel_width;
  };
  double share = 0.0;  // of the parking's width that lies in the roadway
  const std::string* orientation = nullptr;
  if (const std::string* v = first({"parking:" + side, "parking:both"})) {
    static const std::set<std::string> outside = {"no", "street_side", "on_kerb", "shoulder", "yes", "none"};
    if (*v == "lane") share = 1.0;
    else if (*v == "half_on_kerb") share = 0.5;
    else if (*v == "separate") {
      // Separately mapped bays along the curb: the importer measured their depth
      // (streetgen.load_osm_street_parking) and widened the roadway by it.
      if (const std::string* w = first({"parking:" + side + ":separate_width"})) {
        char* end = nullptr;
        double depth = std::strtod(w->c_str(), &end);
        if (end != w->c_str() && *end == '\0' && std::isfinite(depth) && depth >= 1.0 && depth <= 10.0) return depth;
        notes.push_back({"lane_tag_ignored", "parking:" + side + ":separate_width=" + *w + " is not a width in metres (1..10)"});
      }
      return 0.0;
    }
    else if (outside.count(*v) == 0) notes.push_back({"lane_tag_ignored", "parking:" + side + "=" + *v + " is not a known value"});
    orientation = first({"parking:" + side + ":orientation", "parking:both:orientation"});
  } else if (const std::string* o = first({"parking:lane:" + side, "parking:lane:both"})) {
    if (*o == "parallel" || *o == "diagonal" || *o == "perpendicular") {
      const std::string* pos = first({"parking:lane:" + side + ":" + *o, "parking:lane:both:" + *o});
      share = pos == nullptr || *pos == "on_street" ? 1.0 : *pos == "half_on_kerb" ? 0.5 : 0.0;
      orientation = o;
    }
  }
  if (share == 0.0) return 0.0;
  double width = by_orientation(orientation);
  if (const std::string* w = first({"parking:" + side + ":width", "parking:both:width"})) {
    char* end = nullptr;
    double v = std::strtod(w->c_str(), &end);
    if (end != w->c_str() && std::isfinite(v) && v >= 1.0 && v <= 10.0) width = v;
    else notes.push_back({"lane_tag_ignored", "parking:" + side + ":width=" + *w + " is not a width in metres (1..10)"});
  }
  return share * width;
}

// OSM `placement` (left_of:N, middle_of:N, right_of:N): where the way runs, as a distance from
// the roadway's left edge (looking along the way). Lanes are counted from the left as OSM's
// `lanes` counts them: driving and bus lanes, not cycle or parking lanes. `transition` and no tag:
// nullopt (the default placement); a value it cannot use is noted and ignored.
std::optional<double> placement_from_left(const LaneInput& in, const std::vector<LaneSpec>& lanes, std::vector<LaneNote>& notes) {
  const std::string* v = tag(in, "placement");
  if (v == nullptr || *v == "transition") return std::nullopt;
  auto ignored = [&](const std::string& why) {
    notes.push_back({"lane_tag_ignored", "placement=" + *v + ": " + why});
    return std::nullopt;
  };
  std::size_t colon = v->find(':');
  if (colon == std::string::npos) return ignored("not left_of:N, middle_of:N or right_of:N");
  std::string where = v->substr(0, colon);
  std::string number = v->substr(colon + 1);
  if ((where != "left_of" && where != "middle_of" && where != "right_of") || number.empty() || number.size() > 2 ||
      !std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return ignored("not left_of:N, middle_of:N or right_of:N");
  }
  int wanted = std::stoi(number);
  int counted = 0;
  double edge = 0.0;  // the left edge of the lane at hand
  for (const LaneSpec& l : lanes) {
    if (l.type == "driving" || l.type == "bus") {
      if (++counted == wanted) {
        if (where == "left_of") return edge;
        if (where == "middle_of") return edge + l.width / 2;
        return edge + l.width;
      }
    }
    edge += l.width;
  }
  return ignored("the road has " + std::to_string(counted) + " lanes");
}

}  // namespace

LanePlan plan_lanes(const LaneInput& in, double roadway_width, const LaneRules& rules) {
  LanePlan plan;
  std::vector<LaneNote>& notes = plan.notes;
  if (!(std::isfinite(roadway_width) && roadway_width > 0.0)) throw_invalid_argument("roadway width must be a finite number > 0");

  // 0. Street parking in the roadway, at its edges: dropped when not even one driving lane
  // would be left beside it. `width` is then what the traffic lanes share.
  double park_left = parking_width(in, "left", rules, notes);
  double park_right = parking_width(in, "right", rules, notes);
  if (park_left + park_right > 0.0 && roadway_width - park_left - park_right < rules.min_driving_width) {
    notes.push_back({"lanes_do_not_fit", "parking lanes dropped: " + fmt(park_left + park_right) + " m of parking leave less than " +
                                             fmt(rules.min_driving_width) + " m of the " + fmt(roadway_width) + " m roadway"});
    park_left = park_right = 0.0;
  }
  const double width = roadway_width - park_left - park_right;

  // 1. The motor-vehicle lane count: the axis' column, else the tags, else the width.
  std::optional<int> tagged_total = count_tag(in, "lanes", notes);
  std::optional<int> fwd = count_tag(in, "lanes:forward", notes);
  std::optional<int> bwd = count_tag(in, "lanes:backward", notes);
  std::optional<int> both = count_tag(in, "lanes:both_ways", notes);
  int n = 0;
  if (in.lanes && *in.lanes >= 1) {
    n = *in.lanes;
  } else if (tagged_total && *tagged_total >= 1) {
    n = *tagged_total;
  } else if (fwd || bwd) {
    n = fwd.value_or(0) + bwd.value_or(0) + both.value_or(0);
  }
  if (tagged_total && *tagged_total == 0) notes.push_back({"lane_tag_ignored", "lanes=0 is not a lane count"});
  if (n < 1) {
    n = std::max(1, static_cast<int>(std::floor(width / rules.estimate_lane_width)));
  }

  // 2. Per direction.
  int f = 0, b = 0, bw = 0;
  if (in.oneway) {
    f = n;
    if (bwd && *bwd > 0) notes.push_back({"lane_tags_contradict", "lanes:backward=" + std::to_string(*bwd) + " on a one-way road"});
  } else if (n == 1) {
    bw = 1;  // one lane for both directions
  } else {
    int middle = both && *both < n - 1 ? *both : 0;
    if (both && *both >= n - 1) notes.push_back({"lane_tags_contradict", "lanes:both_ways=" + std::to_string(*both) + " leaves no lane per direction"});
    int rest = n - middle;
    bool ok = false;
    if (fwd && bwd) {
      ok = *fwd >= 1 && *bwd >= 1 && *fwd + *bwd == rest;
      if (ok) { f = *fwd; b = *bwd; }
      // lanes=3, lanes:forward=1, lanes:backward=1 without lanes:both_ways: the lane left over
      // is a shared centre lane (a two-way turn lane), as OSM's lanes:both_ways would say.
      if (!ok && !both && *fwd >= 1 && *bwd >= 1 && *fwd + *bwd < rest) {
        ok = true;
        f = *fwd;
        b = *bwd;
        middle = rest - f - b;
      }
    } else if (fwd) {
      ok = *fwd >= 1 && *fwd < rest;
      if (ok) { f = *fwd; b = rest - f; }
    } else if (bwd) {
      ok = *bwd >= 1 && *bwd < rest;
      if (ok) { b = *bwd; f = rest - b; }
    } else {
      ok = true;
      b = rest / 2;
      f = rest - b;
    }
    if (!ok) {
      notes.push_back({"lane_tags_contradict", "lanes:forward=" + (fwd ? std::to_string(*fwd) : std::string("?")) +
                                                   ", lanes:backward=" + (bwd ? std::to_string(*bwd) : std::string("?")) +
                                                   " do not add up to " + std::to_string(rest) + " lanes: split evenly"});
      b = rest / 2;
      f = rest - b;
    }
    bw = middle;
  }

  // 3. Bus and cycle lanes. A bus lane is one of the direction's lanes (OSM counts it in
  // `lanes`) when the direction has two or more, else it is added.
  SideExtras bus = side_extras(in, "busway", notes);
  SideExtras cycle = side_extras(in, "cycleway", notes);

  // Motor lanes of each side, outermost first on the left, innermost first on the right.
  auto group = [](int count, const std::string& dir) { return std::vector<LaneSpec>(count, LaneSpec{"driving", dir, 0.0, {}}); };
  std::vector<LaneSpec> left = group(in.oneway ? 0 : b, "backward");
  std::vector<LaneSpec> middle = group(bw, "both");
  std::vector<LaneSpec> right = group(f, "forward");
  if (in.oneway) {  // every lane forward: the left bus lane is the leftmost of them
    if (bus.left) {
      if (right.size() >= 2) right.front().type = "bus";
      else right.insert(right.begin(), LaneSpec{"bus", "forward", 0.0, {}});
    }
    if (bus.opposite) left.insert(left.begin(), LaneSpec{"bus", "backward", 0.0, {}});
  } else if (bus.left) {
    if (left.size() >= 2) left.front().type = "bus";
    else left.insert(left.begin(), LaneSpec{"bus", "backward", 0.0, {}});
  }
  if (bus.right) {
    long driving = std::count_if(right.begin(), right.end(), [](const LaneSpec& l) { return l.type == "driving"; });
    if (driving >= 2) right.back().type = "bus";
    else right.push_back(LaneSpec{"bus", "forward", 0.0, {}});
  }

  // 4. Turn lanes, per direction in its direction of travel (left to right as the driver sees
  // them): forward lanes as the axis runs, backward ones from the centre outwards.
  auto assign_turns = [&](std::vector<LaneSpec>& lanes, bool reverse, const std::string& key) {
    const std::string* v = tag(in, key);
    if (v == nullptr) return;
    std::vector<std::string> tokens = split_lanes(*v);
    if (tokens.size() != lanes.size()) {
      notes.push_back({"lane_tag_ignored", key + " has " + std::to_string(tokens.size()) + " lanes, the direction " +
                                               std::to_string(lanes.size())});
      return;
    }
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      const std::string& t = tokens[reverse ? lanes.size() - 1 - i : i];
      if (!known_turn(t)) {
        notes.push_back({"lane_tag_ignored", key + " has an unknown turn '" + t + "'"});
        continue;
      }
      if (t != "none" && !t.empty()) lanes[i].turn = t;
    }
  };
  if (in.oneway) {
    assign_turns(right, false, tag(in, "turn:lanes") ? "turn:lanes" : "turn:lanes:forward");
  } else {
    assign_turns(right, false, "turn:lanes:forward");
    assign_turns(left, true, "turn:lanes:backward");
    assign_turns(middle, false, "turn:lanes:both_ways");
  }

  // 5. The cross-section, left to right; cycle lanes at the curbs.
  std::vector<LaneSpec>& lanes = plan.lanes;
  if (cycle.opposite) lanes.push_back({"cycle", "backward", 0.0, {}});
  if (cycle.left) lanes.push_back({"cycle", in.oneway ? "forward" : "backward", 0.0, {}});
  lanes.insert(lanes.end(), left.begin(), left.end());
  lanes.insert(lanes.end(), middle.begin(), middle.end());
  lanes.insert(lanes.end(), right.begin(), right.end());
  if (cycle.right) lanes.push_back({"cycle", "forward", 0.0, {}});

  // 6. Widths. Cycle and bus lanes take their nominal width, the driving lanes share the rest.
  // When a driving lane would be narrower than min_driving_width: cycle lanes go first, then bus
  // lanes share the width equally, then lanes go (the direction with more first, keeping one
  // each way while two fit; one lane for both directions otherwise).
  auto driving_share = [&]() {
    double special = 0.0;
    int driving = 0;
    for (const LaneSpec& l : lanes) {
      if (l.type == "cycle") special += rules.cycle_width;
      else if (l.type == "bus") special += rules.bus_width;
      else ++driving;
    }
    return driving == 0 ? width : (width - special) / driving;
  };
  bool equal_share = false;
  if (driving_share() < rules.min_driving_width) {
    std::size_t before = lanes.size();
    lanes.erase(std::remove_if(lanes.begin(), lanes.end(), [](const LaneSpec& l) { return l.type == "cycle"; }), lanes.end());
    if (lanes.size() != before) notes.push_back({"lanes_do_not_fit", "cycle lanes dropped: the roadway is " + fmt(width) + " m"});
  }
  if (driving_share() < rules.min_driving_width) equal_share = true;
  std::size_t fit = static_cast<std::size_t>(std::max(1.0, std::floor(width / rules.min_driving_width)));
  if (equal_share && lanes.size() > fit) {
    std::size_t had = lanes.size();
    auto count_dir = [&](const std::string& d) {
      return std::count_if(lanes.begin(), lanes.end(), [&](const LaneSpec& l) { return l.direction == d; });
    };
    while (lanes.size() > fit) {
      long nf = count_dir("forward"), nb = count_dir("backward"), nboth = count_dir("both");
      if (lanes.size() == 2 && nf == 1 && nb == 1) {  // the last two: one lane for both directions
        lanes = {LaneSpec{"driving", "both", 0.0, {}}};
        break;
      }
      // Which lane goes: a shared middle lane first, else one of the direction with more lanes
      // (backward on a tie, as the even split gives forward the odd lane): its bus lane, else its
      // outermost lane.
      std::string dir = nboth > 0 ? "both" : nf > nb ? "forward" : "backward";
      auto it = std::find_if(lanes.begin(), lanes.end(), [&](const LaneSpec& l) { return l.direction == dir && l.type == "bus"; });
      if (it == lanes.end()) {
        if (dir == "backward") {
          it = std::find_if(lanes.begin(), lanes.end(), [&](const LaneSpec& l) { return l.direction == dir; });
        } else {
          auto rit = std::find_if(lanes.rbegin(), lanes.rend(), [&](const LaneSpec& l) { return l.direction == dir; });
          it = rit == lanes.rend() ? lanes.end() : std::prev(rit.base());
        }
      }
      if (it == lanes.end()) it = std::prev(lanes.end());
      lanes.erase(it);
    }
    for (LaneSpec& l : lanes) l.turn.clear();  // the turn tags described other lanes
    notes.push_back({"lanes_do_not_fit", std::to_string(had) + " lanes need at least " +
                                             fmt(static_cast<double>(had) * rules.min_driving_width) + " m, the roadway is " +
                                             fmt(width) + " m: " + std::to_string(lanes.size()) + " lanes"});
  }
  if (equal_share) {
    for (LaneSpec& l : lanes) l.width = width / static_cast<double>(lanes.size());
  } else {
    double share = driving_share();
    for (LaneSpec& l : lanes) {
      l.width = l.type == "cycle" ? rules.cycle_width : l.type == "bus" ? rules.bus_width : share;
    }
  }
  // The widths add up to the roadway exactly (no drift from the divisions).
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < lanes.size(); ++i) sum += lanes[i].width;
  lanes.back().width = width - sum;

  // 7. Parking at the curbs; the traffic lanes stay centred on the axis unless `placement` says
  // where the way runs.
  if (park_left > 0.0) lanes.insert(lanes.begin(), LaneSpec{"parking", in.oneway ? "forward" : "backward", park_left, {}});
  if (park_right > 0.0) lanes.push_back(LaneSpec{"parking", "forward", park_right, {}});
  plan.centre_offset = (park_left - park_right) / 2;
  if (std::optional<double> from_left = placement_from_left(in, lanes, notes)) {
    plan.centre_offset = *from_left - roadway_width / 2;
  }
  return plan;
}

std::pair<double, double> street_parking_widths(const LaneInput& in, const LaneRules& rules) {
  std::vector<LaneNote> ignored;
  return {parking_width(in, "left", rules, ignored), parking_width(in, "right", rules, ignored)};
}

double signed_offset(const Polyline& line, Point p) {
  double best = std::numeric_limits<double>::infinity();
  Point foot{}, tangent{};
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    Point a = line[i], b = line[i + 1];
    Point ab = b - a;
    double len2 = dot(ab, ab);
    if (len2 <= 0.0) continue;
    double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
    Point q = a + t * ab;
    double d = distance(p, q);
    if (d < best) {
      best = d;
      foot = q;
      tangent = unit(ab);
      // At an inner vertex, the side is the bisector's (the segments' own tangents disagree
      // beyond right-angle bends).
      if (t == 1.0 && i + 2 < line.size()) tangent = unit(tangent + unit(line[i + 2] - b));
      if (t == 0.0 && i > 0) tangent = unit(tangent + unit(a - line[i - 1]));
    }
  }
  if (!std::isfinite(best)) return 0.0;
  return cross(tangent, p - foot) >= 0.0 ? best : -best;
}

namespace {

GeomPtr line_of(GeosContext& ctx, const Polyline& pts) {
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx.handle(), static_cast<unsigned>(pts.size()), 2);
  if (seq == nullptr) ctx.fail("coordinate sequence");
  for (std::size_t i = 0; i < pts.size(); ++i) GEOSCoordSeq_setXY_r(ctx.handle(), seq, static_cast<unsigned>(i), pts[i].x, pts[i].y);
  return own(ctx, GEOSGeom_createLineString_r(ctx.handle(), seq), "line construction");
}

bool is_empty(GeosContext& ctx, const GEOSGeometry* g) { return GEOSisEmpty_r(ctx.handle(), g) != 0; }

GeomPtr offset_curve(GeosContext& ctx, const GEOSGeometry* line, double offset) {
  // (a boundary on the centre line comes out of the width sums as +-1e-16 or so, and GEOS 3.11's
  // OffsetCurve fails on such distances)
  if (std::abs(offset) < 1e-9) return own(ctx, GEOSGeom_clone_r(ctx.handle(), line), "clone");
  return own(ctx, GEOSOffsetCurve_r(ctx.handle(), line, offset, kQuadrantSegments, GEOSBUF_JOIN_ROUND, 5.0), "offset curve");
}

// Only its lines: where the line touches the boundary the clip also gives points, which are no
// marking (and which the stored MultiLineString could not hold).
GeomPtr clipped(GeosContext& ctx, GeomPtr line, const GEOSGeometry* surface) {
  GeomPtr inside = own(ctx, GEOSIntersection_r(ctx.handle(), line.get(), surface), "marking clip");
  std::vector<GeomPtr> lines;
  std::vector<const GEOSGeometry*> stack{inside.get()};
  while (!stack.empty()) {
    const GEOSGeometry* g = stack.back();
    stack.pop_back();
    int type = GEOSGeomTypeId_r(ctx.handle(), g);
    if (type == GEOS_LINESTRING) {
      double len = 0.0;
      GEOSLength_r(ctx.handle(), g, &len);
      if (len > 1e-6) lines.push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), g), "clone"));
    } else if (type == GEOS_MULTILINESTRING || type == GEOS_GEOMETRYCOLLECTION) {
      int n = GEOSGetNumGeometries_r(ctx.handle(), g);
      for (int i = n - 1; i >= 0; --i) stack.push_back(GEOSGetGeometryN_r(ctx.handle(), g, i));
    }
  }
  if (lines.empty()) return nullptr;
  if (lines.size() == 1) return std::move(lines[0]);
  return make_collection(ctx, GEOS_MULTILINESTRING, lines);
}

}  // namespace

void section_lanes(GeosContext& ctx, std::int64_t axis_id, std::int64_t part, const Polyline& centre,
                   const GEOSGeometry* surface, bool clip, const LanePlan& plan, bool junction_at_start,
                   bool junction_at_end, std::vector<LaneResult>& lanes, std::vector<MarkingResult>& markings,
                   double stop_setback_start, double stop_setback_end) {
  const std::vector<LaneSpec>& specs = plan.lanes;
  if (specs.empty() || surface == nullptr || centre.size() < 2) return;
  double total = 0.0;
  for (const LaneSpec& s : specs) total += s.width;
  // Lane boundaries as offsets from the centre line (left positive): edges[k] is the left edge
  // of lane k, edges[k + 1] its right edge.
  const double shift = plan.centre_offset;
  std::vector<double> edges{shift + total / 2};
  for (const LaneSpec& s : specs) edges.push_back(edges.back() - s.width);
  edges.back() = shift - total / 2;

  // Lanes: the surface split along the offset curves of the inner boundaries. The centre line
  // is prolonged straight beyond the border lines so that every curve crosses the flat ends;
  // faces of the noded line work are assigned to a lane by their signed distance from the
  // centre line. The faces tile the surface, so the lanes do, without gaps or overlaps.
  std::vector<std::vector<GeomPtr>> faces_of(specs.size());
  if (specs.size() == 1) {
    faces_of[0].push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), surface), "clone"));
  } else {
    double reach = total + 1.0;
    Polyline prolonged = centre;
    prolonged.insert(prolonged.begin(), centre.front() - reach * unit(centre[1] - centre[0]));
    prolonged.push_back(centre.back() + reach * unit(centre.back() - centre[centre.size() - 2]));
    GeomPtr axis_line = line_of(ctx, prolonged);
    std::vector<GeomPtr> work;
    work.push_back(own(ctx, GEOSBoundary_r(ctx.handle(), surface), "boundary"));
    for (std::size_t k = 1; k < specs.size(); ++k) work.push_back(offset_curve(ctx, axis_line.get(), edges[k]));
    GeomPtr all = make_collection(ctx, GEOS_GEOMETRYCOLLECTION, work);
    GeomPtr noded = own(ctx, GEOSUnaryUnion_r(ctx.handle(), all.get()), "noding");
    const GEOSGeometry* noded_ptr = noded.get();
    GeomPtr faces = own(ctx, GEOSPolygonize_r(ctx.handle(), &noded_ptr, 1), "polygonize");
    const GEOSPreparedGeometry* prepared = GEOSPrepare_r(ctx.handle(), surface);
    if (prepared == nullptr) ctx.fail("prepare");
    struct PreparedDeleter {
      GEOSContextHandle_t h;
      const GEOSPreparedGeometry* p;
      ~PreparedDeleter() { GEOSPreparedGeom_destroy_r(h, p); }
    } prepared_guard{ctx.handle(), prepared};
    auto lane_of = [&](const GEOSGeometry* point) {
      double x = 0, y = 0;
      GEOSGeomGetX_r(ctx.handle(), point, &x);
      GEOSGeomGetY_r(ctx.handle(), point, &y);
      double s = signed_offset(prolonged, {x, y});
      std::size_t k = 0;
      while (k + 1 < specs.size() && s < edges[k + 1]) ++k;
      return k;
    };
    auto area = [&](const GEOSGeometry* g) {
      double a = 0.0;
      if (GEOSArea_r(ctx.handle(), g, &a) == 0) ctx.fail("area");
      return a;
    };
    double kept_area = 0.0;
    int n = GEOSGetNumGeometries_r(ctx.handle(), faces.get());
    for (int i = 0; i < n; ++i) {
      const GEOSGeometry* face = GEOSGetGeometryN_r(ctx.handle(), faces.get(), i);
      GeomPtr inside = own(ctx, GEOSPointOnSurface_r(ctx.handle(), face), "point on surface");
      if (is_empty(ctx, inside.get())) continue;
      char in = GEOSPreparedContains_r(ctx.handle(), prepared, inside.get());
      if (in == 2) ctx.fail("contains");
      if (in == 0) continue;  // a face outside (a hole, or beside a narrowed section)
      faces_of[lane_of(inside.get())].push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), face), "clone"));
      kept_area += area(face);
    }
    // Polygonize drops a face whose ring touches itself (a narrowed section whose hole touches
    // its shell): what the faces miss goes to the lanes by the same rule, so the lanes still
    // cover the section.
    double surface_area = area(surface);
    if (std::abs(surface_area - kept_area) > 1e-9 * std::max(1.0, surface_area)) {
      std::vector<GeomPtr> kept;
      for (std::vector<GeomPtr>& lane_faces : faces_of) {
        for (GeomPtr& f : lane_faces) kept.push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), f.get()), "clone"));
      }
      GeomPtr kept_all = make_collection(ctx, GEOS_GEOMETRYCOLLECTION, kept);
      GeomPtr kept_union = own(ctx, GEOSUnaryUnion_r(ctx.handle(), kept_all.get()), "union");
      GeomPtr missing = own(ctx, GEOSDifference_r(ctx.handle(), surface, kept_union.get()), "difference");
      int m = GEOSGetNumGeometries_r(ctx.handle(), missing.get());
      for (int i = 0; i < m; ++i) {
        const GEOSGeometry* piece = GEOSGetGeometryN_r(ctx.handle(), missing.get(), i);
        if (GEOSGeomTypeId_r(ctx.handle(), piece) != GEOS_POLYGON || area(piece) <= 0.0) continue;
        GeomPtr inside = own(ctx, GEOSPointOnSurface_r(ctx.handle(), piece), "point on surface");
        if (is_empty(ctx, inside.get())) continue;
        faces_of[lane_of(inside.get())].push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), piece), "clone"));
      }
    }
  }
  for (std::size_t k = 0; k < specs.size(); ++k) {
    if (faces_of[k].empty()) continue;  // a narrowed section lost this lane entirely
    LaneResult lane;
    lane.axis_id = axis_id;
    lane.part = part;
    lane.index = static_cast<int>(k) + 1;
    lane.spec = specs[k];
    if (faces_of[k].size() == 1) {
      lane.surface = std::move(faces_of[k][0]);
    } else {
      GeomPtr c = make_collection(ctx, GEOS_GEOMETRYCOLLECTION, faces_of[k]);
      lane.surface = own(ctx, GEOSUnaryUnion_r(ctx.handle(), c.get()), "lane union");
    }
    lanes.push_back(std::move(lane));
  }

  // Markings between lanes: a centre line between opposite motor-vehicle directions (dashed on
  // a road of one lane each way, solid otherwise), solid lines along bus and cycle lanes,
  // dashed ones between driving lanes of one direction.
  GeomPtr centre_geom = line_of(ctx, centre);
  int motor_forward = 0, motor_backward = 0;
  for (const LaneSpec& s : specs) {
    if (s.type == "cycle" || s.type == "parking") continue;
    if (s.direction == "forward") ++motor_forward;
    if (s.direction == "backward") ++motor_backward;
  }
  for (std::size_t k = 1; k < specs.size(); ++k) {
    const LaneSpec& l = specs[k - 1];
    const LaneSpec& r = specs[k];
    bool motor = l.type != "cycle" && r.type != "cycle" && l.type != "parking" && r.type != "parking";
    MarkingResult m;
    m.axis_id = axis_id;
    m.part = part;
    m.position = static_cast<int>(k);
    if (motor && l.direction != r.direction && l.direction != "both" && r.direction != "both") {
      m.kind = "centre_line";
      m.style = motor_forward == 1 && motor_backward == 1 ? "dashed" : "solid";
    } else {
      m.kind = "lane_separator";
      m.style = l.type == "driving" && r.type == "driving" ? "dashed" : "solid";
    }
    m.line = offset_curve(ctx, centre_geom.get(), edges[k]);
    // (inside an unsplit section by construction: every point is |offset| < half width from
    // the centre line, and the curve ends on the flat ends)
    if (clip) m.line = clipped(ctx, std::move(m.line), surface);
    if (m.line && !is_empty(ctx, m.line.get())) markings.push_back(std::move(m));
  }

  // Stop lines: across the lanes that drive into a junction, a little inside the section.
  double len = length(centre);
  for (int at_end = 0; at_end <= 1; ++at_end) {
    if (!(at_end ? junction_at_end : junction_at_start)) continue;
    const char* entering = at_end ? "forward" : "backward";
    double top = 0.0, bottom = 0.0;
    bool any = false;
    for (std::size_t k = 0; k < specs.size(); ++k) {
      if (specs[k].type == "parking" || (specs[k].direction != entering && specs[k].direction != "both")) continue;
      if (!any) top = edges[k];
      bottom = edges[k + 1];
      any = true;
    }
    if (!any) continue;
    double setback = at_end ? stop_setback_end : stop_setback_start;
    if (!(setback >= 0.0)) setback = kStopLineSetback;
    double s = at_end ? len - std::min(setback, len / 2) : std::min(setback, len / 2);
    Point p = point_at(centre, s);
    Point nrm = left_normal(tangent_at(centre, s));
    // A little beyond the roadway's edges, so that the clip, not rounding, decides where it ends.
    double extra_top = clip && top >= edges.front() - 1e-9 ? 0.5 : 0.0;
    double extra_bottom = clip && bottom <= edges.back() + 1e-9 ? 0.5 : 0.0;
    Polyline seg{p + (top + extra_top) * nrm, p + (bottom - extra_bottom) * nrm};
    MarkingResult m;
    m.axis_id = axis_id;
    m.part = part;
    m.kind = "stop_line";
    m.position = at_end;
    m.style = "solid";
    m.line = clip ? clipped(ctx, line_of(ctx, seg), surface) : line_of(ctx, seg);
    if (m.line) markings.push_back(std::move(m));
  }
}

}  // namespace streetgen::core
