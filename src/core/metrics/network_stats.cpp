#include "core/metrics/network_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "core/interrupts.hpp"

namespace streetgen::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

const std::array<MetricInfo, kMetricCount> kTable = {{
    {"node_count", true, false},
    {"edge_count", true, false},
    {"duplicate_edges", true, false},
    {"collapsed_edges", true, false},
    {"component_count", true, false},
    {"largest_component_share", false, false},
    {"total_length", false, false},
    {"area", false, false},
    {"node_density", false, false},
    {"intersection_count", true, false},
    {"intersection_density", false, true},
    {"street_density", false, true},
    {"mean_degree", false, true},
    {"dead_end_share", false, true},
    {"degree2_share", false, false},
    {"degree3_share", false, false},
    {"degree4_share", false, true},
    {"degree5plus_share", false, false},
    {"connected_node_ratio", false, true},
    {"mean_segment_length", false, false},
    {"circuity", false, false},
    {"orientation_entropy", false, false},
    {"orientation_order", false, true},
    {"block_count", true, false},
    {"block_area_p25", false, false},
    {"block_area_median", false, true},
    {"block_area_p75", false, false},
    {"block_area_mean", false, false},
    {"block_compactness_p25", false, false},
    {"block_compactness_median", false, false},
    {"block_compactness_p75", false, false},
    {"block_aspect_ratio_p25", false, false},
    {"block_aspect_ratio_median", false, false},
    {"block_aspect_ratio_p75", false, false},
}};

double ratio(double num, double den) { return den > 0.0 ? num / den : kNaN; }

// Andrew's monotone chain; returns the area of the convex hull of the points.
double convex_hull_area(std::vector<Point> pts) {
  std::sort(pts.begin(), pts.end(), [](Point a, Point b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end(), [](Point a, Point b) { return a.x == b.x && a.y == b.y; }), pts.end());
  if (pts.size() < 3) return 0.0;
  std::vector<Point> hull(2 * pts.size());
  std::size_t k = 0;
  auto turn = [](Point o, Point a, Point b) { return cross(a - o, b - o); };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Point& p = hull[i];
    const Point& q = hull[(i + 1) % hull.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return std::abs(twice) / 2.0;
}

GeomPtr make_line(GeosContext& geos, const Polyline& line) {
  std::vector<double> xy;
  xy.reserve(2 * line.size());
  for (const Point& p : line) {
    xy.push_back(p.x);
    xy.push_back(p.y);
  }
  GEOSCoordSequence* seq = GEOSCoordSeq_copyFromBuffer_r(geos.handle(), xy.data(), line.size(), 0, 0);
  if (seq == nullptr) geos.fail("coordinate sequence");
  return own(geos, GEOSGeom_createLineString_r(geos.handle(), seq), "line construction");
}

struct PreparedDeleter {
  GEOSContextHandle_t handle = nullptr;
  void operator()(const GEOSPreparedGeometry* p) const noexcept {
    if (p != nullptr) GEOSPreparedGeom_destroy_r(handle, p);
  }
};
using PreparedPtr = std::unique_ptr<const GEOSPreparedGeometry, PreparedDeleter>;

bool predicate(GeosContext& geos, char result, const char* operation) {
  if (result == 2) geos.fail(operation);
  return result == 1;
}

// Bin of a bearing (degrees in [0, 360)) in OSMnx's layout: bin i covers [10 i - 5, 10 i + 5).
void summarise(std::vector<double> values, NetworkStats& s, Metric p25, Metric median, Metric p75) {
  std::sort(values.begin(), values.end());
  s[p25] = quantile_sorted(values, 0.25);
  s[median] = quantile_sorted(values, 0.5);
  s[p75] = quantile_sorted(values, 0.75);
}

void compute_blocks(GeosContext& geos, const NetworkGraph& graph, const GEOSPreparedGeometry* window, NetworkStats& s) {
  GEOSContextHandle_t h = geos.handle();
  std::vector<GeomPtr> lines;
  lines.reserve(graph.edges.size());
  InterruptPoller poller(1024);
  for (const NetworkEdge& e : graph.edges) {
    poller.tick();
    lines.push_back(make_line(geos, e.line));
  }
  std::vector<const GEOSGeometry*> raw(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) raw[i] = lines[i].get();
  poll_interrupts();
  GeomPtr faces = own(geos, GEOSPolygonize_r(h, raw.data(), static_cast<unsigned>(raw.size())), "polygonize");
  lines.clear();
  int n = GEOSGetNumGeometries_r(h, faces.get());
  for (int i = 0; i < n; ++i) {
    poller.tick();
    const GEOSGeometry* face = GEOSGetGeometryN_r(h, faces.get(), i);
    if (window != nullptr && !predicate(geos, GEOSPreparedContains_r(h, window, face), "window test")) continue;
    double area = 0.0, perimeter = 0.0;
    if (GEOSArea_r(h, face, &area) == 0) geos.fail("area");
    const GEOSGeometry* shell = GEOSGetExteriorRing_r(h, face);
    if (shell == nullptr || GEOSGeomGetLength_r(h, shell, &perimeter) == 0) geos.fail("perimeter");
    if (!(area > 0.0) || !(perimeter > 0.0)) continue;
    double aspect = kNaN;
    GeomPtr rect = own(geos, GEOSMinimumRotatedRectangle_r(h, face), "minimum rotated rectangle");
    if (GEOSGeomTypeId_r(h, rect.get()) == GEOS_POLYGON) {
      const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(h, GEOSGetExteriorRing_r(h, rect.get()));
      double x[3], y[3];
      for (unsigned k = 0; k < 3; ++k) GEOSCoordSeq_getXY_r(h, seq, k, &x[k], &y[k]);
      double s1 = std::hypot(x[1] - x[0], y[1] - y[0]), s2 = std::hypot(x[2] - x[1], y[2] - y[1]);
      double lo = std::min(s1, s2), hi = std::max(s1, s2);
      if (lo > 0.0) aspect = hi / lo;
    }
    s.block_areas.push_back(area);
    s.block_compactness.push_back(4.0 * kPi * area / (perimeter * perimeter));
    if (!std::isnan(aspect)) s.block_aspect_ratios.push_back(aspect);
  }
  s[Metric::block_count] = static_cast<double>(s.block_areas.size());
  summarise(s.block_areas, s, Metric::block_area_p25, Metric::block_area_median, Metric::block_area_p75);
  s[Metric::block_area_mean] =
      s.block_areas.empty() ? kNaN
                            : std::accumulate(s.block_areas.begin(), s.block_areas.end(), 0.0) / s.block_areas.size();
  summarise(s.block_compactness, s, Metric::block_compactness_p25, Metric::block_compactness_median,
            Metric::block_compactness_p75);
  summarise(s.block_aspect_ratios, s, Metric::block_aspect_ratio_p25, Metric::block_aspect_ratio_median,
            Metric::block_aspect_ratio_p75);
}

}  // namespace

