#pragma once
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

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

}  // namespace streetgen::test
