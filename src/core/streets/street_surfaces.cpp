#include "core/streets/street_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <set>
#include <string_view>

#include "core/error.hpp"
#include "core/interrupts.hpp"
#include "core/reorder.hpp"
#include "core/streets/arc_centre.hpp"
#include "core/streets/bisector.hpp"
#include "core/streets/box_pairs.hpp"
#include "core/streets/polygon_contact.hpp"

namespace streetgen::core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kQuadrantSegments = 8;  // arc points per quarter circle, as PostGIS's ST_Buffer
constexpr double kSamePoint = 1e-6;   // m
constexpr double kStopBehindCrossing = 1.0;  // m between a crossing and the stop line behind it
constexpr double kGivenAway = 1e-6;          // m²: less overlap than this between roadways is left alone
constexpr double kSidewalkGrid = 1e-6;       // m: sidewalks are snapped to it (slivers collapse)
constexpr double kOnCutLine = 1e-8;         // m: a vertex this close to a line counts as on it
constexpr double kMinSidewalkArea = 0.01;    // m²: smaller pieces of a sidewalk are overlay slivers

double angle_of(Point v) { return std::atan2(v.y, v.x); }

// Counter-clockwise angle from direction u to direction v, in (0, 2 pi].
double ccw_angle(Point u, Point v) {
  double a = angle_of(v) - angle_of(u);
  while (a <= 0.0) a += 2 * kPi;
  while (a > 2 * kPi) a -= 2 * kPi;
  return a;
}

// One end of an edge at a node, seen from the node: `outgoing` starts at the node.
struct End {
  std::size_t edge = 0;
  bool at_end = false;
  Polyline outgoing;
  // The roadway's extent either side of `outgoing`: equal unless street parking on one side
  // widens it there (LanePlan::centre_offset).
  double left = 0.0;
  double right = 0.0;
  double radius = 0.0;    // wanted, from its axis
  double available = 0.0; // how far along it this node's junction may reach
  double angle = 0.0;
  double border = 0.0;    // abscissa of the border line on `outgoing`
};

// The offset direction at a vertex between segments `before` and `after` (unit vectors), scaled
// so that offsetting by h along it keeps distance h from both segments (a mitre), limited to 2.
Point mitre_normal(Point before, Point after) {
  Point n = unit(left_normal(before) + left_normal(after));
  if (norm(n) == 0.0) n = left_normal(after);
  double cos_half = dot(n, left_normal(after));
  return (cos_half > 0.5 ? 1.0 / cos_half : 2.0) * n;
}

// Points of the border at distance h on `side` (+1 left, -1 right) of `line`, between abscissas
// from_s and to_s (either order), with mitred vertices (limited to 2h). The ends take the
// tangent of the line itself, so an empty stretch still gives the border point.
Polyline border_path(const Polyline& line, double from_s, double to_s, double h, int side) {
  double lo = std::min(from_s, to_s);
  double hi = std::max(from_s, to_s);
  Polyline sub = substring(line, lo, hi);
  Polyline out;
  for (std::size_t i = 0; i < sub.size(); ++i) {
    Point n;
    if (i == 0) {
      n = left_normal(tangent_at(line, lo));
    } else if (i + 1 == sub.size()) {
      n = left_normal(tangent_at(line, std::max(0.0, hi - 1e-9)));
    } else {
      n = mitre_normal(unit(sub[i] - sub[i - 1]), unit(sub[i + 1] - sub[i]));
    }
    out.push_back(sub[i] + (side * h) * n);
  }
  if (from_s > to_s) std::reverse(out.begin(), out.end());
  return out;
}

Point border_point(const Polyline& line, double s, double h, int side) {
  return point_at(line, s) + (side * h) * left_normal(tangent_at(line, s));
}

// Arc from `from` to `to` around `centre` the short way, segmentised; both ends included.
Polyline arc_points(Point centre, Point from, Point to, double radius) {
  double a0 = angle_of(from - centre);
  double sweep = angle_of(to - centre) - a0;
  while (sweep > kPi) sweep -= 2 * kPi;
  while (sweep < -kPi) sweep += 2 * kPi;
  int n = std::max(2, static_cast<int>(std::ceil(std::abs(sweep) / (kPi / 2) * kQuadrantSegments)));
  Polyline out;
  out.push_back(from);
  for (int i = 1; i < n; ++i) {
    double a = a0 + sweep * i / n;
    out.push_back(centre + radius * Point{std::cos(a), std::sin(a)});
  }
  out.push_back(to);
  return out;
}

Point arc_middle(Point centre, Point from, Point to, double radius) {
  double a0 = angle_of(from - centre);
  double sweep = angle_of(to - centre) - a0;
  while (sweep > kPi) sweep -= 2 * kPi;
  while (sweep < -kPi) sweep += 2 * kPi;
  double a = a0 + sweep / 2;
  return centre + radius * Point{std::cos(a), std::sin(a)};
}

GeomPtr make_line(GeosContext& ctx, const Polyline& pts) {
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx.handle(), static_cast<unsigned>(pts.size()), 2);
  if (seq == nullptr) ctx.fail("coordinate sequence");
  for (std::size_t i = 0; i < pts.size(); ++i) GEOSCoordSeq_setXY_r(ctx.handle(), seq, static_cast<unsigned>(i), pts[i].x, pts[i].y);
  return own(ctx, GEOSGeom_createLineString_r(ctx.handle(), seq), "line construction");
}

GeomPtr make_polygon(GeosContext& ctx, Polyline ring) {
  if (ring.empty()) return nullptr;
  if (distance(ring.front(), ring.back()) > kSamePoint) {
    ring.push_back(ring.front());
  } else {
    ring.back() = ring.front();
  }
  if (ring.size() < 4) return nullptr;
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx.handle(), static_cast<unsigned>(ring.size()), 2);
  if (seq == nullptr) ctx.fail("coordinate sequence");
  for (std::size_t i = 0; i < ring.size(); ++i) GEOSCoordSeq_setXY_r(ctx.handle(), seq, static_cast<unsigned>(i), ring[i].x, ring[i].y);
  GEOSGeometry* shell = GEOSGeom_createLinearRing_r(ctx.handle(), seq);
  if (shell == nullptr) ctx.fail("ring construction");
  return own(ctx, GEOSGeom_createPolygon_r(ctx.handle(), shell, nullptr, 0), "polygon construction");
}

GeomPtr make_point(GeosContext& ctx, Point p) {
  return own(ctx, GEOSGeom_createPointFromXY_r(ctx.handle(), p.x, p.y), "point construction");
}

double area_of(GeosContext& ctx, const GEOSGeometry* g) {
  double a = 0.0;
  if (GEOSArea_r(ctx.handle(), g, &a) == 0) ctx.fail("area");
  return a;
}

// The polygon of `geom` (a polygon or a collection) that holds `node`, else the largest one.
GeomPtr pick_polygon(GeosContext& ctx, const GEOSGeometry* geom, Point node) {
  GeomPtr node_point = make_point(ctx, node);
  std::vector<const GEOSGeometry*> polygons;
  std::vector<const GEOSGeometry*> stack{geom};
  while (!stack.empty()) {
    const GEOSGeometry* g = stack.back();
    stack.pop_back();
    int type = GEOSGeomTypeId_r(ctx.handle(), g);
    if (type == GEOS_POLYGON) {
      if (GEOSisEmpty_r(ctx.handle(), g) == 0) polygons.push_back(g);
    } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
      int n = GEOSGetNumGeometries_r(ctx.handle(), g);
      for (int i = 0; i < n; ++i) stack.push_back(GEOSGetGeometryN_r(ctx.handle(), g, i));
    }
  }
  const GEOSGeometry* best = nullptr;
  double best_area = 0.0;
  for (const GEOSGeometry* p : polygons) {
    if (GEOSIntersects_r(ctx.handle(), p, node_point.get()) == 1) {
      best = p;
      break;
    }
    double a = area_of(ctx, p);
    if (a > best_area) {
      best = p;
      best_area = a;
    }
  }
  if (best == nullptr) return nullptr;
  return own(ctx, GEOSGeom_clone_r(ctx.handle(), best), "clone");
}


void envelope_box(GeosContext& ctx, const GEOSGeometry* g, Box& box) {
  if (GEOSGeom_getXMin_r(ctx.handle(), g, &box.xmin) == 0 || GEOSGeom_getYMin_r(ctx.handle(), g, &box.ymin) == 0 ||
      GEOSGeom_getXMax_r(ctx.handle(), g, &box.xmax) == 0 || GEOSGeom_getYMax_r(ctx.handle(), g, &box.ymax) == 0) {
    ctx.fail("envelope");
  }
}

// The polygons of `geom` of at least `min_area` m² (slivers of an overlay dropped), as one
// polygon or a multipolygon; null when none is left.
GeomPtr polygons_of(GeosContext& ctx, const GEOSGeometry* geom, double min_area) {
  std::vector<GeomPtr> kept;
  std::vector<const GEOSGeometry*> stack{geom};
  while (!stack.empty()) {
    const GEOSGeometry* g = stack.back();
    stack.pop_back();
    int type = GEOSGeomTypeId_r(ctx.handle(), g);
    if (type == GEOS_POLYGON) {
      if (GEOSisEmpty_r(ctx.handle(), g) == 0 && area_of(ctx, g) >= min_area) kept.push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), g), "clone"));
    } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
      int n = GEOSGetNumGeometries_r(ctx.handle(), g);
      for (int i = n - 1; i >= 0; --i) stack.push_back(GEOSGetGeometryN_r(ctx.handle(), g, i));
    }
  }
  if (kept.empty()) return nullptr;
  if (kept.size() == 1) return std::move(kept[0]);
  return make_collection(ctx, GEOS_MULTIPOLYGON, kept);
}

// One side of a line buffered: the region between the line and its offset at `distance` (left
// of the line when positive, right when negative), flat at the line's ends.
GeomPtr single_sided_buffer(GeosContext& ctx, const GEOSGeometry* line, double distance) {
  GEOSBufferParams* params = GEOSBufferParams_create_r(ctx.handle());
  if (params == nullptr) ctx.fail("buffer parameters");
  GEOSBufferParams_setSingleSided_r(ctx.handle(), params, 1);
  GEOSBufferParams_setJoinStyle_r(ctx.handle(), params, GEOSBUF_JOIN_ROUND);
  GEOSBufferParams_setQuadrantSegments_r(ctx.handle(), params, kQuadrantSegments);
  GEOSGeometry* g = GEOSBufferWithParams_r(ctx.handle(), line, params, distance);
  GEOSBufferParams_destroy_r(ctx.handle(), params);
  return own(ctx, g, "single-sided buffer");
}

void check_axis(const SurfaceAxis& axis) {
  auto bad = [&](const std::string& what) {
    throw_invalid_argument("axis " + std::to_string(axis.id) + ": " + what);
  };
  if (!(std::isfinite(axis.roadway_width) && axis.roadway_width > 0.0)) bad("roadway_width must be a finite number > 0");
  if (!(std::isfinite(axis.speed_kmh) && axis.speed_kmh > 0.0)) bad("speed_kmh must be a finite number > 0");
  if (axis.radius_override && !(std::isfinite(*axis.radius_override) && *axis.radius_override > 0.0)) {
    bad("radius_override must be a finite number > 0");
  }
  for (const Point& p : axis.line) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) bad("has a non-finite coordinate");
  }
  if (!(std::isfinite(axis.sidewalk_left) && axis.sidewalk_left >= 0.0 && axis.sidewalk_left <= 50.0) ||
      !(std::isfinite(axis.sidewalk_right) && axis.sidewalk_right >= 0.0 && axis.sidewalk_right <= 50.0)) {
    bad("sidewalk widths must be finite numbers from 0 to 50 m");
  }
}

// CPU seconds since the previous lap (or since construction): CPU rather than wall time, so
// that a profile on a busy machine still adds up.
class PhaseClock {
 public:
  double lap() {
    std::clock_t now = std::clock();
    double seconds = static_cast<double>(now - last_) / CLOCKS_PER_SEC;
    last_ = now;
    return seconds;
  }

 private:
  std::clock_t last_ = std::clock();
};

class SurfaceBuilder {
 public:
  SurfaceBuilder(GeosContext& ctx, const std::vector<SurfaceAxis>& axes, const std::vector<CornerOverride>& overrides,
                 const SurfaceSettings& settings, const SurfaceOutput& output)
      : ctx_(ctx), axes_(axes), overrides_(overrides), s_(settings), output_(output) {}

  SurfaceResult run() {
    through_lanes();
    return finish();
  }

  // Topology, corners, sections, lanes and markings (lanes() and markings() complete after it).
  void through_lanes() {
    PhaseClock& clock = clock_;
    std::vector<TopologyAxis> topo_axes;
    topo_axes.reserve(axes_.size());
    for (const SurfaceAxis& a : axes_) topo_axes.push_back({a.id, a.line, a.layer});
    topo_ = build_topology(topo_axes, s_.snap_tolerance);
    for (std::size_t i = 0; i < axes_.size(); ++i) {
      axis_layer_[axes_[i].id] = axes_[i].layer;
      axis_index_[axes_[i].id] = i;
    }
    result_.issues = topo_.issues;
    // The cross-section of every axis first: street parking shifts its roadway off the axis.
    plans_.reserve(axes_.size());
    for (const SurfaceAxis& a : axes_) plans_.push_back(plan_lanes(a.lane_input, a.roadway_width));

    ends_of_node_.assign(topo_.nodes.size(), {});
    for (std::size_t e = 0; e < topo_.edges.size(); ++e) {
      if (topo_.edges[e].duplicate) continue;
      ends_of_node_[topo_.edges[e].from_node].push_back(make_end(e, false));
      ends_of_node_[topo_.edges[e].to_node].push_back(make_end(e, true));
    }
    border_.assign(topo_.edges.size(), {0.0, 0.0});
    transition_.assign(topo_.nodes.size(), false);
    result_.stats.topology = clock.lap();

    // Corners and border lines first, then sections between the border lines, then the junction
    // surfaces (whose repairs may need the sections around them).
    InterruptPoller poller(64);
    corner_first_.assign(topo_.nodes.size() + 1, 0);
    for (std::size_t n = 0; n < topo_.nodes.size(); ++n) {
      poller.tick();
      corner_first_[n] = result_.corners.size();
      build_node(n);
    }
    corner_first_.back() = result_.corners.size();
    result_.stats.corners = clock.lap();
    for (std::size_t e = 0; e < topo_.edges.size(); ++e) {
      poller.tick();
      build_section(e);
    }
    separate_overlapping_sections();
    result_.stats.sections = clock.lap();
    if (s_.details) build_lanes(poller);
    // (grown by doubling, up to twice what they hold, and held to the end)
    result_.lanes.shrink_to_fit();
    result_.markings.shrink_to_fit();
    result_.stats.lanes = clock.lap();
  }

