// Whether two simple polygons may share interior area, by exact predicates on their vertices and
// edges (CGAL), without an overlay: most roadways that a junction's box meets only touch it
// along a border line, and a GEOS union and difference to learn that cost about 60 us each.
#pragma once
#include "core/no_postgres.hpp"

#include "core/streets/polyline.hpp"

namespace streetgen::core {

// Rings closed or not (a repeated first point is ignored), at least three distinct points each.
// false only when the interiors certainly do not meet: no edge of one properly crosses an edge
// of the other, and no vertex or edge midpoint of either lies strictly inside the other (an
// overlap of two simple polygons without a proper crossing has a vertex of one strictly inside
// the other, or runs along an edge whose midpoint is inside). true when they may: callers then
// compute the overlay, so a doubtful case costs time, never a missed overlap of any size.
bool interiors_may_meet(const Polyline& ring_a, const Polyline& ring_b);

}  // namespace streetgen::core
