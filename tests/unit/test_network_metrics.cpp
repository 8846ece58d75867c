#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "core/metrics/compare_networks.hpp"
#include "core/metrics/network_graph.hpp"
#include "core/metrics/network_stats.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::wkt;

namespace {

// A square grid of `n` x `n` blocks of `size` m, one edge per block side.
std::vector<Polyline> grid(int n, double size) {
  std::vector<Polyline> lines;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j < n; ++j) {
      lines.push_back({{j * size, i * size}, {(j + 1) * size, i * size}});
      lines.push_back({{i * size, j * size}, {i * size, (j + 1) * size}});
    }
  }
  return lines;
}

NetworkStats stats_of(GeosContext& geos, const std::vector<Polyline>& lines, NetworkGraphOptions g = {},
                      const GEOSGeometry* window = nullptr) {
  NetworkStatsOptions o;
  o.window = window;
  return network_stats(geos, build_network_graph(lines, g), o);
}

}  // namespace

TEST(NetworkMetrics, GridOfThreeByThreeBlocks) {
  GeosContext geos;
  NetworkStats s = stats_of(geos, grid(3, 100.0));
  EXPECT_EQ(s[Metric::node_count], 16);
  EXPECT_EQ(s[Metric::edge_count], 24);
  EXPECT_EQ(s[Metric::intersection_count], 16);  // OSMnx: >= 2 streets
  EXPECT_DOUBLE_EQ(s[Metric::mean_degree], 3.0);
  EXPECT_DOUBLE_EQ(s[Metric::degree4_share], 4.0 / 16);
  EXPECT_DOUBLE_EQ(s[Metric::degree3_share], 8.0 / 16);
  EXPECT_DOUBLE_EQ(s[Metric::dead_end_share], 0.0);
  EXPECT_DOUBLE_EQ(s[Metric::connected_node_ratio], 1.0);
  EXPECT_DOUBLE_EQ(s[Metric::area], 90000.0);
  EXPECT_NEAR(s[Metric::street_density], 2.4 / 0.09, 1e-9);
  EXPECT_DOUBLE_EQ(s[Metric::circuity], 1.0);
  EXPECT_NEAR(s[Metric::orientation_entropy], std::log(4.0), 1e-12);
  EXPECT_NEAR(s[Metric::orientation_order], 1.0, 1e-12);
  EXPECT_NEAR(s.orientation_histogram[0], 0.25, 1e-12);
  EXPECT_NEAR(s.orientation_histogram[9], 0.25, 1e-12);
  EXPECT_EQ(s[Metric::block_count], 9);
  EXPECT_NEAR(s[Metric::block_area_median], 10000.0, 1e-6);
  EXPECT_NEAR(s[Metric::block_compactness_median], M_PI / 4, 1e-9);
  EXPECT_NEAR(s[Metric::block_aspect_ratio_median], 1.0, 1e-9);
  EXPECT_EQ(s[Metric::component_count], 1);
}

TEST(NetworkMetrics, OrientationBinsAreCentredOnNorthLikeOsmnx) {
  GeosContext geos;
  auto bearing_line = [](double deg) {
    double r = deg * M_PI / 180.0;
    return Polyline{{0, 0}, {100 * std::sin(r), 100 * std::cos(r)}};
  };
  // 4.9° and 355.1° (and their reverses, 184.9° and 175.1°) fall in the bins of 0° and 180°.
  NetworkStats s = stats_of(geos, {bearing_line(4.9), bearing_line(-4.9)});
  EXPECT_NEAR(s.orientation_histogram[0], 0.5, 1e-12);
  EXPECT_NEAR(s.orientation_histogram[18], 0.5, 1e-12);
  // 5.1° is in the next bin [5°, 15°).
  s = stats_of(geos, {bearing_line(5.1)});
  EXPECT_NEAR(s.orientation_histogram[1], 0.5, 1e-12);
  EXPECT_NEAR(s.orientation_histogram[19], 0.5, 1e-12);
  // Length-weighted.
  s = stats_of(geos, {{{0, 0}, {0, 300}}, {{0, 0}, {100, 0}}});
  EXPECT_NEAR(s.orientation_histogram[0], 0.375, 1e-12);
  EXPECT_NEAR(s.orientation_histogram[9], 0.125, 1e-12);
}

TEST(NetworkMetrics, NodeToleranceMergesNearbyEnds) {
  GeosContext geos;
  std::vector<Polyline> lines = {{{0, 0}, {100, 0}}, {{100.3, 0.0}, {200, 0}}, {{100, 0.2}, {100, 100}}};
  EXPECT_EQ(stats_of(geos, lines)[Metric::node_count], 6);
  NetworkGraphOptions o;
  o.node_tolerance = 0.5;
  NetworkStats s = stats_of(geos, lines, o);
  EXPECT_EQ(s[Metric::node_count], 4);
  EXPECT_EQ(s[Metric::degree3_share], 0.25);
  EXPECT_EQ(s[Metric::dead_end_share], 0.75);
  EXPECT_EQ(s[Metric::connected_node_ratio], 0.25);
}