  std::vector<LaneResult>& lanes() { return result_.lanes; }
  std::vector<MarkingResult>& markings() { return result_.markings; }

  // Junctions, sidewalks and crossings; the whole result (no later phase reads the lanes and
  // markings: the caller may have taken them).
  SurfaceResult finish() {
    PhaseClock& clock = clock_;
    clock.lap();  // (not the caller's time between the steps)
    InterruptPoller poller(64);
    for (SectionResult& sec : result_.sections) {
      if (sec.surface) section_surface_[{sec.axis_id, sec.part}] = sec.surface.get();
    }
    for (std::size_t n = 0; n < topo_.nodes.size(); ++n) {
      poller.tick();
      if (ends_of_node_[n].size() < 2) continue;
      if (transition_[n]) {
        build_transition_surface(n);
      } else {
        build_intersection(n);
      }
    }
    decltype(section_surface_)().swap(section_surface_);  // (the junctions' repairs only)
    separate_overlapping_junctions(poller);
    result_.stats.junctions = clock.lap();
    if (s_.details) build_sidewalks(poller);
    result_.stats.sidewalks = clock.lap();
    return std::move(result_);
  }

 private:
  // A finished output that no later phase reads, handed over as EWKB when the caller asked for it.
  void hand_over(GeomPtr& geom, Bytes& ewkb) {
    if (!output_.ewkb_srid || !geom) return;
    ewkb = write_ewkb(ctx_, geom.get(), *output_.ewkb_srid);
    geom.reset();
  }

  double axis_radius(const SurfaceAxis& a) const {
    return a.radius_override ? *a.radius_override : radius_for_speed(s_, a.speed_kmh);
  }

  End make_end(std::size_t e, bool at_end) {
    const TopologyEdge& edge = topo_.edges[e];
    const SurfaceAxis& axis = axes_[edge.axis_index];
    End end;
    end.edge = e;
    end.at_end = at_end;
    end.outgoing = at_end ? reversed(edge.line) : edge.line;
    double shift = plans_[edge.axis_index].centre_offset;  // to the left of the axis
    end.left = axis.roadway_width / 2 + (at_end ? -shift : shift);
    end.right = axis.roadway_width - end.left;
    end.radius = axis_radius(axis);
    return end;
  }

  EdgeEnd key_of(const End& end) const {
    const TopologyEdge& edge = topo_.edges[end.edge];
    return {edge.axis_id, edge.part, end.at_end};
  }

  int degree_of(std::size_t node) const { return static_cast<int>(ends_of_node_[node].size()); }

  // Corner i of node n (all nodes built).
  const CornerResult& corner(std::size_t n, std::size_t i) const { return result_.corners[corner_first_[n] + i]; }

  std::optional<double> corner_override(std::int64_t node_id, const EdgeEnd& a, const EdgeEnd& b) const {
    for (const CornerOverride& o : overrides_) {
      if (o.node_id == node_id && o.a == a && o.b == b) return o.radius;
    }
    return std::nullopt;
  }

  struct Arc {
    Point centre;
    Point tangent_a, tangent_b;  // on the borders
    double foot_a, foot_b;       // abscissas of the tangent points' feet on the axes
  };

  // `fast`: the double-precision pass only (the radius search probes many radii).
  std::optional<Arc> arc_for(const End& a, const End& b, double radius, bool fast = false) const {
    Polyline oa = substring(a.outgoing, 0.0, a.available);
    Polyline ob = substring(b.outgoing, 0.0, b.available);
    // The arc lies in the sector swept counter-clockwise from a to b: left of a, right of b.
    std::optional<Point> c = fast ? arc_centre_fast(oa, a.left + radius, ob, b.right + radius)
                                  : arc_centre(oa, a.left + radius, ob, b.right + radius);
    if (!c) return std::nullopt;
    Projection pa = project(oa, *c);
    Projection pb = project(ob, *c);
    Arc arc;
    arc.centre = *c;
    arc.foot_a = pa.abscissa;
    arc.foot_b = pb.abscissa;
    arc.tangent_a = *c + (radius / std::max(pa.distance, 1e-12)) * (pa.point - *c);
    arc.tangent_b = *c + (radius / std::max(pb.distance, 1e-12)) * (pb.point - *c);
    return arc;
  }

  // The corner swept counter-clockwise from end a to end b at node n, with the paper's fallbacks.
  CornerResult build_corner(std::size_t n, End& a, End& b) {
    const TopologyNode& node = topo_.nodes[n];
    CornerResult c;
    c.node_id = node.id;
    c.a = key_of(a);
    c.b = key_of(b);
    std::optional<double> forced = corner_override(node.id, c.a, c.b);
    double wanted = forced ? *forced : std::min(a.radius, b.radius);
    c.radius_wanted = wanted;
    double radius = std::clamp(wanted, s_.min_radius, std::max(s_.min_radius, s_.max_radius));
    if (forced) radius = std::max(*forced, 1e-3);

    double sector = ccw_angle(tangent_at(a.outgoing, 0.0), tangent_at(b.outgoing, 0.0));
    if (sector >= kPi - 1e-9) {
      c.status = "convex";  // the outer side of a bend: the borders meet around the node, no curb arc
      return c;
    }

    std::optional<Arc> arc = arc_for(a, b, radius);
    std::string status = "ok";
    if (!arc) {
      // Too short an axis for this radius: the largest radius that fits (bisection; the
      // tangent points move away from the node as the radius grows).
      double lo = s_.min_radius;
      std::optional<Arc> at_lo = arc_for(a, b, lo);
      if (at_lo && radius > lo) {
        double hi = radius;
        for (int i = 0; i < 24 && hi - lo > 1e-3; ++i) {
          double mid = 0.5 * (lo + hi);
          std::optional<Arc> m = arc_for(a, b, mid, true);
          if (m) {
            lo = mid;
            at_lo = m;
          } else {
            hi = mid;
          }
        }
        arc = at_lo;
        radius = lo;
        status = "radius_reduced";
      }
    }
    if (arc) {
      double reach = distance(arc->centre, node.position) - radius;
      double limit = s_.misplaced_factor * (std::max(a.left, b.right) + radius);
      if (reach > limit && radius > s_.min_radius) {
        std::optional<Arc> small = arc_for(a, b, s_.min_radius);
        if (small) {
          arc = small;
          radius = s_.min_radius;
          status = "min_radius";
        }
      }
    }
    // A sharp corner (radius 0): the curb lines meet in `point`.
    auto sharp_corner = [&](Point point, double foot_a, double foot_b) {
      c.radius = 0.0;
      c.status = "sharp";
      c.arc = {point, point, point};
      c.arc_points = {point};
      a.border = std::max(a.border, foot_a);
      b.border = std::max(b.border, foot_b);
      return c;
    };
    // An arc whose two tangent points coincide (an axis meeting itself where both its ends leave
    // the node the same way) has no length: its curb lines touch in a point.
    if (arc && distance(arc->tangent_a, arc->tangent_b) <= 1e-9) return sharp_corner(arc->tangent_a, arc->foot_a, arc->foot_b);
    if (arc) {
      c.radius = radius;
      c.status = status;
      c.centre = arc->centre;
      c.arc = {arc->tangent_a, arc_middle(arc->centre, arc->tangent_a, arc->tangent_b, radius), arc->tangent_b};
      c.arc_points = arc_points(arc->centre, arc->tangent_a, arc->tangent_b, radius);
      a.border = std::max(a.border, arc->foot_a);
      b.border = std::max(b.border, arc->foot_b);
      return c;
    }
    // No arc fits: the curb lines meet in a sharp corner (radius 0), if they meet at all.
    std::optional<Arc> sharp = arc_for(a, b, 0.0);
    if (sharp) return sharp_corner(sharp->centre, sharp->foot_a, sharp->foot_b);
    // The curb lines meet beyond the reach of this junction along an axis (very short axes,
    // narrow angles): where the straight continuations of the first segments' borders meet;
    // the junction takes the axes that far, or as far as it may ('clamped'). Two axes that
    // never part (meeting at 0 degrees) are taken as far as the junction may ('no_corner').
    Point ta = tangent_at(a.outgoing, 0.0);
    Point tb = tangent_at(b.outgoing, 0.0);
    double det = cross(ta, tb);
    if (std::abs(det) > 1e-9) {
      Point offset = (-b.right) * left_normal(tb) - a.left * left_normal(ta);
      double along_a = cross(offset, tb) / det;
      double along_b = cross(offset, ta) / det;
      if (along_a >= 0.0 && along_b >= 0.0) {
        c.status = "clamped";
        a.border = std::max(a.border, std::min(along_a, a.available));
        b.border = std::max(b.border, std::min(along_b, b.available));
        return c;
      }
    }
    c.status = "no_corner";
    if (sector < kPi / 2) {
      a.border = a.available;
      b.border = b.available;
    }
    return c;
  }

  bool is_width_transition(const std::vector<End>& ends) const {
    if (ends.size() != 2) return false;
    // (end 0's left side runs on as end 1's right side, and the other way round)
    if (std::abs(ends[0].left - ends[1].right) < 0.005 && std::abs(ends[0].right - ends[1].left) < 0.005) return false;
    double deflection = kPi - std::min(ccw_angle(tangent_at(ends[0].outgoing, 0.0), tangent_at(ends[1].outgoing, 0.0)),
                                       ccw_angle(tangent_at(ends[1].outgoing, 0.0), tangent_at(ends[0].outgoing, 0.0)));
    return deflection <= s_.max_transition_deflection_deg * kPi / 180.0;
  }

  void build_node(std::size_t n) {
    const TopologyNode& node = topo_.nodes[n];
    std::vector<End>& ends = ends_of_node_[n];
    NodeResult nr;
    nr.id = node.id;
    nr.position = node.position;
    nr.layer = node.layer;
    nr.degree = static_cast<int>(ends.size());
    nr.axis_ids = node.axis_ids;
    result_.nodes.push_back(nr);
    if (ends.empty()) return;

    for (End& e : ends) {
      const TopologyEdge& edge = topo_.edges[e.edge];
      double len = length(edge.line);
      std::size_t other = e.at_end ? edge.from_node : edge.to_node;
      bool other_is_dead_end = other != n && degree_of(other) == 1;
      e.available = other_is_dead_end ? len : len / 2;
      double probe = std::min(e.available, std::max({2.0, e.left, e.right}));
      e.angle = angle_of(point_at(e.outgoing, probe) - node.position);
      e.border = ends.size() >= 2 ? std::min(s_.min_border_distance, e.available) : 0.0;
    }
    std::sort(ends.begin(), ends.end(), [&](const End& x, const End& y) {
      if (x.angle != y.angle) return x.angle < y.angle;
      return std::make_tuple(topo_.edges[x.edge].axis_id, topo_.edges[x.edge].part, x.at_end) <
             std::make_tuple(topo_.edges[y.edge].axis_id, topo_.edges[y.edge].part, y.at_end);
    });
    if (ends.size() == 1) {  // a dead end: the section runs to the end of the axis
      record_border(ends[0]);
      return;
    }

    if (is_width_transition(ends)) {
      transition_[n] = true;
      build_transition_borders(n, ends);
      return;
    }

    for (std::size_t i = 0; i < ends.size(); ++i) {
      result_.corners.push_back(build_corner(n, ends[i], ends[(i + 1) % ends.size()]));
    }
    for (End& e : ends) {
      e.border = std::min(e.border, e.available);
      record_border(e);
    }
  }

  void record_border(const End& e) {
    auto& b = border_[e.edge];
    (e.at_end ? b.second : b.first) = e.border;
  }

  // Degree-2 node where only the width changes: a linear transition over a length that grows
  // with the change (the paper's variable buffer), instead of curb arcs.
  void build_transition_borders(std::size_t n, std::vector<End>& ends) {
    const TopologyNode& node = topo_.nodes[n];
    double change = std::abs(ends[0].left - ends[1].right) + std::abs(ends[0].right - ends[1].left);
    double half_length = 0.5 * std::max(s_.min_transition_length, s_.transition_length_per_metre * change);
    for (End& e : ends) {
      e.border = std::min(half_length, e.available);
      record_border(e);
    }
    for (std::size_t i = 0; i < 2; ++i) {
      CornerResult c;
      c.node_id = node.id;
      c.a = key_of(ends[i]);
      c.b = key_of(ends[1 - i]);
      c.radius_wanted = std::min(ends[0].radius, ends[1].radius);
      c.status = "transition";
      result_.corners.push_back(std::move(c));
    }
  }

