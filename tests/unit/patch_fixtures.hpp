#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"

namespace streetgen::test {

// A 7 x 7 node grid of 100 m blocks (one row per block): avenues along x = 100, x = 400, y = 100
// and y = 400 (crossing at four arterial junctions), streets elsewhere. Shared by the patch and
// terrain tests.
inline std::vector<core::PatchInputEdge> avenue_grid() {
  std::vector<core::PatchInputEdge> out;
  std::int64_t id = 0;
  auto avenue = [](int k) { return k == 1 || k == 4; };
  for (int i = 0; i <= 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      out.push_back({{{j * 100.0, i * 100.0}, {(j + 1) * 100.0, i * 100.0}}, avenue(i) ? "avenue" : "street", ++id, false});
      out.push_back({{{i * 100.0, j * 100.0}, {i * 100.0, (j + 1) * 100.0}}, avenue(i) ? "avenue" : "street", ++id, false});
    }
  }
  return out;
}

// Dead ends farther than 200 m inside the edge of a region whose x and y lie within +-1500 m
// (the tests' grown squares): nodes of degree 1 with |x|, |y| < 1300.
inline int interior_dead_ends(const core::GrowResult& r) {
  std::map<std::int64_t, int> degree;
  std::map<std::int64_t, core::Point> at;
  for (const core::GrownEdge& e : r.edges) {
    ++degree[e.from_node];
    ++degree[e.to_node];
    at[e.from_node] = e.a;
    at[e.to_node] = e.b;
  }
  int n = 0;
  for (const auto& [node, d] : degree) {
    const core::Point q = at[node];
    n += d == 1 && std::abs(q.x) < 1300 && std::abs(q.y) < 1300;
  }
  return n;
}

// Two grown edges cross or touch without sharing a node (touching counts: an edge ending on
// another's interior is not joined to it).
inline bool crosses_without_node(const core::GrownEdge& a, const core::GrownEdge& b) {
  bool shared = a.from_node == b.from_node || a.from_node == b.to_node || a.to_node == b.from_node ||
                a.to_node == b.to_node;
  if (shared) return false;
  auto orient = [](core::Point p, core::Point q, core::Point r) { return core::cross(q - p, r - p); };
  double d1 = orient(a.a, a.b, b.a), d2 = orient(a.a, a.b, b.b);
  double d3 = orient(b.a, b.b, a.a), d4 = orient(b.a, b.b, a.b);
  return d1 * d2 <= 0 && d3 * d4 <= 0 &&
         std::max(std::min(a.a.x, a.b.x), std::min(b.a.x, b.b.x)) <= std::min(std::max(a.a.x, a.b.x), std::max(b.a.x, b.b.x)) &&
         std::max(std::min(a.a.y, a.b.y), std::min(b.a.y, b.b.y)) <= std::min(std::max(a.a.y, a.b.y), std::max(b.a.y, b.b.y));
}

// Pairs of grown edges that cross without a shared node: 0 for a planar growth.
inline long crossings_without_node(const core::GrowResult& r) {
  long n = 0;
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < r.edges.size(); ++j) n += crosses_without_node(r.edges[i], r.edges[j]);
  }
  return n;
}

// The same graph, edge for edge (a growth run again with the same seed).
inline void expect_same_graph(const core::GrowResult& again, const core::GrowResult& first) {
  ASSERT_EQ(again.edges.size(), first.edges.size());
  for (std::size_t i = 0; i < first.edges.size(); ++i) {
    EXPECT_EQ(again.edges[i].from_node, first.edges[i].from_node);
    EXPECT_EQ(again.edges[i].to_node, first.edges[i].to_node);
  }
}

// The same growth, edge for edge and point for point, copied from the same example edges (one made
// another way, e.g. resumed from a checkpoint).
inline void expect_same_edges(const core::GrowResult& a, const core::GrowResult& b) {
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].from_node, b.edges[i].from_node);
    EXPECT_EQ(a.edges[i].to_node, b.edges[i].to_node);
    EXPECT_EQ(a.edges[i].a.x, b.edges[i].a.x);
    EXPECT_EQ(a.edges[i].a.y, b.edges[i].a.y);
    EXPECT_EQ(a.edges[i].b.x, b.edges[i].b.x);
    EXPECT_EQ(a.edges[i].b.y, b.edges[i].b.y);
    EXPECT_EQ(a.edges[i].example, b.edges[i].example);
  }
}

}  // namespace streetgen::test
