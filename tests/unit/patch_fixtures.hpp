#pragma once
#include <cstdint>
#include <vector>

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

}  // namespace streetgen::test