  void build_transition_surface(std::size_t n) {
    const std::vector<End>& ends = ends_of_node_[n];
    // The path from end 0's border line through the node to end 1's border line, with the half
    // width varying linearly along it.
    Polyline path = reversed(substring(ends[0].outgoing, 0.0, ends[0].border));
    Polyline second = substring(ends[1].outgoing, 0.0, ends[1].border);
    path.insert(path.end(), second.begin() + 1, second.end());
    path = without_repeated_points(path, 1e-9);
    double total = length(path);
    Polyline left, right;
    double walked = 0.0;
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (i > 0) walked += distance(path[i - 1], path[i]);
      double t = total > 0.0 ? walked / total : 0.0;
      // The path runs the way end 1 leaves the node: its left is end 0's right.
      double h_left = ends[0].right + t * (ends[1].left - ends[0].right);
      double h_right = ends[0].left + t * (ends[1].right - ends[0].left);
      Point before = i > 0 ? unit(path[i] - path[i - 1]) : unit(path[1] - path[0]);
      Point after = i + 1 < path.size() ? unit(path[i + 1] - path[i]) : before;
      Point n = mitre_normal(before, after);
      left.push_back(path[i] + h_left * n);
      right.push_back(path[i] - h_right * n);
    }
    Polyline ring = left;
    ring.insert(ring.end(), right.rbegin(), right.rend());
    finish_intersection(n, make_polygon(ctx_, ring), "transition");
  }

  // The ring around the node: each end's border line, then the curb of each corner (along the
  // border back to the arc, the arc, out along the next border), as the paper's surface model.
  void build_intersection(std::size_t n) {
    const std::vector<End>& ends = ends_of_node_[n];
    Polyline ring;
    for (std::size_t i = 0; i < ends.size(); ++i) {
      const End& a = ends[i];
      append_points(ring, {border_point(a.outgoing, a.border, a.right, -1)});
      append_points(ring, curb(n, i, 0.0));
    }
    finish_intersection(n, make_polygon(ctx_, ring), "ok");
  }

  // Appends `pts` to `line`, dropping points closer than a micrometre to the last one: GEOS sees
  // a hair-thin back-and-forth as a self-intersection.
  static void append_points(Polyline& line, const Polyline& pts) {
    for (const Point& p : pts) {
      if (line.empty() || distance(line.back(), p) > kSamePoint) line.push_back(p);
    }
  }

  // The curb of corner i of node n, from end i's left border point to end i + 1's right border
  // point, moved `out` metres away from the roadway (0: the curb itself, the junction's ring
  // between two border lines; w: the outer edge of a sidewalk w wide; not for the outside of a
  // bend, a convex corner, whose outline callers buffer). Outward, an arc of radius
  // r becomes the arc of radius r - out around the same centre, or, once out >= r, the corner
  // where the two moved borders cross (as a buffer's outline has it: a sharp corner), or, when
  // that lies beyond a border line, the single point where the two border lines cross. Empty
  // when none of these exists (a corner without a curb, or border lines crossing too far out).
  Polyline curb(std::size_t n, std::size_t i, double out) {
    const std::vector<End>& ends = ends_of_node_[n];
    const End& a = ends[i];
    const End& b = ends[(i + 1) % ends.size()];
    const CornerResult& c = corner(n, i);
    Polyline line{border_point(a.outgoing, a.border, a.left + out, +1)};
    if (c.status == "convex") {
      // Around the outside of the node: a's left border in, round the node, b's right border out.
      // (Outward, callers buffer this curb instead: its joins are round.)
      if (out > 0.0) return {};
      Point node = topo_.nodes[n].position;
      append_points(line, border_path(a.outgoing, a.border, 0.0, a.left, +1));
      Point from = border_point(a.outgoing, 0.0, a.left, +1);
      Point to = border_point(b.outgoing, 0.0, b.right, -1);
      double h = 0.5 * (a.left + b.right);
      double a0 = angle_of(from - node);
      double sweep = ccw_angle(from - node, to - node);
      if (sweep > 2 * kPi - 1e-9) sweep = 0.0;  // straight on: the borders continue each other
      int steps = static_cast<int>(std::ceil(sweep / (kPi / 2) * kQuadrantSegments));
      for (int k = 1; k < steps; ++k) {
        double ang = a0 + sweep * k / steps;
        line.push_back(node + h * Point{std::cos(ang), std::sin(ang)});
      }
      append_points(line, border_path(b.outgoing, 0.0, b.border, b.right, -1));
      return line;
    }
    if (c.status == "clamped" || c.status == "no_corner") {
      // Straight across to the next border line: no curb to follow outward.
      if (out > 0.0) return {};
      return line;
    }
    // The arc's tangent points replace the border points at the feet: where a foot is at a
    // bend of the axis the arc touches the rounded offset, not the normal of a segment.
    double foot_a = project(a.outgoing, c.arc_points.front()).abscissa;
    double foot_b = project(b.outgoing, c.arc_points.back()).abscissa;
    Polyline corner = c.arc_points;
    if (out > 0.0) {
      if (c.centre && c.radius > out) {
        double k = (c.radius - out) / c.radius;
        Point centre = *c.centre;
        corner = arc_points(centre, centre + k * (c.arc_points.front() - centre), centre + k * (c.arc_points.back() - centre),
                            c.radius - out);
      } else {
        // The moved borders cross: a's left border line at the foot, b's right one.
        Point pa = border_point(a.outgoing, foot_a, a.left + out, +1);
        Point pb = border_point(b.outgoing, foot_b, b.right + out, -1);
        Point da = tangent_at(a.outgoing, foot_a);
        Point db = tangent_at(b.outgoing, foot_b);
        double det = cross(da, db);
        if (std::abs(det) < 1e-9) return {};
        Point x = pa + (cross(pb - pa, db) / det) * da;
        foot_a = project(a.outgoing, x).abscissa;
        foot_b = project(b.outgoing, x).abscissa;
        if (foot_a > a.border || foot_b > b.border) {
          // Beyond a border line, where a street's own claim is: the band then reaches the
          // crossing of the two border lines, if that lies within `out` of both curbs' ends
          // (a tight corner whose arc starts on both border lines: the whole corner up to them).
          Point a_border = point_at(a.outgoing, a.border), b_border = point_at(b.outgoing, b.border);
          Point across_a = left_normal(tangent_at(a.outgoing, a.border));
          Point across_b = -1.0 * left_normal(tangent_at(b.outgoing, b.border));
          double d = cross(across_a, across_b);
          if (std::abs(d) < 1e-9) return {};
          double ta = cross(b_border - a_border, across_b) / d;  // along a's border line, from its axis
          double tb = cross(b_border - a_border, across_a) / d;  // along b's
          if (ta < a.left - kSamePoint || ta > a.left + out || tb < b.right - kSamePoint || tb > b.right + out) return {};
          return {a_border + ta * across_a};
        }
        corner = {x};
      }
    }
    Polyline in = border_path(a.outgoing, a.border, std::min(foot_a, a.border), a.left + out, +1);
    in.pop_back();
    Polyline away = border_path(b.outgoing, std::min(foot_b, b.border), b.border, b.right + out, -1);
    away.erase(away.begin());
    append_points(line, in);
    append_points(line, corner);
    append_points(line, away);
    return line;
  }

  // Keeps a valid constructed polygon, or repairs it. Otherwise the fallback: the stubs of the axes up to their border lines, buffered, with the node's
  // surroundings, minus the sections around the node: never a missing junction, never an
  // overlap with a section.
  void finish_intersection(std::size_t n, GeomPtr polygon, const char* status) {
    const TopologyNode& node = topo_.nodes[n];
    IntersectionResult ir;
    ir.node_id = node.id;
    ir.status = status;
    if (polygon && GEOSisValid_r(ctx_.handle(), polygon.get()) == 1 && area_of(ctx_, polygon.get()) > 1e-9) {
      ir.surface = std::move(polygon);
    } else if (GeomPtr repaired = repair(polygon.get(), node.position)) {
      ir.surface = std::move(repaired);
      ir.status = "repaired";
    } else {
      ir.status = "fallback";
      ir.surface = fallback_polygon(n);
    }
    result_.intersections.push_back(std::move(ir));
    junction_node_.push_back(n);
  }

  // A ring with small defects (spikes, a pinch where border and arc meet at a bend) made valid:
  // the part holding the node, if it keeps nearly all of the ring's area. Null otherwise.
  GeomPtr repair(const GEOSGeometry* polygon, Point node) {
    if (polygon == nullptr) return nullptr;
    double ring_area = std::abs(signed_area(polygon));
    GEOSGeometry* fixed = GEOSMakeValid_r(ctx_.handle(), polygon);
    if (fixed == nullptr) {
      ctx_.clear_error();
      return nullptr;
    }
    GeomPtr fixed_ptr(fixed, GeomDeleter{ctx_.handle()});
    GeomPtr part = pick_polygon(ctx_, fixed_ptr.get(), node);
    if (!part || ring_area <= 1e-9 || area_of(ctx_, part.get()) < 0.9 * ring_area) return nullptr;
    return part;
  }

  // Shoelace area of a polygon's shell (what the ring meant, before any repair).
  double signed_area(const GEOSGeometry* polygon) {
    const GEOSGeometry* shell = GEOSGetExteriorRing_r(ctx_.handle(), polygon);
    const GEOSCoordSequence* seq = shell ? GEOSGeom_getCoordSeq_r(ctx_.handle(), shell) : nullptr;
    if (seq == nullptr) return 0.0;
    unsigned int n = 0;
    GEOSCoordSeq_getSize_r(ctx_.handle(), seq, &n);
    double sum = 0.0;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    for (unsigned int i = 0; i + 1 < n; ++i) {
      GEOSCoordSeq_getXY_r(ctx_.handle(), seq, i, &x0, &y0);
      GEOSCoordSeq_getXY_r(ctx_.handle(), seq, i + 1, &x1, &y1);
      sum += x0 * y1 - x1 * y0;
    }
    return sum / 2;
  }

  GeomPtr fallback_polygon(std::size_t n) {
    const TopologyNode& node = topo_.nodes[n];
    const std::vector<End>& ends = ends_of_node_[n];
    std::vector<GeomPtr> parts;
    double h_max = 0.0;
    for (const End& e : ends) {
      h_max = std::max({h_max, e.left, e.right});
      if (e.border <= 1e-9) continue;
      parts.push_back(roadway_polygon(substring(e.outgoing, 0.0, e.border), e.left, e.right, "stub buffer"));
    }
    GeomPtr centre = make_point(ctx_, node.position);
    parts.push_back(own(ctx_, GEOSBuffer_r(ctx_.handle(), centre.get(), std::max(h_max, 0.25), kQuadrantSegments), "node buffer"));
    GeomPtr collection = make_collection(ctx_, GEOS_GEOMETRYCOLLECTION, parts);
    GeomPtr surface = own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), collection.get()), "union");
    // Minus the sections of the axes at this node.
    for (const End& e : ends) {
      const TopologyEdge& edge = topo_.edges[e.edge];
      auto it = section_surface_.find({edge.axis_id, edge.part});
      if (it == section_surface_.end()) continue;
      surface = own(ctx_, GEOSDifference_r(ctx_.handle(), surface.get(), it->second), "difference");
    }
    GeomPtr part = pick_polygon(ctx_, surface.get(), node.position);
    if (part && area_of(ctx_, part.get()) > 1e-9) return part;
    return own(ctx_, GEOSBuffer_r(ctx_.handle(), centre.get(), 0.25, kQuadrantSegments), "node buffer");
  }

  // Sections of different axes on one layer overlap where the axes run closer than their half
  // widths add up (dual carriageways whose width is estimated, acute branches): each keeps the
  // part of the overlap nearer its own axis. The split follows a Voronoi diagram of points
  // sampled along both axes, so it runs along the midline however the axes curve.
  void separate_overlapping_sections() {
    std::vector<std::size_t> with_surface;
    std::vector<Box> boxes;
    for (std::size_t i = 0; i < result_.sections.size(); ++i) {
      const SectionResult& s = result_.sections[i];
      if (!s.surface) continue;
      double x0, y0, x1, y1;
      if (GEOSGeom_getXMin_r(ctx_.handle(), s.surface.get(), &x0) == 0 ||
          GEOSGeom_getYMin_r(ctx_.handle(), s.surface.get(), &y0) == 0 ||
          GEOSGeom_getXMax_r(ctx_.handle(), s.surface.get(), &x1) == 0 ||
          GEOSGeom_getYMax_r(ctx_.handle(), s.surface.get(), &y1) == 0) {
        ctx_.fail("envelope");
      }
      with_surface.push_back(i);
      boxes.push_back({x0, y0, x1, y1});
    }
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for_each_overlapping_pair(boxes, [&](std::size_t i, std::size_t j) {
      const SectionResult& a = result_.sections[with_surface[i]];
      const SectionResult& b = result_.sections[with_surface[j]];
      if (a.axis_id == b.axis_id || axis_layer_.at(a.axis_id) != axis_layer_.at(b.axis_id)) return;
      // The pair's first member is the one with the smaller key: results do not depend on the
      // order sections were built in (an incremental recompute of a few axes gives the same).
      bool a_first = std::make_pair(a.axis_id, a.part) < std::make_pair(b.axis_id, b.part);
      pairs.push_back(a_first ? std::make_pair(with_surface[i], with_surface[j]) : std::make_pair(with_surface[j], with_surface[i]));
    });
    auto key = [&](std::size_t s) { return std::make_pair(result_.sections[s].axis_id, result_.sections[s].part); };
    std::sort(pairs.begin(), pairs.end(), [&](const auto& x, const auto& y) {
      return std::make_pair(key(x.first), key(x.second)) < std::make_pair(key(y.first), key(y.second));
    });
    // Every pair is split on the sections as built, and each section then gives away, at once,
    // what is nearer to any other axis: the result does not depend on the order of the pairs,
    // and a section's shape depends only on the sections that overlap it.
    std::map<std::size_t, std::vector<GeomPtr>> given_away;
    InterruptPoller poller(16);
    for (auto [i, j] : pairs) {
      poller.tick();
      const SectionResult& a = result_.sections[i];
      const SectionResult& b = result_.sections[j];
      Polyline axis_a = substring(a.centre_line, a.start_border, a.end_border);
      Polyline axis_b = substring(b.centre_line, b.start_border, b.end_border);
      // Sections are within half their width of their axes: farther apart, they cannot overlap.
      if (polyline_distance(axis_a, axis_b) >= reach_of(a.axis_id) + reach_of(b.axis_id)) continue;
      // GEOS overlay (OverlayNG) is robust where its predicates can throw on nearly coincident
      // edges, so no GEOSIntersects here; and one pair that GEOS cannot split is reported, not
      // allowed to fail the whole model.
      // (most pairs left only touch, at a junction's border line or by a hair where roadways
      // meet: an overlay would find less than kGivenAway, which is left alone)
      if (surely_share_less(a.surface.get(), b.surface.get(), 0.25 * kGivenAway)) {
        ++result_.stats.section_pairs_touching;
        continue;
      }
      ++result_.stats.section_pair_overlays;
      try {
        GeomPtr overlap = own(ctx_, GEOSIntersection_r(ctx_.handle(), a.surface.get(), b.surface.get()), "overlap");
        if (area_of(ctx_, overlap.get()) < kGivenAway) continue;
        auto [nearer_a, nearer_b] = split_by_nearness(overlap.get(), axis_a, axis_b);
        given_away[i].push_back(std::move(nearer_b));
        given_away[j].push_back(std::move(nearer_a));
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::geometry_engine) throw;
        result_.issues.push_back({a.axis_id, "overlap_kept",
                                  "the overlap with axis " + std::to_string(b.axis_id) + " could not be split: " + e.detail(),
                                  a.part});
      }
    }
    for (auto& [i, pieces] : given_away) {
      SectionResult& sec = result_.sections[i];
      try {
        GeomPtr all = make_collection(ctx_, GEOS_GEOMETRYCOLLECTION, pieces);
        GeomPtr lost = own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), all.get()), "union");
        Polyline axis = substring(sec.centre_line, sec.start_border, sec.end_border);
        sec.surface = main_part(own(ctx_, GEOSDifference_r(ctx_.handle(), sec.surface.get(), lost.get()), "difference"), axis);
        sec.status = "narrowed";
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::geometry_engine) throw;
        result_.issues.push_back({sec.axis_id, "overlap_kept", "its overlaps could not be removed: " + e.detail(), sec.part});
      }
    }
  }

  // Junction surfaces overlap where nodes lie closer than their junctions reach: acute branches
  // packed together (interchanges, slip lanes, sausage links), a ramp beside a junction, and by
  // a few cm² where a curb meets its own section off the border line. Sections win, as they are
  // final by now (their lanes are built): a junction gives up what any section covers. Two junctions split their overlap along the midline of their skeletons
  // (the node and the axis stubs out to its border lines), each keeping the part nearer its own,
  // as sections do with each other. A junction that gave up area is `narrowed`; it keeps the
  // polygon that holds its node (what else is left, cut off, is dropped: a few slivers).
  // A junction's final shape depends only on its own surface, the sections overlapping it and
  // the junctions overlapping it: the refresh brings those in (sql/65-refresh.sql).
  void separate_overlapping_junctions(InterruptPoller& poller) {
    const std::size_t junctions = result_.intersections.size();
    std::vector<std::size_t> sections;  // indices into result_.sections, with a surface
    std::vector<Box> junction_boxes;
    std::vector<Box> section_boxes;     // of `sections`
    for (std::size_t j = 0; j < junctions; ++j) {
      Box b{};
      envelope_box(ctx_, result_.intersections[j].surface.get(), b);
      junction_boxes.push_back(b);
    }
    for (std::size_t i = 0; i < result_.sections.size(); ++i) {
      if (!result_.sections[i].surface) continue;
      Box b{};
      envelope_box(ctx_, result_.sections[i].surface.get(), b);
      sections.push_back(i);
      section_boxes.push_back(b);
    }
    // Junction against junction and junction against section only: the section pairs, most of
    // the boxes that meet (a street's sections meet end to end), are not enumerated at all.
    std::vector<std::pair<std::size_t, std::size_t>> junction_pairs;
    for_each_overlapping_pair(junction_boxes, [&](std::size_t x, std::size_t y) {
      if (topo_.nodes[junction_node_[x]].layer == topo_.nodes[junction_node_[y]].layer) junction_pairs.emplace_back(x, y);
    });
    std::map<std::size_t, std::vector<std::size_t>> covering;  // junction -> sections over it (result_ indices)
    for_each_overlapping_cross_pair(junction_boxes, section_boxes, [&](std::size_t x, std::size_t k) {
      std::size_t i = sections[k];
      if (axis_layer_.at(result_.sections[i].axis_id) != topo_.nodes[junction_node_[x]].layer) return;
      covering[x].push_back(i);
    });
    // (in index order, as the callbacks come in no set order: the bound below sums over them)
    for (auto& [j, over] : covering) std::sort(over.begin(), over.end());
    // The junctions less the sections over them. Most sections whose box meets a junction's only
    // touch it along a border line: an exact test on their rings drops those before the overlay.
    std::vector<GeomPtr> cut(junctions);
    std::map<std::size_t, Polyline> section_rings;  // result_ index -> exterior ring of a simple polygon
    for (auto& [j, over] : covering) {
      poller.tick();
      IntersectionResult& ir = result_.intersections[j];
      Polyline junction_ring = simple_ring(ir.surface.get());
      if (!junction_ring.empty()) {
        over.erase(std::remove_if(over.begin(), over.end(),
                                  [&](std::size_t i) {
                                    auto it = section_rings.find(i);
                                    if (it == section_rings.end()) it = section_rings.emplace(i, simple_ring(result_.sections[i].surface.get())).first;
                                    return !it->second.empty() && !interiors_may_meet(junction_ring, it->second);
                                  }),
                   over.end());
        if (over.empty()) {
          ++result_.stats.junctions_touching;
          continue;
        }
        // Most of the rest touch it too, but for rounding where a section's flat end meets the
        // junction's border line: if what they can share is provably under kGivenAway (with room
        // for the overlay's own rounding), the overlay below would keep the junction as it is.
        double shared_at_most = 0.0;
        for (std::size_t i : over) {
          const Polyline& ring = section_rings.at(i);
          std::optional<double> bound = ring.empty() ? std::nullopt : touching_overlap_bound(junction_ring, ring, kSamePoint);
          if (!bound) {
            shared_at_most = kGivenAway;
            break;
          }
          shared_at_most += *bound;
        }
        if (shared_at_most < 0.25 * kGivenAway) {
          ++result_.stats.junctions_touching_but_for_rounding;
          continue;
        }
      }
      ++result_.stats.junction_overlays;
      try {
        // (in key order, as one union: the same result whichever order the boxes were paired in)
        std::sort(over.begin(), over.end(), [&](std::size_t a, std::size_t b) {
          return std::make_pair(result_.sections[a].axis_id, result_.sections[a].part) <
                 std::make_pair(result_.sections[b].axis_id, result_.sections[b].part);
        });
        std::vector<GeomPtr> copies;
        for (std::size_t i : over) copies.push_back(own(ctx_, GEOSGeom_clone_r(ctx_.handle(), result_.sections[i].surface.get()), "clone"));
        GeomPtr all = make_collection(ctx_, GEOS_GEOMETRYCOLLECTION, copies);
        GeomPtr under = own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), all.get()), "union");
        GeomPtr rest = own(ctx_, GEOSDifference_r(ctx_.handle(), ir.surface.get(), under.get()), "difference");
        if (area_of(ctx_, ir.surface.get()) - area_of(ctx_, rest.get()) > kGivenAway) cut[j] = std::move(rest);
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::geometry_engine) throw;
        result_.issues.push_back({topo_.nodes[junction_node_[j]].axis_ids.front(), "overlap_kept",
                                  "the junction's overlap with sections could not be removed: " + e.detail(), std::nullopt,
                                  ir.node_id});
      }
    }
    auto current = [&](std::size_t j) { return cut[j] ? cut[j].get() : result_.intersections[j].surface.get(); };
    // Pairs in key order, split on the junctions as cut above, all given away at once: the result
    // does not depend on the order of the pairs.
    for (auto& [x, y] : junction_pairs) {
      if (result_.intersections[y].node_id < result_.intersections[x].node_id) std::swap(x, y);
    }
    std::sort(junction_pairs.begin(), junction_pairs.end(), [&](const auto& p, const auto& q) {
      return std::make_pair(result_.intersections[p.first].node_id, result_.intersections[p.second].node_id) <
             std::make_pair(result_.intersections[q.first].node_id, result_.intersections[q.second].node_id);
    });
    std::map<std::size_t, std::vector<GeomPtr>> given_away;
    for (auto [x, y] : junction_pairs) {
      poller.tick();
      if (surely_share_less(current(x), current(y), 0.25 * kGivenAway)) {
        ++result_.stats.junction_pairs_touching;
        continue;
      }
      ++result_.stats.junction_pair_overlays;
      try {
        GeomPtr overlap = own(ctx_, GEOSIntersection_r(ctx_.handle(), current(x), current(y)), "overlap");
        if (area_of(ctx_, overlap.get()) < kGivenAway) continue;
        auto [nearer_x, nearer_y] = split_by_nearness(overlap.get(), skeleton(junction_node_[x]), skeleton(junction_node_[y]));
        given_away[x].push_back(std::move(nearer_y));
        given_away[y].push_back(std::move(nearer_x));
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::geometry_engine) throw;
        result_.issues.push_back({topo_.nodes[junction_node_[x]].axis_ids.front(), "overlap_kept",
                                  "the overlap with the junction of node " + std::to_string(result_.intersections[y].node_id) +
                                      " could not be split: " + e.detail(),
                                  std::nullopt, result_.intersections[x].node_id});
      }
    }
    for (std::size_t j = 0; j < junctions; ++j) {
      IntersectionResult& ir = result_.intersections[j];
      auto lost = given_away.find(j);
      if (!cut[j] && lost == given_away.end()) continue;
      try {
        GeomPtr rest = own(ctx_, GEOSGeom_clone_r(ctx_.handle(), current(j)), "clone");
        if (lost != given_away.end()) {
          GeomPtr all = make_collection(ctx_, GEOS_GEOMETRYCOLLECTION, lost->second);
          GeomPtr pieces = own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), all.get()), "union");
          rest = own(ctx_, GEOSDifference_r(ctx_.handle(), rest.get(), pieces.get()), "difference");
        }
        GeomPtr part = pick_polygon(ctx_, rest.get(), topo_.nodes[junction_node_[j]].position);
        // (covered all over by sections and other junctions: the surface stays as built, reported)
        if (!part || area_of(ctx_, part.get()) <= 1e-9) {
          result_.issues.push_back({topo_.nodes[junction_node_[j]].axis_ids.front(), "overlap_kept",
                                    "the junction lies under other roadways", std::nullopt, ir.node_id});
          continue;
        }
        ir.surface = std::move(part);
        ir.status = "narrowed";
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::geometry_engine) throw;
        result_.issues.push_back({topo_.nodes[junction_node_[j]].axis_ids.front(), "overlap_kept",
                                  "its overlaps could not be removed: " + e.detail(), std::nullopt, ir.node_id});
      }
    }
  }

  // The exterior ring of a polygon without holes; empty for anything else.
  Polyline simple_ring(const GEOSGeometry* g) {
    if (GEOSGeomTypeId_r(ctx_.handle(), g) != GEOS_POLYGON || GEOSGetNumInteriorRings_r(ctx_.handle(), g) != 0) return {};
    const GEOSGeometry* ring = GEOSGetExteriorRing_r(ctx_.handle(), g);
    const GEOSCoordSequence* seq = ring ? GEOSGeom_getCoordSeq_r(ctx_.handle(), ring) : nullptr;
    unsigned int n = 0;
    if (!seq || GEOSCoordSeq_getSize_r(ctx_.handle(), seq, &n) == 0) return {};
    Polyline out(n);
    for (unsigned int i = 0; i < n; ++i) GEOSCoordSeq_getXY_r(ctx_.handle(), seq, i, &out[i].x, &out[i].y);
    return out;
  }

  // Whether two simple polygons surely share less than `area`, by exact tests without an overlay:
  // their interiors apart, or apart but for rounding with a bound on what they can share under it.
  // false when that cannot be shown (then an overlay tells).
  bool surely_share_less(const GEOSGeometry* a, const GEOSGeometry* b, double area) {
    Polyline ring_a = simple_ring(a), ring_b = simple_ring(b);
    if (ring_a.empty() || ring_b.empty()) return false;
    if (!interiors_may_meet(ring_a, ring_b)) return true;
    std::optional<double> bound = touching_overlap_bound(ring_a, ring_b, kSamePoint);
    return bound && *bound < area;
  }

  // A junction's skeleton as one polyline: from the node out along each axis to its border line
  // and back (distances to it are distances to the nearest stub).
  Polyline skeleton(std::size_t n) const {
    Point node = topo_.nodes[n].position;
    Polyline star{node};
    for (const End& e : ends_of_node_[n]) {
      if (e.border <= 1e-9) continue;
      Polyline stub = substring(e.outgoing, 0.0, e.border);
      star.insert(star.end(), stub.begin() + 1, stub.end());
      star.insert(star.end(), stub.rbegin() + 1, stub.rend());
    }
    if (star.size() == 1) star.push_back(node);
    return star;
  }

  // The overlap's area split in two: the part nearer to polyline a than to polyline b, and the rest. The
  // split line is the Voronoi boundary between points sampled along a and along b (CGAL,
  // bisector.hpp); the region's boundary and that line are noded and polygonized, and each face
  // goes to the line it is nearer to. (GEOS's Voronoi diagram, whose cells had to be clipped to
  // its box, classified, united and intersected with the region, took 38 % of Paris' engine.)
  std::pair<GeomPtr, GeomPtr> split_by_nearness(const GEOSGeometry* overlap, const Polyline& a, const Polyline& b) {
    // (an overlap can come with lines and points where the surfaces touch: they have no area)
    GeomPtr polygonal = polygons_of(ctx_, overlap, 0.0);
    auto empty = [&] { return own(ctx_, GEOSGeom_createEmptyPolygon_r(ctx_.handle()), "empty polygon"); };
    if (!polygonal) return {empty(), empty()};
    const GEOSGeometry* region = polygonal.get();
    Box box{};
    envelope_box(ctx_, region, box);
    double extent = std::max(box.xmax - box.xmin, box.ymax - box.ymin);
    // Sixty samples across the overlap: the split line is then within a few centimetres of the
    // true midline for carriageways a few metres apart, at a fraction of the Delaunay cost.
    double spacing = std::clamp(extent / 60.0, 0.05, 2.0);
    auto sample = [&](const Polyline& line) {
      std::vector<Point> sites;
      double len = length(line);
      int n = std::max(2, static_cast<int>(std::ceil(len / spacing)) + 1);
      for (int k = 0; k < n; ++k) {
        Point p = point_at(line, len * k / (n - 1));
        // Only the stretch beside the overlap matters.
        if (p.x < box.xmin - extent || p.x > box.xmax + extent || p.y < box.ymin - extent || p.y > box.ymax + extent) continue;
        sites.push_back(p);
      }
      return sites;
    };
    double margin = std::max(1.0, 0.01 * extent);
    std::vector<BisectorSegment> split =
        bisector_segments(sample(a), sample(b), {box.xmin - margin, box.ymin - margin, box.xmax + margin, box.ymax + margin});
    std::vector<GeomPtr> lines;
    lines.push_back(own(ctx_, GEOSBoundary_r(ctx_.handle(), region), "boundary"));
    for (const BisectorSegment& s : split) lines.push_back(make_line(ctx_, {s.from, s.to}));
    GeomPtr linework = make_collection(ctx_, GEOS_GEOMETRYCOLLECTION, lines);
    GeomPtr noded = own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), linework.get()), "noding");
    const GEOSGeometry* noded_ptr = noded.get();
    GeomPtr faces = own(ctx_, GEOSPolygonize_r(ctx_.handle(), &noded_ptr, 1), "polygonize");
    std::vector<GeomPtr> nearer_a, nearer_b;
    int n = GEOSGetNumGeometries_r(ctx_.handle(), faces.get());
    for (int k = 0; k < n; ++k) {
      const GEOSGeometry* face = GEOSGetGeometryN_r(ctx_.handle(), faces.get(), k);
      GeomPtr probe = own(ctx_, GEOSPointOnSurface_r(ctx_.handle(), face), "point on surface");
      // (faces outside the region: its holes, and loops of the split line outside it)
      char inside = GEOSIntersects_r(ctx_.handle(), region, probe.get());
      if (inside == 2) ctx_.fail("point in overlap");  // (the caller keeps the overlap, reported)
      if (inside == 0) continue;
      double x, y;
      GEOSGeomGetX_r(ctx_.handle(), probe.get(), &x);
      GEOSGeomGetY_r(ctx_.handle(), probe.get(), &y);
      bool to_a = project(a, {x, y}).distance <= project(b, {x, y}).distance;
      (to_a ? nearer_a : nearer_b).push_back(own(ctx_, GEOSGeom_clone_r(ctx_.handle(), face), "clone"));
    }
    auto united = [&](std::vector<GeomPtr>& parts) {
      if (parts.empty()) return empty();
      if (parts.size() == 1) return std::move(parts.front());
      GeomPtr all = make_collection(ctx_, GEOS_GEOMETRYCOLLECTION, parts);
      return own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), all.get()), "union");
    };
    GeomPtr part_a = united(nearer_a);
    GeomPtr part_b = united(nearer_b);
    return {std::move(part_a), std::move(part_b)};
  }

  // A section after the split: the polygon on its axis (slivers dropped).
  GeomPtr main_part(GeomPtr surface, const Polyline& axis) {
    if (GEOSGeomTypeId_r(ctx_.handle(), surface.get()) == GEOS_POLYGON) return surface;
    GeomPtr part = pick_polygon(ctx_, surface.get(), point_at(axis, 0.5 * length(axis)));
    return part ? std::move(part) : std::move(surface);
  }

  // Lanes and markings on the final section surfaces (after the overlap split). Sections are
  // built one per edge, in edge order. Stop lines where a section meets a junction of three or
  // more streets (a degree-2 node is a street running on).
  void build_lanes(InterruptPoller& poller) {
    if (result_.sections.size() != topo_.edges.size()) throw Error(ErrorKind::internal, "sections out of step with edges");
    for (std::size_t e = 0; e < topo_.edges.size(); ++e) {
      const SectionResult& sec = result_.sections[e];
      if (!sec.surface) continue;
      poller.tick();
      const TopologyEdge& edge = topo_.edges[e];
      const LanePlan& plan = plans_[edge.axis_index];
      const SurfaceAxis& axis = axes_[edge.axis_index];
      for (const LaneNote& note : plan.notes) result_.issues.push_back({sec.axis_id, note.kind, note.detail, sec.part});
      // One section GEOS cannot split is reported, not allowed to fail the whole model: it
      // keeps its surface without lanes.
      std::vector<LaneResult> lanes;
      std::vector<MarkingResult> markings;
      Polyline centre = substring(sec.centre_line, sec.start_border, sec.end_border);
      // A crossing at a junction end: the stop line moves behind it.
      double setback[2] = {-1.0, -1.0};
      for (int at_end = 0; at_end <= 1; ++at_end) {
        if (!crossing_at(edge, axis, sec, at_end == 1)) continue;
        try {
          if (add_crossing(sec, edge, centre, at_end == 1)) setback[at_end] = s_.crossing_width + kStopBehindCrossing;
        } catch (const Error& e) {
          if (e.kind() != ErrorKind::geometry_engine) throw;
          result_.issues.push_back({sec.axis_id, "crossing_failed", e.what() + std::string(": ") + e.detail(), sec.part});
        }
      }
      try {
        section_lanes(ctx_, sec.axis_id, sec.part, centre, sec.surface.get(), sec.status != "ok", plan,
                      degree_of(edge.from_node) >= 3, degree_of(edge.to_node) >= 3, lanes, markings, setback[0],
                      setback[1]);
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::geometry_engine) throw;
        result_.issues.push_back({sec.axis_id, "lanes_failed", e.what() + std::string(": ") + e.detail(), sec.part});
        continue;
      }
      for (LaneResult& l : lanes) {
        hand_over(l.surface, l.ewkb);
        result_.lanes.push_back(std::move(l));
      }
      for (MarkingResult& m : markings) {
        hand_over(m.line, m.ewkb);
        result_.markings.push_back(std::move(m));
      }
    }
  }

  // Crossings (a documented rule; OSM crossing nodes are not imported): at each end of a section
  // that meets a junction of three or more streets, on streets no faster than
  // crossing_max_speed_kmh with a sidewalk on both sides (a crossing joins two sidewalks), where
  // the section is long enough for a crossing and a stop line behind it at both ends.
  bool crossing_at(const TopologyEdge& edge, const SurfaceAxis& axis, const SectionResult& sec, bool at_end) const {
    if (!(s_.crossing_width > 0.0) || !sec.surface) return false;
    if (degree_of(at_end ? edge.to_node : edge.from_node) < 3) return false;
    if (axis.speed_kmh > s_.crossing_max_speed_kmh) return false;
    if (!(axis.sidewalk_left > 0.0 && axis.sidewalk_right > 0.0)) return false;
    return sec.end_border - sec.start_border >= 2 * (s_.crossing_width + kStopBehindCrossing + 0.5);
  }

  // The zebra area: the roadway between the border line and crossing_width into the section.
  bool add_crossing(const SectionResult& sec, const TopologyEdge& edge, const Polyline& centre,
                    bool at_end) {
    double len = length(centre);
    Polyline piece = at_end ? substring(centre, len - s_.crossing_width, len) : substring(centre, 0.0, s_.crossing_width);
    GeomPtr band;
    if (piece.size() == 2 && distance(piece[0], piece[1]) > kSamePoint) {
      // A straight piece (most are: 3 m of axis): the band is the rectangle the buffer below
      // would make, built directly (a GEOS buffer for each of Paris' 56,600 crossings was a third
      // of the lanes phase). Its sides stay at the roadway's reach: where a section is wider
      // than that (50 of Paris' crossings), the crossing keeps the roadway's width.
      Point along = unit(piece[1] - piece[0]);
      Point across = reach_of(sec.axis_id) * left_normal(along);
      band = make_polygon(ctx_, {piece[0] + across, piece[0] - 1.0 * across, piece[1] - 1.0 * across, piece[1] + across,
                                 piece[0] + across});
    } else {
      GeomPtr line = make_line(ctx_, piece);
      band = own(ctx_,
                 GEOSBufferWithStyle_r(ctx_.handle(), line.get(), reach_of(sec.axis_id), kQuadrantSegments, GEOSBUF_CAP_FLAT,
                                       GEOSBUF_JOIN_ROUND, 5.0),
                 "crossing buffer");
    }
    GeomPtr inside = own(ctx_, GEOSIntersection_r(ctx_.handle(), band.get(), sec.surface.get()), "crossing clip");
    GeomPtr area = polygons_of(ctx_, inside.get(), 1e-3);
    if (!area) return false;
    CrossingResult c;
    c.axis_id = sec.axis_id;
    c.part = sec.part;
    c.position = at_end ? 1 : 0;
    c.node_id = topo_.nodes[at_end ? edge.to_node : edge.from_node].id;
    c.width = s_.crossing_width;
    c.surface = std::move(area);
    hand_over(c.surface, c.ewkb);
    result_.crossings.push_back(std::move(c));
    return true;
  }

  // What a claim's sidewalk will be: a SidewalkResult without its geometry (a city has tens of
  // thousands of claims).
  struct ClaimKey {
    std::int64_t axis_id = 0;
    std::int64_t part = 0;
    std::int64_t node_id = 0;
    std::string_view side;  // "left", "right", "around"
    double width = 0.0;
    SidewalkResult result() const {
      SidewalkResult r;
      r.axis_id = axis_id;
      r.part = part;
      r.node_id = node_id;
      r.side = std::string(side);
      r.width = width;
      return r;
    }
  };

  // A sidewalk's claim, as build_sidewalks holds it during its turn.
  struct SidewalkItem {
    const GEOSGeometry* geom = nullptr;  // owned's
    GeomPtr owned;
    int layer = 0;
    ClaimKey meta;
    // A street side's claim ends on the normals at its section's border points, and a junction
    // corner's on its two streets' border lines: the lines through cut_point[k] across
    // cut_direction[k] (pointing into the claim), when the whole claim lies on their inner side
    // (cuts[k]; a tight bend can break that).
    bool cuts[2] = {false, false};
    Point cut_point[2];
    Point cut_direction[2];
    // A junction corner's claim: piece > 0, numbered from 1 round the node; the pieces of one
    // junction make one sidewalk.
    int piece = 0;
    // A claim that is one polygon without holes built for its own shape (a corner's band, a band
    // outside a roadway): tested exactly against what it may meet, by its shell (read from its
    // geometry when its turn comes: every claim's ring held at once was a copy of them all).
    bool own_ring = false;
  };

  // Which sidewalk width an end's street has on its side facing the corner to the left (true)
  // or to the right (false) of its outgoing direction.
  double facing_sidewalk(const End& e, bool left_of_outgoing) const {
    const SurfaceAxis& axis = axes_[topo_.edges[e.edge].axis_index];
    return left_of_outgoing != e.at_end ? axis.sidewalk_left : axis.sidewalk_right;
  }

  // A junction's sidewalk claimed corner by corner: the band between the curb and the curb moved
  // out by the sidewalk width (the wider of the two streets' sides facing the corner), ending on
  // the two streets' border lines, where their side claims end. Built from the corner's own
  // lines it needs no buffer and, where the junction is as built, touches its neighbours only
  // along its edges (each tested exactly). A corner without such a band (no curb to follow
  // outward: clamped, no arc; the moved curb crossing a border line; an invalid ring) claims the
  // buffer of its own curb instead, which gives way to the roadways and earlier claims by
  // overlays, as a junction's buffer would, but only there. Adds nothing and returns false when
  // the junction has no curb per corner or two corners' bands overlap: the caller then claims
  // the buffer of the whole junction. `buffered`: how many corners claim their curb's buffer.
  bool add_corner_claims(std::size_t n, std::int64_t node_id, std::vector<SidewalkItem>& claims, long& buffered) {
    const std::vector<End>& ends = ends_of_node_[n];
    // (a street taken whole by the junction has no claim beyond its border line to end on)
    for (const End& e : ends) {
      if (!result_.sections[e.edge].surface) return false;
    }
    std::vector<SidewalkItem> pieces;
    std::vector<Polyline> rings;  // (the bands', by piece; empty for a buffered corner)
    buffered = 0;
    for (std::size_t i = 0; i < ends.size(); ++i) {
      const End& a = ends[i];
      const End& b = ends[(i + 1) % ends.size()];
      double w = std::max(facing_sidewalk(a, true), facing_sidewalk(b, false));
      if (!(w > 0.0)) continue;
      SidewalkItem it;
      Polyline ring = corner_band(n, i, w, it);
      if (ring.empty()) {
        // (a clamped corner's curb is a's border point alone: the ring goes straight on to b's)
        Polyline curb_line = curb(n, i, 0.0);
        append_points(curb_line, {border_point(b.outgoing, b.border, b.right, -1)});
        if (curb_line.size() < 2) return false;
        GeomPtr line = make_line(ctx_, curb_line);
        it.owned = own(ctx_, GEOSBufferWithStyle_r(ctx_.handle(), line.get(), w, kQuadrantSegments, GEOSBUF_CAP_ROUND,
                                                   GEOSBUF_JOIN_ROUND, 5.0),
                       "corner sidewalk buffer");
        it.own_ring = false;
        ++buffered;
      } else {
        it.own_ring = true;
      }
      it.geom = it.owned.get();
      it.layer = topo_.nodes[n].layer;
      it.piece = static_cast<int>(i) + 1;
      rings.push_back(std::move(ring));
      it.cut_point[0] = point_at(a.outgoing, a.border);
      it.cut_direction[0] = -1.0 * tangent_at(a.outgoing, a.border);
      it.cut_point[1] = point_at(b.outgoing, b.border);
      it.cut_direction[1] = -1.0 * tangent_at(b.outgoing, b.border);
      for (int k = 0; k < 2; ++k) it.cuts[k] = beyond_line(it.geom, it.cut_point[k], it.cut_direction[k]);
      it.meta.node_id = node_id;
      it.meta.side = "around";
      it.meta.width = w;
      pieces.push_back(std::move(it));
    }
    // (a buffered corner gives way to the bands before it, and the bands after it to it, as any
    // claims do; two bands, each built whole, must not overlap)
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      for (std::size_t j = i + 1; j < pieces.size(); ++j) {
        if (!rings[i].empty() && !rings[j].empty() && interiors_may_meet(rings[i], rings[j])) return false;
      }
    }
    for (SidewalkItem& it : pieces) claims.push_back(std::move(it));
    return true;
  }

  // Corner i's band of width w (see add_corner_claims) into `it.owned`, and its shell; empty
  // when the corner has none.
  Polyline corner_band(std::size_t n, std::size_t i, double w, SidewalkItem& it) {
    Polyline ring = curb(n, i, 0.0);
    if (corner(n, i).status == "convex") {
      // Round the outside of a bend, or a step between two streets' borders: the curb's
      // single-sided buffer, whose joins are round as a buffer of the junction's were (the
      // junction's ring runs counter-clockwise: its outside is on the right).
      if (ring.size() < 2) return {};
      GeomPtr line = make_line(ctx_, ring);
      it.owned = single_sided_buffer(ctx_, line.get(), -w);
      if (GEOSGeomTypeId_r(ctx_.handle(), it.owned.get()) != GEOS_POLYGON ||
          GEOSGetNumInteriorRings_r(ctx_.handle(), it.owned.get()) != 0) {
        return {};
      }
      ring = shells_of(it.owned.get()).front();
    } else {
      Polyline outer = curb(n, i, w);
      if (outer.empty()) return {};
      append_points(ring, Polyline(outer.rbegin(), outer.rend()));
      if (ring.size() < 3) return {};
      it.owned = make_polygon(ctx_, ring);
    }
    if (!it.owned || GEOSisValid_r(ctx_.handle(), it.owned.get()) != 1) return {};
    return ring;
  }

  // The side of a section's roadway outline, `side` +1 left of its centre line `between`, -1
  // right, from its start border line to its end one: the chain of the outline's vertices
  // between the corners it has on the two border lines (the outline is GEOS's flat-capped
  // buffer, so its ends lie on those lines). Empty when the outline has no such corners.
  Polyline roadway_side(const GEOSGeometry* section, const Polyline& between, int side) {
    if (between.size() < 2 || GEOSGeomTypeId_r(ctx_.handle(), section) != GEOS_POLYGON) return {};
    std::vector<Polyline> shells = shells_of(section);
    if (shells.size() != 1 || shells[0].size() < 5) return {};
    Polyline ring = shells[0];
    ring.pop_back();  // (closed: the first point again)
    const std::size_t n = ring.size();
    Point ends[2] = {between.front(), between.back()};
    Point along[2] = {unit(between[1] - between[0]), unit(between.back() - between[between.size() - 2])};
    // On each border line, the outline's corners farthest to this side of the centre line and
    // to the other side.
    long corner[2] = {-1, -1}, opposite[2] = {-1, -1};
    double reach[2] = {0.0, 0.0}, opposite_reach[2] = {0.0, 0.0};
    for (std::size_t k = 0; k < n; ++k) {
      for (int e = 0; e < 2; ++e) {
        if (std::abs(dot(ring[k] - ends[e], along[e])) > kSamePoint) continue;
        double r = side * cross(along[e], ring[k] - ends[e]);
        if (r > reach[e]) {
          reach[e] = r;
          corner[e] = static_cast<long>(k);
        } else if (-r > opposite_reach[e]) {
          opposite_reach[e] = -r;
          opposite[e] = static_cast<long>(k);
        }
      }
    }
    if (corner[0] < 0 || corner[1] < 0 || opposite[0] < 0 || opposite[1] < 0 || corner[0] == corner[1]) return {};
    // Of the two ways round from one corner to the other, the one that passes neither of the
    // other side's.
    for (long step : {1L, -1L}) {
      Polyline chain;
      for (long k = corner[0];; k = (k + static_cast<long>(n) + step) % static_cast<long>(n)) {
        if (k == opposite[0] || k == opposite[1]) {
          chain.clear();
          break;
        }
        chain.push_back(ring[static_cast<std::size_t>(k)]);
        if (k == corner[1]) break;
      }
      if (chain.size() >= 2) return chain;
    }
    return {};
  }

  // A street side's claim as the band outside its roadway: the single-sided buffer of the
  // roadway's side `edge` (along the centre line) by w metres (> 0 left, < 0 right), whose inner
  // edge is the roadway's own outline, so that the two meet along that line only. Null when
  // GEOS makes anything but one polygon without holes of it.
  GeomPtr side_band(const Polyline& edge, double w) {
    GeomPtr line = make_line(ctx_, edge);
    GeomPtr band = single_sided_buffer(ctx_, line.get(), w);
    if (GEOSGeomTypeId_r(ctx_.handle(), band.get()) != GEOS_POLYGON || GEOSGetNumInteriorRings_r(ctx_.handle(), band.get()) != 0) {
      return nullptr;
    }
    return band;
  }

  // The exterior rings of a polygon or multipolygon's parts.
  std::vector<Polyline> shells_of(const GEOSGeometry* g) {
    GEOSContextHandle_t h = ctx_.handle();
    std::vector<Polyline> out;
    auto add = [&](const GEOSGeometry* polygon) {
      const GEOSGeometry* shell = GEOSGetExteriorRing_r(h, polygon);
      const GEOSCoordSequence* seq = shell ? GEOSGeom_getCoordSeq_r(h, shell) : nullptr;
      unsigned int size = 0;
      if (seq == nullptr || GEOSCoordSeq_getSize_r(h, seq, &size) == 0) ctx_.fail("coordinates");
      Polyline ring(size);
      for (unsigned int k = 0; k < size; ++k) {
        if (GEOSCoordSeq_getXY_r(h, seq, k, &ring[k].x, &ring[k].y) == 0) ctx_.fail("coordinates");
      }
      out.push_back(std::move(ring));
    };
    int type = GEOSGeomTypeId_r(h, g);
    if (type == GEOS_POLYGON) {
      add(g);
    } else if (type == GEOS_MULTIPOLYGON) {
      int parts = GEOSGetNumGeometries_r(h, g);
      for (int k = 0; k < parts; ++k) add(GEOSGetGeometryN_r(h, g, k));
    }
    return out;
  }

  // Whether a claim built by its own ring (a junction corner's, a band outside a roadway) may
  // share area with `blocker`: false only when
  // certainly not (every part's shell tested exactly, polygon_contact.hpp; a part with holes
  // counts by its shell, which can only say "may").
  bool claim_may_meet(const Polyline& ring, const GEOSGeometry* blocker) {
    std::vector<Polyline> shells = shells_of(blocker);
    if (shells.empty()) return true;
    for (const Polyline& shell : shells) {
      if (shell.size() >= 4 && interiors_may_meet(ring, shell)) return true;
    }
    return false;
  }

  // A ring rounded vertex by vertex to the sidewalk grid, as a polygon, or null when rounding
  // leaves it invalid. (Snap rounding by GEOS gives the same for a ring that nothing cuts, at
  // about 240 us a ring in GEOS 3.11: it builds a std::random_device each time.)
  GeomPtr rounded_polygon(Polyline ring) {
    for (Point& p : ring) {
      p.x = std::round(p.x / kSidewalkGrid) * kSidewalkGrid;
      p.y = std::round(p.y / kSidewalkGrid) * kSidewalkGrid;
    }
    Polyline kept;
    append_points(kept, ring);
    if (kept.size() < 3) return nullptr;
    GeomPtr polygon = make_polygon(ctx_, kept);
    if (!polygon || GEOSisValid_r(ctx_.handle(), polygon.get()) != 1) return nullptr;
    return polygon;
  }

  // Sidewalks: each section's side bands (the band outside its roadway's own outline, or for a
  // narrowed section the single-sided buffer of its centre line out to half the roadway plus the
  // sidewalk width) and each junction's surroundings (a band per corner along its curb, the
  // buffer of a corner's curb where it has no band, or the junction's surface buffered by the
  // widest sidewalk of its streets: add_corner_claims) are claims; a sidewalk is its claim minus
  // every roadway of its layer and the claims that come before it (sections' in key order, then
  // junctions' by node id), so that sidewalks never overlap a roadway or each other, and a
  // sidewalk depends only on what lies within its reach, whatever else the engine was given.
  //
  // Since a sidewalk depends only on the claims themselves (never on an earlier sidewalk), the
  // claims are taken in any order: along a Hilbert curve, each built when first needed and freed
  // once every claim it blocks is done, so that only the claims round the curve's front are held.
  // Taken in key order, every street side's claim was held until the junctions (all after the
  // street sides) were done: a third of the engine's peak memory on Reisterstown. A claim is
  // built twice: once for its box (the boxes set what blocks what) and once for its turn.
  void build_sidewalks(InterruptPoller& poller) {
    using Item = SidewalkItem;
    std::map<std::int64_t, std::size_t> node_index;
    for (std::size_t n = 0; n < topo_.nodes.size(); ++n) node_index[topo_.nodes[n].id] = n;
    // By index: the roadways, then the claims. What blocks what is found by boxes over both.
    std::vector<const GEOSGeometry*> geoms;  // a claim's while it is held, else null
    std::vector<int> layers;
    // The roadways by key (sections by axis and part, junctions by node id), not in the
    // engine's order: a claim's blockers are taken away in index order, and the same blockers in
    // another order can round its sidewalk differently on the micrometre grid. The sections follow
    // the order the axes were given in (by id from SQL, any order from C++); the junctions come
    // in the order the topology found their crossings, which changes with any other axis given:
    // a full run and a local refresh put two junctions' roadways the other way round, and a junction
    // sidewalk came out one grid step apart (a soak, after an edit 1.5 km away).
    std::vector<const SectionResult*> sections_by_key;
    for (const SectionResult& sec : result_.sections) {
      if (sec.surface) sections_by_key.push_back(&sec);
    }
    std::sort(sections_by_key.begin(), sections_by_key.end(), [](const SectionResult* a, const SectionResult* b) {
      return std::make_pair(a->axis_id, a->part) < std::make_pair(b->axis_id, b->part);
    });
    std::vector<const IntersectionResult*> junctions_by_key;
    for (const IntersectionResult& ir : result_.intersections) {
      if (ir.surface) junctions_by_key.push_back(&ir);
    }
    std::sort(junctions_by_key.begin(), junctions_by_key.end(),
              [](const IntersectionResult* a, const IntersectionResult* b) { return a->node_id < b->node_id; });
    for (const SectionResult* sec : sections_by_key) {
      geoms.push_back(sec->surface.get());
      layers.push_back(axis_layer_.at(sec->axis_id));
    }
    for (const IntersectionResult* ir : junctions_by_key) {
      geoms.push_back(ir->surface.get());
      layers.push_back(topo_.nodes[node_index.at(ir->node_id)].layer);
    }
    std::size_t first_claim = geoms.size();
    std::vector<Box> boxes(first_claim);
    for (std::size_t i = 0; i < first_claim; ++i) envelope_box(ctx_, geoms[i], boxes[i]);
    // Every claim built once for its box and its key, then dropped. A street side or a junction
    // corner makes one claim each.
    std::vector<ClaimSource> sources;
    std::size_t expected = 0;
    for (std::size_t e = 0; e < result_.sections.size(); ++e) {
      if (!result_.sections[e].surface) continue;
      for (int side = 0; side < 2; ++side) sources.push_back({e, side, kNoIntersection});
      expected += 2;
    }
    for (std::size_t j = 0; j < result_.intersections.size(); ++j) {
      if (!result_.intersections[j].surface) continue;
      sources.push_back({0, 0, j});
      expected += ends_of_node_[node_index.at(result_.intersections[j].node_id)].size();
    }
    struct Claim {
      ClaimKey meta;
      std::size_t source;
      int piece;
    };
    std::vector<Claim> claims;
    claims.reserve(expected);
    boxes.reserve(first_claim + expected);
    std::vector<Item> built;
    std::clock_t first_builds = std::clock();
    for (std::size_t s = 0; s < sources.size(); ++s) {
      poller.tick();
      built.clear();
      build_claims(sources[s], node_index, built, true);
      for (const Item& it : built) {
        Box box;
        envelope_box(ctx_, it.geom, box);
        boxes.push_back(box);
        layers.push_back(it.layer);
        claims.push_back({it.meta, s, it.piece});
      }
    }
    result_.stats.sidewalk_claim_builds = static_cast<double>(std::clock() - first_builds) / CLOCKS_PER_SEC;
    // Key order: sections' (axis, part, left before right), then junctions' by node id (a
    // junction's corners in turn). The boxes and layers follow their claims.
    {
      std::vector<std::size_t> key_order(claims.size());
      for (std::size_t c = 0; c < key_order.size(); ++c) key_order[c] = c;
      std::sort(key_order.begin(), key_order.end(), [&](std::size_t i, std::size_t j) {
        const Claim& a = claims[i];
        const Claim& b = claims[j];
        bool ja = a.meta.node_id != 0, jb = b.meta.node_id != 0;
        return std::make_tuple(ja, a.meta.node_id, a.piece, a.meta.axis_id, a.meta.part, a.meta.side) <
               std::make_tuple(jb, b.meta.node_id, b.piece, b.meta.axis_id, b.meta.part, b.meta.side);
      });
      std::vector<Claim> sorted;
      sorted.reserve(claims.size());
      std::vector<Box> claim_boxes(boxes.begin() + static_cast<std::ptrdiff_t>(first_claim), boxes.end());
      std::vector<int> claim_layers(layers.begin() + static_cast<std::ptrdiff_t>(first_claim), layers.end());
      for (std::size_t c = 0; c < key_order.size(); ++c) {
        sorted.push_back(claims[key_order[c]]);
        boxes[first_claim + c] = claim_boxes[key_order[c]];
        layers[first_claim + c] = claim_layers[key_order[c]];
      }
      claims.swap(sorted);
    }
    geoms.resize(first_claim + claims.size(), nullptr);
    // A source's claims lie together in key order (a junction's corners follow each other):
    // the groups, each one sidewalk, in key order.
    struct Group {
      std::size_t first, last;  // claims [first, last) by index
      bool built = false;
    };
    std::vector<Group> groups;
    std::vector<std::size_t> group_of(claims.size(), 0);
    for (std::size_t c = 0; c < claims.size(); ++c) {
      std::size_t i = first_claim + c;
      if (c == 0 || claims[c].source != claims[c - 1].source) groups.push_back({i, i});
      groups.back().last = i + 1;
      group_of[c] = groups.size() - 1;
    }
    // What each claim must give way to: roadways, and claims before it, on its layer.
    std::vector<std::vector<std::size_t>> blockers(geoms.size());
    for_each_overlapping_pair(boxes, [&](std::size_t i, std::size_t j) {
      if (layers[i] != layers[j]) return;
      std::size_t lo = std::min(i, j), hi = std::max(i, j);
      if (hi < first_claim) return;  // two roadways
      blockers[hi].push_back(lo);     // a roadway (lo < first_claim) or an earlier claim
    });
    std::vector<Box> group_boxes(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g) {
      Box& box = group_boxes[g];
      box = boxes[groups[g].first];
      for (std::size_t i = groups[g].first + 1; i < groups[g].last; ++i) {
        box = {std::min(box.xmin, boxes[i].xmin), std::min(box.ymin, boxes[i].ymin), std::max(box.xmax, boxes[i].xmax),
               std::max(box.ymax, boxes[i].ymax)};
      }
    }
    std::vector<Box>().swap(boxes);
    std::vector<int>().swap(layers);
    // A claim is held (built again, in `held`) from the first turn that needs it until its own
    // turn and the turns of the claims it blocks are done.
    std::vector<std::size_t> uses(geoms.size(), 0);
    for (std::size_t i = first_claim; i < geoms.size(); ++i) {
      ++uses[i];
      for (std::size_t b : blockers[i]) {
        if (b >= first_claim) ++uses[b];
      }
    }
    std::vector<std::unique_ptr<Item>> held(claims.size());
    long held_count = 0;
    result_.stats.sidewalk_claims = static_cast<long>(claims.size());
    auto release = [&](std::size_t i) {
      if (i >= first_claim && --uses[i] == 0 && held[i - first_claim]) {
        held[i - first_claim].reset();
        geoms[i] = nullptr;
        --held_count;
      }
    };
    auto ensure_built = [&](Group& g) {
      if (g.built) return;
      g.built = true;
      built.clear();
      build_claims(sources[claims[g.first - first_claim].source], node_index, built, false);
      // (the same inputs build the same claims: anything else is a bug, not bad input)
      if (built.size() != g.last - g.first) {
        throw Error(ErrorKind::internal, "sidewalk claim built again differs from its first build");
      }
      for (std::size_t k = 0; k < built.size(); ++k) {
        std::size_t i = g.first + k;
        if (built[k].piece != claims[i - first_claim].piece) {
          throw Error(ErrorKind::internal, "sidewalk claim built again differs from its first build");
        }
        held[i - first_claim] = std::make_unique<Item>(std::move(built[k]));
        geoms[i] = held[i - first_claim]->geom;
      }
      held_count += static_cast<long>(built.size());
      result_.stats.sidewalk_claims_held_peak = std::max(result_.stats.sidewalk_claims_held_peak, held_count);
    };
    // Sidewalks and failures as they come, each with its claim's index: put back in key order
    // at the end, as the rows have always come (the sidewalks in place: a second vector of them
    // was the engine's peak).
    std::vector<SidewalkResult>& sidewalks = result_.sidewalks;
    std::vector<std::size_t> sidewalk_claim;
    std::vector<std::pair<std::size_t, TopologyIssue>> failures;
    sidewalks.reserve(groups.size());
    sidewalk_claim.reserve(groups.size());
    std::vector<GeomPtr> junction_parts;
    for (std::size_t g : hilbert_order(group_boxes)) {
      poller.tick();
      Group& group = groups[g];
      ensure_built(group);
      for (std::size_t i = group.first; i < group.last; ++i) {
        for (std::size_t b : blockers[i]) {
          if (b >= first_claim) ensure_built(groups[group_of[b - first_claim]]);
        }
      }
      bool junction = claims[group.first - first_claim].piece > 0;
      SidewalkResult junction_sidewalk;
      junction_parts.clear();
      for (std::size_t i = group.first; i < group.last; ++i) {
        const Item& it = *held[i - first_claim];
        try {
          GeomPtr surface = sidewalk_of(it, blockers[i], geoms);
          if (!surface) continue;
          if (junction) {
            junction_sidewalk.node_id = it.meta.node_id;
            junction_sidewalk.side = std::string(it.meta.side);
            junction_sidewalk.width = std::max(junction_sidewalk.width, it.meta.width);
            append_polygons(ctx_, surface.get(), junction_parts);
            continue;
          }
          SidewalkResult sidewalk = it.meta.result();
          sidewalk.surface = std::move(surface);
          hand_over(sidewalk.surface, sidewalk.ewkb);
          sidewalks.push_back(std::move(sidewalk));
          sidewalk_claim.push_back(group.first);
        } catch (const Error& err) {
          if (err.kind() != ErrorKind::geometry_engine) throw;
          failures.emplace_back(i, sidewalk_failure(it.meta.result(), err, node_index));
        }
      }
      if (!junction_parts.empty()) {
        try {
          if (GeomPtr surface = junction_surface(junction_parts)) {
            junction_sidewalk.surface = std::move(surface);
            hand_over(junction_sidewalk.surface, junction_sidewalk.ewkb);
            sidewalks.push_back(std::move(junction_sidewalk));
            sidewalk_claim.push_back(group.first);
          }
        } catch (const Error& err) {
          if (err.kind() != ErrorKind::geometry_engine) throw;
          // (after its pieces' failures, as when the junction was emitted at the next claim)
          failures.emplace_back(group.last - 1, sidewalk_failure(junction_sidewalk, err, node_index));
        }
      }
      for (std::size_t i = group.first; i < group.last; ++i) {
        for (std::size_t b : blockers[i]) release(b);
        release(i);
        std::vector<std::size_t>().swap(blockers[i]);
      }
    }
    apply_order(sidewalks, stable_order(sidewalk_claim));
    auto by_index = [](const auto& a, const auto& b) { return a.first < b.first; };
    std::stable_sort(failures.begin(), failures.end(), by_index);
    for (auto& f : failures) result_.issues.push_back(std::move(f.second));
  }

  // Where a group of sidewalk claims comes from: a street side (section index, side) or a
  // junction (intersection index).
  static constexpr std::size_t kNoIntersection = static_cast<std::size_t>(-1);
  struct ClaimSource {
    std::size_t section;
    int side;
    std::size_t intersection;  // kNoIntersection for a street side
  };

  // Appends the claims of `source` to `out`: a street side's band, a junction's corner pieces or
  // its buffer. `first_build` counts them and reports failures; a build again does neither.
  void build_claims(const ClaimSource& source, const std::map<std::int64_t, std::size_t>& node_index,
                    std::vector<SidewalkItem>& out, bool first_build) {
    using Item = SidewalkItem;
    if (source.intersection == kNoIntersection) {
      std::size_t e = source.section;
      const SectionResult& sec = result_.sections[e];
      const SurfaceAxis& axis = axes_[topo_.edges[e].axis_index];
      int side = source.side;
      double w = side == 0 ? axis.sidewalk_left : axis.sidewalk_right;
      if (!(w > 0.0)) return;
      try {
        Polyline between = substring(sec.centre_line, sec.start_border, sec.end_border);
        GeomPtr line = make_line(ctx_, between);
        // The roadway's side extent (street parking shifts it off the axis), then the sidewalk.
        double shift = plans_[topo_.edges[e].axis_index].centre_offset;
        double d = axis.roadway_width / 2 + (side == 0 ? shift : -shift) + w;
        Item it;
        // (a section as built: outside its roadway's side, a band of its own; else the
        // buffer from the axis, which loses the roadway by an overlay)
        if (sec.status == "ok") {
          Polyline edge = roadway_side(sec.surface.get(), between, side == 0 ? +1 : -1);
          if (edge.size() >= 2) it.owned = side_band(edge, side == 0 ? w : -w);
          it.own_ring = it.owned != nullptr;
        }
        if (!it.owned) it.owned = single_sided_buffer(ctx_, line.get(), side == 0 ? d : -d);
        if (GEOSisValid_r(ctx_.handle(), it.owned.get()) != 1) {
          it.own_ring = false;
          // (its polygons only: a made-valid buffer can hold lines, and an overlay refuses
          // input of mixed dimension)
          GeomPtr fixed = own(ctx_, GEOSMakeValid_r(ctx_.handle(), it.owned.get()), "make valid");
          it.owned = polygons_of(ctx_, fixed.get(), 0.0);
          if (!it.owned) return;
        }
        it.geom = it.owned.get();
        it.layer = axis.layer;
        it.cut_point[0] = between.front();
        it.cut_direction[0] = unit(between[1] - between[0]);
        it.cut_point[1] = between.back();
        it.cut_direction[1] = unit(between[between.size() - 2] - between.back());
        for (int k = 0; k < 2; ++k) {  // (a zero direction, from repeated points, would pass any test)
          it.cuts[k] = norm(it.cut_direction[k]) > 0.5 && beyond_line(it.geom, it.cut_point[k], it.cut_direction[k]);
        }
        it.meta.axis_id = sec.axis_id;
        it.meta.part = sec.part;
        it.meta.side = side == 0 ? "left" : "right";
        it.meta.width = w;
        out.push_back(std::move(it));
      } catch (const Error& err) {
        if (err.kind() != ErrorKind::geometry_engine) throw;
        if (first_build) {
          result_.issues.push_back({sec.axis_id, "sidewalk_failed", err.what() + std::string(": ") + err.detail(), sec.part});
        }
      }
      return;
    }
    const IntersectionResult& ir = result_.intersections[source.intersection];
    std::size_t n = node_index.at(ir.node_id);
    // (a junction as built, not narrowed, repaired or a transition: its curb is its ring)
    long buffered_corners = 0;
    if (ir.status == "ok" && add_corner_claims(n, ir.node_id, out, buffered_corners)) {
      if (first_build) {
        ++result_.stats.junction_sidewalks_by_corner;
        result_.stats.junction_corners_by_buffer += buffered_corners;
      }
      return;
    }
    double w = 0.0;
    for (const End& e : ends_of_node_[n]) {
      const SurfaceAxis& axis = axes_[topo_.edges[e.edge].axis_index];
      w = std::max({w, axis.sidewalk_left, axis.sidewalk_right});
    }
    if (!(w > 0.0)) return;
    if (first_build) ++result_.stats.junction_sidewalks_by_buffer;
    Item it;
    it.owned = own(ctx_, GEOSBufferWithStyle_r(ctx_.handle(), ir.surface.get(), w, kQuadrantSegments, GEOSBUF_CAP_ROUND,
                                               GEOSBUF_JOIN_ROUND, 5.0),
                   "junction sidewalk buffer");
    it.geom = it.owned.get();
    it.layer = topo_.nodes[n].layer;
    it.meta.node_id = ir.node_id;
    it.meta.side = "around";
    it.meta.width = w;
    out.push_back(std::move(it));
  }

  // A junction's sidewalk from its corners' pieces: one multipolygon.
  GeomPtr junction_surface(std::vector<GeomPtr>& parts) {
    GeomPtr surface = make_collection(ctx_, GEOS_MULTIPOLYGON, parts);
    parts.clear();
    // (corner bands do not overlap and lie apart, the streets between them; a difference
    // could still leave two touching along an edge, which one multipolygon may not)
    if (GEOSisValid_r(ctx_.handle(), surface.get()) != 1) {
      GeomPtr united = own(ctx_, GEOSUnaryUnion_r(ctx_.handle(), surface.get()), "union");
      surface = polygons_of(ctx_, united.get(), kMinSidewalkArea);
    }
    return surface;
  }

  TopologyIssue sidewalk_failure(const SidewalkResult& meta, const Error& err, const std::map<std::int64_t, std::size_t>& node_index) {
    std::string detail = err.what() + std::string(": ") + err.detail();
    if (meta.node_id == 0) return {meta.axis_id, "sidewalk_failed", detail, meta.part};
    // a junction's: about the node, under its first axis
    const TopologyNode& node = topo_.nodes[node_index.at(meta.node_id)];
    return {node.axis_ids.front(), "sidewalk_failed", detail, std::nullopt, node.id};
  }

  // What is left of claim `it` once every roadway of its layer and every claim before it that
  // it meets (of `blockers`, by box) are taken away: its sidewalk, or null.
  GeomPtr sidewalk_of(const SidewalkItem& it, std::vector<std::size_t>& blockers, const std::vector<const GEOSGeometry*>& geoms) {
    // Boxes overlap far more often than shapes (long diagonal streets): only what the claim
    // really meets is taken away (a predicate that fails counts as meeting).
    std::vector<const GEOSGeometry*> meeting;
    Polyline ring;
    if (it.own_ring) ring = shells_of(it.geom).front();
    if (!blockers.empty()) {
      std::sort(blockers.begin(), blockers.end());
      const GEOSPreparedGeometry* prepared = nullptr;
      if (!it.own_ring) {
        prepared = GEOSPrepare_r(ctx_.handle(), it.geom);
        if (prepared == nullptr) ctx_.fail("prepare");
      }
      for (std::size_t b : blockers) {
        // (a junction's roadway touches a street side's claim along the border line, and
        // a difference with it took nothing away: 89,000 of the street sides' 170,000
        // floating differences on Paris. A line with the claim on one side and the blocker
        // on the other shows that without an overlay.)
        if ((it.cuts[0] && beyond_line(geoms[b], it.cut_point[0], -1.0 * it.cut_direction[0])) ||
            (it.cuts[1] && beyond_line(geoms[b], it.cut_point[1], -1.0 * it.cut_direction[1]))) {
          continue;
        }
        if (prepared == nullptr) {  // a band of its own shape: exactly, against the blocker's rings
          if (claim_may_meet(ring, geoms[b])) meeting.push_back(geoms[b]);
          continue;
        }
        char meets = GEOSPreparedIntersects_r(ctx_.handle(), prepared, geoms[b]);
        if (meets == 2) ctx_.clear_error();
        if (meets != 0) meeting.push_back(geoms[b]);
      }
      if (prepared != nullptr) GEOSPreparedGeom_destroy_r(ctx_.handle(), prepared);
    }
    // A corner's band that meets nothing is its own ring on the grid.
    if (meeting.empty() && it.own_ring) {
      if (GeomPtr rounded = rounded_polygon(ring)) {
        ++result_.stats.sidewalks_without_overlay;
        return polygons_of(ctx_, rounded.get(), kMinSidewalkArea);
      }
    }
    GeomPtr rest = own(ctx_, GEOSGeom_clone_r(ctx_.handle(), it.geom), "clone");
    // One blocker after another, not their union: a difference clips the blocker to the
    // claim's box before it nodes anything (a union has no such envelope, and a long
    // street's roadway or a large junction's sidewalk would be united whole for every claim
    // along it). The last step is snap-rounded on the micrometre grid, and so is a claim
    // nothing blocks: an overlay can leave a sliver nanometres wide along an edge it nearly
    // shares, present or not as the roadways around differ in their last bits (a local
    // refresh and a full run then disagreed by 2.75 m of sliver, 1e-8 m2); snap rounding
    // collapses such slivers, those of the floating steps before it included, and gives
    // valid output. (A union of the blockers in floating precision once had a zero-area
    // hole through a vertex of the claim, and the whole claim came back: pgTAP 62.)
    for (std::size_t k = 0; k < meeting.size() && rest; ++k) {
      rest = k + 1 < meeting.size()
                 ? difference_by_part(std::move(rest), meeting[k])
                 : own(ctx_, GEOSDifferencePrec_r(ctx_.handle(), rest.get(), meeting[k], kSidewalkGrid), "difference");
      if (!rest) break;
      // (a floating difference can leave a collapsed edge as a line beside the polygons, and
      // the next overlay would refuse input of mixed dimension)
      int type = GEOSGeomTypeId_r(ctx_.handle(), rest.get());
      if (type != GEOS_POLYGON && type != GEOS_MULTIPOLYGON) rest = polygons_of(ctx_, rest.get(), 0.0);
    }
    if (!rest) return nullptr;
    if (meeting.empty()) {
      rest = own(ctx_, GEOSGeom_setPrecision_r(ctx_.handle(), rest.get(), kSidewalkGrid, 0), "sidewalk grid");
    }
    GeomPtr surface = polygons_of(ctx_, rest.get(), kMinSidewalkArea);
    if (!surface) return nullptr;
    if (GEOSisValid_r(ctx_.handle(), surface.get()) != 1) {
      GeomPtr fixed = own(ctx_, GEOSMakeValid_r(ctx_.handle(), surface.get()), "make valid");
      surface = polygons_of(ctx_, fixed.get(), kMinSidewalkArea);
    }
    return surface;
  }

  // Whether every vertex of `g` lies on the side of the line through `p` across `direction`
  // that `direction` points to, or on the line up to kOnCutLine. Two geometries beyond the same
  // line from either side can share at most a strip 2 kOnCutLine wide, far below the sidewalk grid.
  bool beyond_line(const GEOSGeometry* g, Point p, Point direction) {
    GEOSContextHandle_t h = ctx_.handle();
    auto ring_beyond = [&](const GEOSGeometry* ring) {
      const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(h, ring);
      unsigned int n = 0;
      if (seq == nullptr || GEOSCoordSeq_getSize_r(h, seq, &n) == 0) ctx_.fail("coordinates");
      for (unsigned int i = 0; i < n; ++i) {
        Point q;
        if (GEOSCoordSeq_getXY_r(h, seq, i, &q.x, &q.y) == 0) ctx_.fail("coordinates");
        if (dot(q - p, direction) < -kOnCutLine) return false;
      }
      return true;
    };
    auto polygon_beyond = [&](const GEOSGeometry* polygon) {
      const GEOSGeometry* shell = GEOSGetExteriorRing_r(h, polygon);
      return shell != nullptr && ring_beyond(shell);  // (the holes lie inside the shell)
    };
    int type = GEOSGeomTypeId_r(h, g);
    if (type == GEOS_POLYGON) return polygon_beyond(g);
    if (type != GEOS_MULTIPOLYGON) return false;
    int n = GEOSGetNumGeometries_r(h, g);
    for (int i = 0; i < n; ++i) {
      if (!polygon_beyond(GEOSGetGeometryN_r(h, g, i))) return false;
    }
    return true;
  }

  // `rest` minus `blocker`, in floating point, part by part: once a junction's own roadway and
  // its streets' roadways are taken from its claim, the claim is a handful of corner pieces and
  // each later blocker (a street's side claim) meets one or two of them. Parts whose box misses
  // the blocker's are kept as they are and only the others go through the overlay, instead of
  // noding every part again for each blocker (Paris: 243,000 differences for 21,675 junction
  // claims; the engine 49.8 s -> 46.1 s of CPU). Null when nothing is left.
  GeomPtr difference_by_part(GeomPtr rest, const GEOSGeometry* blocker) {
    GEOSContextHandle_t h = ctx_.handle();
    if (GEOSGeomTypeId_r(h, rest.get()) != GEOS_MULTIPOLYGON || GEOSGetNumGeometries_r(h, rest.get()) < 2) {
      return own(ctx_, GEOSDifference_r(h, rest.get(), blocker), "difference");
    }
    Box reach;
    envelope_box(ctx_, blocker, reach);
    std::vector<GeomPtr> parts;
    int n = GEOSGetNumGeometries_r(h, rest.get());
    for (int i = 0; i < n; ++i) {
      const GEOSGeometry* part = GEOSGetGeometryN_r(h, rest.get(), i);
      Box box;
      envelope_box(ctx_, part, box);
      if (box.xmax < reach.xmin || box.xmin > reach.xmax || box.ymax < reach.ymin || box.ymin > reach.ymax) {
        append_polygons(ctx_, part, parts);
        continue;
      }
      GeomPtr left = own(ctx_, GEOSDifference_r(h, part, blocker), "difference");
      append_polygons(ctx_, left.get(), parts);
    }
    if (parts.empty()) return nullptr;
    if (parts.size() == 1) return std::move(parts.front());
    // (the parts are disjoint pieces of one valid MultiPolygon, each cut on its own: still one)
    return make_collection(ctx_, GEOS_MULTIPOLYGON, parts);
  }

  // How far from its axis an axis' roadway reaches, on its wider side.
  double reach_of(std::int64_t axis_id) const {
    std::size_t i = axis_index_.at(axis_id);
    return axes_[i].roadway_width / 2 + std::abs(plans_[i].centre_offset);
  }

  // The roadway along `centre`, `left` and `right` of it, with flat ends on the normals at its
  // ends: a buffer, of the centre line shifted by the offset where the sides differ (GEOS offset
  // curves keep polylines' bends; a plain translation would not).
  GeomPtr roadway_polygon(const Polyline& centre, double left, double right, const char* what) {
    GeomPtr line = make_line(ctx_, centre);
    double shift = (left - right) / 2;
    if (std::abs(shift) > 1e-9) {
      GEOSGeometry* shifted = GEOSOffsetCurve_r(ctx_.handle(), line.get(), shift, kQuadrantSegments, GEOSBUF_JOIN_ROUND, 5.0);
      if (shifted != nullptr && GEOSGeomTypeId_r(ctx_.handle(), shifted) == GEOS_LINESTRING && GEOSisEmpty_r(ctx_.handle(), shifted) == 0) {
        line.reset(shifted);
      } else {
        // (GEOS may give up on the offset of a short, sharply bent piece: the roadway then stays
        // centred on the axis, as wide, rather than spill beyond its narrower side)
        if (shifted != nullptr) GEOSGeom_destroy_r(ctx_.handle(), shifted);
        ctx_.clear_error();
      }
    }
    return own(ctx_, GEOSBufferWithStyle_r(ctx_.handle(), line.get(), (left + right) / 2, kQuadrantSegments,
                                           GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_ROUND, 5.0), what);
  }

  void build_section(std::size_t e) {
    const TopologyEdge& edge = topo_.edges[e];
    const SurfaceAxis& axis = axes_[edge.axis_index];
    SectionResult sr;
    sr.axis_id = edge.axis_id;
    sr.part = edge.part;
    sr.from_node = topo_.nodes[edge.from_node].id;
    sr.to_node = topo_.nodes[edge.to_node].id;
    sr.centre_line = edge.line;
    double len = length(edge.line);
    sr.start_border = border_[e].first;
    sr.end_border = len - border_[e].second;
    if (edge.duplicate) {
      sr.status = "duplicate";
    } else if (sr.end_border - sr.start_border <= 1e-6) {
      sr.status = "absorbed";
    } else {
      sr.status = "ok";
      Polyline centre = substring(edge.line, sr.start_border, sr.end_border);
      double left = axis.roadway_width / 2 + plans_[edge.axis_index].centre_offset;
      GeomPtr buffer = roadway_polygon(centre, left, axis.roadway_width - left, "section buffer");
      // GEOS can leave slivers beside a flat-capped buffer of a short piece with a bend: the
      // section is the part on its axis.
      if (GEOSGeomTypeId_r(ctx_.handle(), buffer.get()) != GEOS_POLYGON) {
        buffer = pick_polygon(ctx_, buffer.get(), point_at(centre, 0.5 * length(centre)));
      }
      sr.surface = std::move(buffer);
    }
    result_.sections.push_back(std::move(sr));
  }

  GeosContext& ctx_;
  const std::vector<SurfaceAxis>& axes_;
  const std::vector<CornerOverride>& overrides_;
  const SurfaceSettings& s_;
  const SurfaceOutput& output_;
  PhaseClock clock_;
  Topology topo_;
  std::vector<std::vector<End>> ends_of_node_;
  std::vector<std::pair<double, double>> border_;  // per edge: border abscissa at its start, at its end
  // Node n's corners are result_.corners[corner_first_[n], corner_first_[n + 1]): built node by
  // node in node order, they are the result's corners as they are (a vector per node, moved into
  // one at the end, held them twice at the engine's peak; Reisterstown: 3.5 MB).
  std::vector<std::size_t> corner_first_;
  std::vector<bool> transition_;
  std::map<std::pair<std::int64_t, std::int64_t>, const GEOSGeometry*> section_surface_;
  std::vector<std::size_t> junction_node_;  // per result_.intersections entry: its node's index
  std::map<std::int64_t, int> axis_layer_;
  std::map<std::int64_t, std::size_t> axis_index_;
  std::vector<LanePlan> plans_;  // per axis, as axes_
  SurfaceResult result_;
};

}  // namespace

