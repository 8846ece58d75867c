// Axis-aligned boxes: all pairs that overlap (CGAL's box_intersection_d: sweep + segment tree,
// O(n log^2 n + k); the spatial join behind topology building), and an order that keeps
// neighbours together (CGAL's Hilbert sort).
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <functional>
#include <vector>

namespace streetgen::core {

struct Box {
  double xmin, ymin, xmax, ymax;
};

// Calls visit(i, j) once for each pair i < j of boxes that overlap (closed boxes).
void for_each_overlapping_pair(const std::vector<Box>& boxes, const std::function<void(std::size_t, std::size_t)>& visit);

// Calls visit(i, j) once for each box i of `a` and box j of `b` that overlap (closed boxes): the
// pairs between two sets only, without enumerating the pairs within either (CGAL's bipartite
// box_intersection_d). The order of the calls is unspecified.
void for_each_overlapping_cross_pair(const std::vector<Box>& a, const std::vector<Box>& b,
                                     const std::function<void(std::size_t, std::size_t)>& visit);

// The indices of `boxes` in the order a Hilbert curve visits their centres (median policy:
// deterministic), so that boxes near each other mostly come near each other in the order.
std::vector<std::size_t> hilbert_order(const std::vector<Box>& boxes);

}  // namespace streetgen::core
