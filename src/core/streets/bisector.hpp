// The boundary between the points nearer to one set of sites than to another: the Voronoi edges
// between a site of each set (CGAL's Delaunay triangulation, exact predicates). Roadways that
// overlap are split along it: sites sampled along two axes (or two junctions' skeletons) give
// their midline however the axes curve.
#pragma once
#include "core/no_postgres.hpp"

#include <vector>

#include "core/streets/box_pairs.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct BisectorSegment {
  Point from, to;
};

// The Voronoi edges that separate a site of `a` from a site of `b`, clipped to `clip` (rays and
// long edges cut at its sides; edges outside it dropped). A point that is in both sets counts as
// `a`'s; points with a NaN or infinite coordinate are ignored. Empty when one set is empty (or every point of `b` is also in `a`).
std::vector<BisectorSegment> bisector_segments(const std::vector<Point>& a, const std::vector<Point>& b, const Box& clip);

}  // namespace streetgen::core