TEST(NetworkMetrics, CollapsedAndDuplicateEdgesAreDroppedAndCounted) {
  GeosContext geos;
  NetworkGraphOptions o;
  o.node_tolerance = 1.0;
  NetworkGraph g = build_network_graph({{{0, 0}, {100, 0}},
                                        {{100, 0}, {0, 0}},            // reversed duplicate
                                        {{0, 0}, {50, 10}, {100, 0}},  // parallel, another course: kept
                                        {{100, 0}, {100.5, 0.5}},      // collapses into one node
                                        {{5, 5}, {5, 5}}},             // degenerate
                                       o);
  EXPECT_EQ(g.edges.size(), 2u);
  EXPECT_EQ(g.duplicate_edges, 1u);
  EXPECT_EQ(g.collapsed_edges, 2u);
  EXPECT_EQ(g.nodes.size(), 2u);
  EXPECT_EQ(g.degree[0], 2);
}

TEST(NetworkMetrics, SimplifyMergesChainsThroughDegreeTwoNodes) {
  GeosContext geos;
  NetworkGraphOptions o;
  o.simplify = true;
  NetworkGraph g = build_network_graph(
      {{{0, 0}, {10, 0}}, {{10, 0}, {20, 5}}, {{20, 5}, {30, 0}}, {{30, 0}, {30, 50}}, {{30, 0}, {60, 0}}}, o);
  ASSERT_EQ(g.edges.size(), 3u);
  EXPECT_EQ(g.nodes.size(), 4u);
  EXPECT_EQ(g.merged_nodes, 2u);
  double total = 0;
  for (const NetworkEdge& e : g.edges) total += e.length;
  EXPECT_NEAR(total, 10 + 2 * std::hypot(10, 5) + 50 + 30, 1e-9);
}

TEST(NetworkMetrics, SplitAtCrossingsUsesTheEngineTopology) {
  GeosContext geos;
  NetworkGraphOptions o;
  o.split_at_crossings = true;
  NetworkStats s = stats_of(geos, {{{-50, 0}, {50, 0}}, {{0, -50}, {0, 50}}}, o);
  EXPECT_EQ(s[Metric::node_count], 5);
  EXPECT_EQ(s[Metric::edge_count], 4);
  EXPECT_EQ(s[Metric::degree4_share], 0.2);
  EXPECT_EQ(stats_of(geos, {{{-50, 0}, {50, 0}}, {{0, -50}, {0, 50}}})[Metric::node_count], 4);
  // A bridge (layer 1) crosses without a junction.
  NetworkGraph bridge = build_network_graph({{{-50, 0}, {50, 0}}, {{0, -50}, {0, 50}}}, o, {0, 1});
  EXPECT_EQ(bridge.nodes.size(), 4u);
  EXPECT_EQ(bridge.edges.size(), 2u);
}

TEST(NetworkMetrics, WindowKeepsFullDegreesAndClipsLengths) {
  GeosContext geos;
  std::vector<Polyline> cross = {{{0, 0}, {100, 0}}, {{0, 0}, {-100, 0}}, {{0, 0}, {0, 100}}, {{0, 0}, {0, -100}}};
  auto window = wkt(geos, "POLYGON((-50 -50, 50 -50, 50 50, -50 50, -50 -50))");
  NetworkStats s = stats_of(geos, cross, {}, window.get());
  EXPECT_EQ(s[Metric::node_count], 1);
  EXPECT_EQ(s[Metric::dead_end_share], 0.0);
  EXPECT_EQ(s[Metric::degree4_share], 1.0);
  EXPECT_NEAR(s[Metric::total_length], 200.0, 1e-9);
  EXPECT_NEAR(s[Metric::area], 10000.0, 1e-9);
  EXPECT_NEAR(s[Metric::street_density], 0.2 / 0.01, 1e-9);
  // Without the window the arms' ends are dead ends.
  EXPECT_EQ(stats_of(geos, cross)[Metric::dead_end_share], 0.8);
  // An edge that leaves and re-enters the window: its clipped part is a MultiLineString.
  NetworkStats u = stats_of(geos, {{{-40, 0}, {-40, 100}, {40, 100}, {40, 0}}}, {}, window.get());
  EXPECT_NEAR(u[Metric::total_length], 100.0, 1e-9);
  EXPECT_EQ(u[Metric::node_count], 2);
  auto line = wkt(geos, "LINESTRING(0 0, 1 1)");
  NetworkStatsOptions bad;
  bad.window = line.get();
  EXPECT_THROW(network_stats(geos, build_network_graph(cross, {}), bad), Error);
}