double radius_for_speed(const SurfaceSettings& settings, double speed_kmh) {
  double v = settings.turn_speed_ratio * speed_kmh / 3.6;
  double r = v * v / settings.lateral_acceleration;
  return std::clamp(r, settings.min_radius, std::max(settings.min_radius, settings.max_radius));
}

namespace {

void check_inputs(const std::vector<SurfaceAxis>& axes, const std::vector<CornerOverride>& corner_overrides,
                  const SurfaceSettings& settings) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!(std::isfinite(settings.snap_tolerance) && settings.snap_tolerance >= 0.0) || !positive(settings.min_radius) ||
      !positive(settings.max_radius) || !positive(settings.turn_speed_ratio) || !positive(settings.lateral_acceleration) ||
      !positive(settings.misplaced_factor) || !(std::isfinite(settings.min_border_distance) && settings.min_border_distance >= 0.0) ||
      !positive(settings.transition_length_per_metre) || !(std::isfinite(settings.min_transition_length) && settings.min_transition_length >= 0.0) ||
      !(std::isfinite(settings.crossing_width) && settings.crossing_width >= 0.0) ||
      !(std::isfinite(settings.crossing_max_speed_kmh) && settings.crossing_max_speed_kmh >= 0.0)) {
    throw_invalid_argument("street surface settings must be finite and positive");
  }
  for (const SurfaceAxis& a : axes) check_axis(a);
  for (const CornerOverride& o : corner_overrides) {
    if (!positive(o.radius)) throw_invalid_argument("corner radius overrides must be finite numbers > 0");
  }
}

}  // namespace

