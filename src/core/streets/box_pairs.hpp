// All pairs of overlapping axis-aligned boxes (CGAL's box_intersection_d: sweep + segment tree,
// O(n log^2 n + k)). The spatial join behind topology building.
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

}  // namespace streetgen::core