TEST(NetworkMetrics, BadInputHasDefinedResults) {
  GeosContext geos;
  NetworkStats empty = stats_of(geos, {});
  EXPECT_EQ(empty[Metric::node_count], 0);
  EXPECT_EQ(empty[Metric::edge_count], 0);
  EXPECT_EQ(empty[Metric::total_length], 0);
  EXPECT_TRUE(std::isnan(empty[Metric::mean_degree]));
  EXPECT_TRUE(std::isnan(empty[Metric::street_density]));
  EXPECT_TRUE(std::isnan(empty[Metric::orientation_entropy]));
  EXPECT_EQ(empty[Metric::block_count], 0);

  NetworkStats single = stats_of(geos, {{{0, 0}, {100, 0}}});
  EXPECT_EQ(single[Metric::node_count], 2);
  EXPECT_EQ(single[Metric::area], 0);  // zero-area hull: densities undefined, not infinite
  EXPECT_TRUE(std::isnan(single[Metric::street_density]));
  EXPECT_EQ(single[Metric::dead_end_share], 1.0);
  EXPECT_EQ(single[Metric::connected_node_ratio], 0.0);

  NetworkStats two = stats_of(geos, {{{0, 0}, {100, 0}}, {{0, 50}, {100, 50}}});
  EXPECT_EQ(two[Metric::component_count], 2);
  EXPECT_EQ(two[Metric::largest_component_share], 0.5);
  EXPECT_EQ(two[Metric::block_count], 0);

  NetworkGraphOptions negative;
  negative.node_tolerance = -1;
  try {
    build_network_graph({}, negative);
    FAIL() << "a negative tolerance must throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
  }
}

TEST(CompareNetworks, DistancesOfKnownSamples) {
  EXPECT_DOUBLE_EQ(ks_distance({1, 2, 3}, {1, 2, 3}), 0.0);
  EXPECT_DOUBLE_EQ(ks_distance({1, 2}, {3, 4}), 1.0);
  EXPECT_DOUBLE_EQ(ks_distance({1, 2, 3, 4}, {1, 2}), 0.5);
  EXPECT_DOUBLE_EQ(wasserstein_distance({0, 0}, {1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(wasserstein_distance({0, 1}, {0, 3}), 1.0);
  EXPECT_TRUE(std::isnan(ks_distance({}, {1})));
  std::vector<double> a(36, 0.0), b(36, 0.0);
  a[0] = 1;
  b[35] = 1;  // neighbours across north: 10° apart on the circle, not 350°
  EXPECT_NEAR(circular_wasserstein_histogram(a, b, 10.0), 10.0, 1e-12);
  EXPECT_NEAR(kuiper_histogram(a, b), 1.0, 1e-12);
  EXPECT_NEAR(kuiper_histogram(a, a), 0.0, 1e-12);
}

TEST(CompareNetworks, IdenticalNetworksScoreOneAndChangesShow) {
  GeosContext geos;
  NetworkStats a = stats_of(geos, grid(4, 100.0));
  auto find = [](const std::vector<ComparisonRow>& rows, const std::string& name) {
    for (const ComparisonRow& r : rows) {
      if (r.metric == name) return r;
    }
    ADD_FAILURE() << "no row " << name;
    return rows.front();
  };
  std::vector<ComparisonRow> same = compare_networks(a, a);
  EXPECT_DOUBLE_EQ(find(same, "realism_score").score, 1.0);
  EXPECT_DOUBLE_EQ(find(same, "mean_degree").relative_difference, 0.0);
  EXPECT_DOUBLE_EQ(find(same, "block_area").ks, 0.0);
  EXPECT_DOUBLE_EQ(find(same, "orientation").wasserstein, 0.0);

  NetworkStats b = stats_of(geos, grid(4, 125.0));  // the same grid, blocks 25 % longer
  std::vector<ComparisonRow> rows = compare_networks(a, b);
  EXPECT_NEAR(find(rows, "street_density").relative_difference, -0.2, 1e-9);
  EXPECT_NEAR(find(rows, "block_area_median").relative_difference, 0.5625, 1e-9);
  EXPECT_DOUBLE_EQ(find(rows, "mean_degree").relative_difference, 0.0);
  EXPECT_DOUBLE_EQ(find(rows, "block_area").ks, 1.0);
  EXPECT_NEAR(find(rows, "segment_length").wasserstein, 25.0, 1e-9);
  // Headline metrics: street density -20 %, intersection density -36 %, block area +56 %, the
  // five others 0: the median of the eight is 0.
  EXPECT_DOUBLE_EQ(find(rows, "realism_score").score, 1.0);
  EXPECT_NEAR(find(rows, "median_abs_relative_difference").score, 0.0, 1e-12);
}