SurfaceResult street_surfaces(GeosContext& ctx, const std::vector<SurfaceAxis>& axes,
                              const std::vector<CornerOverride>& corner_overrides, const SurfaceSettings& settings,
                              const SurfaceOutput& output) {
  check_inputs(axes, corner_overrides, settings);
  return SurfaceBuilder(ctx, axes, corner_overrides, settings, output).run();
}

struct SurfaceRun::State {
  State(GeosContext& ctx, std::vector<SurfaceAxis> a, std::vector<CornerOverride> o, const SurfaceSettings& s,
        const SurfaceOutput& out)
      : axes(std::move(a)), overrides(std::move(o)), settings(s), output(out), builder(ctx, axes, overrides, settings, output) {}
  std::vector<SurfaceAxis> axes;
  std::vector<CornerOverride> overrides;
  SurfaceSettings settings;
  SurfaceOutput output;
  SurfaceBuilder builder;  // (last: it refers to the members above)
};

SurfaceRun::SurfaceRun(GeosContext& ctx, std::vector<SurfaceAxis> axes, std::vector<CornerOverride> corner_overrides,
                       const SurfaceSettings& settings, const SurfaceOutput& output) {
  check_inputs(axes, corner_overrides, settings);
  state_ = std::make_unique<State>(ctx, std::move(axes), std::move(corner_overrides), settings, output);
}

SurfaceRun::~SurfaceRun() = default;

void SurfaceRun::through_lanes() { state_->builder.through_lanes(); }
std::vector<LaneResult>& SurfaceRun::lanes() { return state_->builder.lanes(); }
std::vector<MarkingResult>& SurfaceRun::markings() { return state_->builder.markings(); }
SurfaceResult SurfaceRun::finish() { return state_->builder.finish(); }

}  // namespace streetgen::core
