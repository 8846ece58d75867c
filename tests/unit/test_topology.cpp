#include <gtest/gtest.h>

#include <algorithm>

#include "core/streets/topology.hpp"

using namespace streetgen::core;

namespace {
std::size_t degree(const Topology& t, std::size_t node) {
  std::size_t d = 0;
  for (const auto& e : t.edges) {
    if (e.duplicate) continue;
    d += (e.from_node == node) + (e.to_node == node);
  }
  return d;
}
std::size_t node_near(const Topology& t, Point p) {
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    if (distance(t.nodes[i].position, p) < 1e-6) return i;
  }
  return t.nodes.size();
}
}  // namespace

TEST(Topology, CrossingAxesOnOneLayerAreSplit) {
  Topology t = build_topology({{1, {{-50, 0}, {50, 0}}, 0}, {2, {{0, -50}, {0, 50}}, 0}}, 0.5);
  ASSERT_EQ(t.edges.size(), 4u);
  std::size_t centre = node_near(t, {0, 0});
  ASSERT_LT(centre, t.nodes.size());
  EXPECT_EQ(degree(t, centre), 4u);
  EXPECT_EQ(t.nodes.size(), 5u);
}

TEST(Topology, BridgeOverAStreetStaysApart) {
  Topology t = build_topology({{1, {{-50, 0}, {50, 0}}, 1}, {2, {{0, -50}, {0, 50}}, 0}}, 0.5);
  EXPECT_EQ(t.edges.size(), 2u);
  EXPECT_EQ(node_near(t, {0, 0}), t.nodes.size());
}

TEST(Topology, BridgeEndMeetsTheGroundStreet) {
  Topology t = build_topology({{1, {{0, 0}, {50, 0}}, 1}, {2, {{50, 0}, {100, 0}}, 0}}, 0.5);
  EXPECT_EQ(t.edges.size(), 2u);
  EXPECT_EQ(t.nodes.size(), 3u);
}

TEST(Topology, FuzzyEndpointsSnapWithinTolerance) {
  // A T-junction digitised 0.3 m short, and two ends 0.2 m apart.
  Topology t = build_topology({{1, {{-50, 0}, {50, 0}}, 0}, {2, {{0, 0.3}, {0, 50}}, 0}, {3, {{0.2, 50}, {20, 80}}, 0}}, 0.5);
  EXPECT_EQ(t.edges.size(), 4u);  // axis 1 split in two, plus axes 2 and 3
  std::size_t top = node_near(t, {0.1, 50});
  ASSERT_LT(top, t.nodes.size());
  EXPECT_EQ(degree(t, top), 2u);
  // Beyond the tolerance nothing snaps.
  Topology far = build_topology({{1, {{-50, 0}, {50, 0}}, 0}, {2, {{0, 0.8}, {0, 50}}, 0}}, 0.5);
  EXPECT_EQ(far.edges.size(), 2u);
}

TEST(Topology, SharedInteriorVertexSplitsBothAxes) {
  // OSM style: two ways share a vertex in the middle of both.
  Topology t = build_topology({{1, {{0, 0}, {10, 10}, {20, 0}}, 0}, {2, {{0, 20}, {10, 10}, {20, 20}}, 0}}, 0.01);
  EXPECT_EQ(t.edges.size(), 4u);
  std::size_t mid = node_near(t, {10, 10});
  ASSERT_LT(mid, t.nodes.size());
  EXPECT_EQ(degree(t, mid), 4u);
}

TEST(Topology, DuplicateAndZeroLengthAxesAreReported) {
  Topology t = build_topology({{1, {{0, 0}, {100, 0}}, 0}, {2, {{100, 0}, {0, 0}}, 0}, {3, {{5, 5}, {5, 5}}, 0}}, 0.5);
  ASSERT_EQ(t.edges.size(), 2u);
  EXPECT_EQ(std::count_if(t.edges.begin(), t.edges.end(), [](const TopologyEdge& e) { return e.duplicate; }), 1);
  auto has = [&](const char* kind, std::int64_t id) {
    return std::any_of(t.issues.begin(), t.issues.end(), [&](const TopologyIssue& i) { return i.kind == kind && i.axis_id == id; });
  };
  EXPECT_TRUE(has("duplicate_axis", 2));
  EXPECT_TRUE(has("degenerate_axis", 3));
}

TEST(Topology, NodeIdsAreStableAndIndependentOfInputOrder) {
  Topology a = build_topology({{1, {{-50, 0}, {50, 0}}, 0}, {2, {{0, -50}, {0, 50}}, 0}}, 0.5);
  Topology b = build_topology({{2, {{0, -50}, {0, 50}}, 0}, {1, {{-50, 0}, {50, 0}}, 0}}, 0.5);
  auto ids = [](const Topology& t) {
    std::vector<std::int64_t> v;
    for (const auto& n : t.nodes) v.push_back(n.id);
    std::sort(v.begin(), v.end());
    return v;
  };
  EXPECT_EQ(ids(a), ids(b));
  EXPECT_EQ(node_id_for({0, 0}, 0), node_id_for({0.0004, -0.0004}, 0));
  EXPECT_NE(node_id_for({0, 0}, 0), node_id_for({0, 0}, 1));
  for (auto id : ids(a)) EXPECT_GT(id, 0);
}

TEST(Topology, SelfCrossingAxisMakesANode) {
  Topology t = build_topology({{1, {{0, 0}, {20, 20}, {20, 0}, {0, 20}}, 0}}, 0.1);
  std::size_t x = node_near(t, {10, 10});
  ASSERT_LT(x, t.nodes.size());
  EXPECT_EQ(degree(t, x), 4u);
}