int orientation_bin(double bearing) {
  double shifted = std::fmod(bearing + 180.0 / kOrientationBins, 360.0);
  int bin = static_cast<int>(std::floor(shifted / (360.0 / kOrientationBins)));
  return std::clamp(bin, 0, kOrientationBins - 1);
}

double orientation_order_of_entropy(double entropy) {
  const double h_max = std::log(static_cast<double>(kOrientationBins)), h_grid = std::log(4.0);
  return 1.0 - std::pow((entropy - h_grid) / (h_max - h_grid), 2.0);
}

const std::array<MetricInfo, kMetricCount>& metric_table() { return kTable; }

double quantile_sorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return kNaN;
  double pos = q * static_cast<double>(sorted.size() - 1);
  std::size_t lo = static_cast<std::size_t>(std::floor(pos));
  std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  double t = pos - static_cast<double>(lo);
  return sorted[lo] + t * (sorted[hi] - sorted[lo]);
}

NetworkStats network_stats(GeosContext& geos, const NetworkGraph& graph, const NetworkStatsOptions& options) {
  GEOSContextHandle_t h = geos.handle();
  NetworkStats s;
  s.value.fill(kNaN);
  const std::size_t n = graph.nodes.size();
  InterruptPoller poller;

  PreparedPtr window(nullptr, PreparedDeleter{h});
  double window_area = 0.0;
  if (options.window != nullptr) {
    int type = GEOSGeomTypeId_r(h, options.window);
    if ((type != GEOS_POLYGON && type != GEOS_MULTIPOLYGON) || GEOSisEmpty_r(h, options.window) != 0) {
      throw_invalid_argument("window must be a non-empty Polygon or MultiPolygon");
    }
    if (GEOSArea_r(h, options.window, &window_area) == 0) geos.fail("window area");
    if (!(window_area > 0.0)) throw_invalid_argument("window must have a positive area");
    window.reset(GEOSPrepare_r(h, options.window));
    if (!window) geos.fail("window preparation");
  }

  // Which nodes count: all, or those in the window (each keeps its full degree).
  std::vector<char> inside(n, 1);
  if (window) {
    for (std::size_t v = 0; v < n; ++v) {
      poller.tick();
      GeomPtr pt = own(geos, GEOSGeom_createPointFromXY_r(h, graph.nodes[v].x, graph.nodes[v].y), "point");
      inside[v] = predicate(geos, GEOSPreparedIntersects_r(h, window.get(), pt.get()), "window test") ? 1 : 0;
    }
  }

  // Components over the whole graph.
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const NetworkEdge& e : graph.edges) {
    std::size_t a = find(e.a), b = find(e.b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::size_t> comp_size(n, 0);
  std::size_t components = 0, largest = 0;
  for (std::size_t v = 0; v < n; ++v) {
    std::size_t r = find(v);
    if (comp_size[r]++ == 0) ++components;
    largest = std::max(largest, comp_size[r]);
  }

  // Nodes.
  std::size_t counted = 0, by_degree[6] = {0, 0, 0, 0, 0, 0}, degree_sum = 0, intersections = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!inside[v]) continue;
    int d = graph.degree[v];
    ++counted;
    degree_sum += static_cast<std::size_t>(d);
    ++by_degree[std::min(d, 5)];
    if (d >= 2) ++intersections;
    s.degrees.push_back(d);
  }
  const double nodes = static_cast<double>(counted);
  const std::size_t junctions = by_degree[3] + by_degree[4] + by_degree[5];

  // Edges: lengths (clipped to the window), chords, orientations.
  double total_length = 0.0, circuit_length = 0.0, chord_total = 0.0;
  std::vector<double> bins(kOrientationBins, 0.0);
  std::vector<Point> hull_points;
  if (!window) {
    std::size_t total_vertices = 0;
    for (const NetworkEdge& e : graph.edges) total_vertices += e.line.size();
    hull_points.reserve(total_vertices);
  }
  for (const NetworkEdge& e : graph.edges) {
    poller.tick();
    double in_window = e.length;
    bool counts_whole = true;
    if (window) {
      counts_whole = inside[e.a] || inside[e.b];
      GeomPtr line = make_line(geos, e.line);
      if (!predicate(geos, GEOSPreparedContains_r(h, window.get(), line.get()), "window test")) {
        if (!predicate(geos, GEOSPreparedIntersects_r(h, window.get(), line.get()), "window test")) {
          in_window = 0.0;
        } else {
          GeomPtr part = own(geos, GEOSIntersection_r(h, options.window, line.get()), "window clip");
          if (GEOSLength_r(h, part.get(), &in_window) == 0) geos.fail("clipped length");  // may be a MultiLineString
        }
      }
    } else {
      hull_points.insert(hull_points.end(), e.line.begin(), e.line.end());
    }
    total_length += in_window;
    const Point pa = graph.nodes[e.a], pb = graph.nodes[e.b];
    if (counts_whole) {
      s.segment_lengths.push_back(e.length);
      circuit_length += e.length;
      chord_total += distance(pa, pb);
    }
    if (e.a != e.b && in_window > 0.0) {  // self-loops have no bearing (OSMnx ignores them too)
      double bearing = std::atan2(pb.x - pa.x, pb.y - pa.y) * 180.0 / kPi;  // clockwise from north (+y)
      bearing = std::fmod(bearing + 360.0, 360.0);
      bins[orientation_bin(bearing)] += in_window;
      bins[orientation_bin(std::fmod(bearing + 180.0, 360.0))] += in_window;
    }
  }
  const double area = window ? window_area : convex_hull_area(std::move(hull_points));
  const double area_km2 = area / 1e6;

  s[Metric::node_count] = nodes;
  s[Metric::edge_count] = static_cast<double>(s.segment_lengths.size());
  s[Metric::duplicate_edges] = static_cast<double>(graph.duplicate_edges);
  s[Metric::collapsed_edges] = static_cast<double>(graph.collapsed_edges);
  s[Metric::component_count] = static_cast<double>(components);
  s[Metric::largest_component_share] = ratio(static_cast<double>(largest), static_cast<double>(n));
  s[Metric::total_length] = total_length;
  s[Metric::area] = area;
  s[Metric::node_density] = ratio(nodes, area_km2);
  s[Metric::intersection_count] = static_cast<double>(intersections);
  s[Metric::intersection_density] = ratio(static_cast<double>(intersections), area_km2);
  s[Metric::street_density] = ratio(total_length / 1000.0, area_km2);
  s[Metric::mean_degree] = ratio(static_cast<double>(degree_sum), nodes);
  s[Metric::dead_end_share] = ratio(static_cast<double>(by_degree[1]), nodes);
  s[Metric::degree2_share] = ratio(static_cast<double>(by_degree[2]), nodes);
  s[Metric::degree3_share] = ratio(static_cast<double>(by_degree[3]), nodes);
  s[Metric::degree4_share] = ratio(static_cast<double>(by_degree[4]), nodes);
  s[Metric::degree5plus_share] = ratio(static_cast<double>(by_degree[5]), nodes);
  s[Metric::connected_node_ratio] =
      ratio(static_cast<double>(junctions), static_cast<double>(junctions + by_degree[1]));
  s[Metric::mean_segment_length] = ratio(circuit_length, static_cast<double>(s.segment_lengths.size()));
  s[Metric::circuity] = ratio(circuit_length, chord_total);

  const double weight = std::accumulate(bins.begin(), bins.end(), 0.0);
  if (weight > 0.0) {
    double entropy = 0.0;
    s.orientation_histogram.resize(kOrientationBins);
    for (int i = 0; i < kOrientationBins; ++i) {
      double p = bins[i] / weight;
      s.orientation_histogram[i] = p;
      if (p > 0.0) entropy -= p * std::log(p);
    }
    s[Metric::orientation_entropy] = entropy;
    s[Metric::orientation_order] = orientation_order_of_entropy(entropy);
  }

  if (options.blocks) {
    compute_blocks(geos, graph, window.get(), s);
  }
  return s;
}

}  // namespace streetgen::core
