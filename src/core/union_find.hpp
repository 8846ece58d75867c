// Disjoint sets over indices 0..n-1 (path halving), for clustering points within a tolerance.
#pragma once
#include "core/no_postgres.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace streetgen::core {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // smallest index is the root: deterministic
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace streetgen::core
