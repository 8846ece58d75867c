// Street network statistics with OSMnx's definitions (Boeing 2017, 2019) plus Connected Node
// Ratio, dead-end share and block shape distributions, computed in one pass over a NetworkGraph.
// The same code serves streetgen.network_stats in SQL and the growth benchmarks.
//
// Definitions (undirected graph, lengths in metres, areas in m²):
//   mean_degree          2 E / N (= OSMnx streets_per_node_avg; OSMnx's k_avg is directed)
//   intersection_count   nodes with >= 2 streets (OSMnx intersection_count)
//   street_density       total length (km) / area (km²); area: the window, else the convex hull
//   circuity             sum of edge lengths / sum of straight distances between edge end nodes
//   orientation          bearing of the straight line between an edge's end nodes, counted both
//                        ways, weighted by length, 36 bins of 10° centred on 0°, 10°, ... (OSMnx)
//   orientation_order    φ = 1 - ((H - ln 4) / (ln 36 - ln 4))² (Boeing 2019)
//   connected_node_ratio nodes of degree >= 3 / (nodes of degree >= 3 + dead ends)
//   blocks               bounded faces of the planar line work (GEOS polygonize)
// Undefined values (a ratio over nothing, a density over a zero area) are NaN.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "core/geos_context.hpp"
#include "core/metrics/network_graph.hpp"
#include "core/no_postgres.hpp"

namespace streetgen::core {

enum class Metric : int {
  node_count,
  edge_count,
  duplicate_edges,
  collapsed_edges,
  component_count,
  largest_component_share,
  total_length,
  area,
  node_density,
  intersection_count,
  intersection_density,
  street_density,
  mean_degree,
  dead_end_share,
  degree2_share,
  degree3_share,
  degree4_share,
  degree5plus_share,
  connected_node_ratio,
  mean_segment_length,
  circuity,
  orientation_entropy,
  orientation_order,
  block_count,
  block_area_p25,
  block_area_median,
  block_area_p75,
  block_area_mean,
  block_compactness_p25,
  block_compactness_median,
  block_compactness_p75,
  block_aspect_ratio_p25,
  block_aspect_ratio_median,
  block_aspect_ratio_p75,
  count_
};
constexpr std::size_t kMetricCount = static_cast<std::size_t>(Metric::count_);

struct MetricInfo {
  const char* name;  // the SQL column name
  bool integer;      // bigint in SQL
  bool headline;     // one of the metrics of the realism score (see compare_networks)
};
const std::array<MetricInfo, kMetricCount>& metric_table();

constexpr int kOrientationBins = 36;

// The orientation bin of a bearing (degrees clockwise from north, [0, 360)): kOrientationBins bins
// of 10° centred on 0°, 10°, ... (OSMnx).
int orientation_bin(double bearing);
// The orientation order φ of an orientation entropy H: 1 - ((H - ln 4) / (ln 36 - ln 4))² (Boeing 2019).
double orientation_order_of_entropy(double entropy);

struct NetworkStats {
  std::array<double, kMetricCount> value{};
  std::vector<int> degrees;                   // per node counted (in the window)
  std::vector<double> segment_lengths;        // per edge counted
  std::vector<double> orientation_histogram;  // kOrientationBins length shares (sum 1), bin 0 centred on 0°
  std::vector<double> block_areas, block_compactness, block_aspect_ratios;

  double& operator[](Metric m) { return value[static_cast<std::size_t>(m)]; }
  double operator[](Metric m) const { return value[static_cast<std::size_t>(m)]; }
};

struct NetworkStatsOptions {
  // A Polygon or MultiPolygon, or nullptr. With a window, node metrics count the nodes inside it
  // (with their full degree, so edges cut by a crop outside the window make no dead ends);
  // lengths and orientations count the part of each edge inside it; segment lengths and
  // circuity the edges with an end node inside; blocks the faces inside it; the area is its area.
  const GEOSGeometry* window = nullptr;
  bool blocks = true;
};

NetworkStats network_stats(GeosContext& geos, const NetworkGraph& graph, const NetworkStatsOptions& options);

// Quantile q in [0, 1] of sorted values, linear between order statistics (numpy's default).
double quantile_sorted(const std::vector<double>& sorted, double q);

}  // namespace streetgen::core
