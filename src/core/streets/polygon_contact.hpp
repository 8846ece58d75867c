// Whether two simple polygons may share interior area, by exact predicates on their vertices and
// edges (CGAL), without an overlay: most roadways that a junction's box meets only touch it
// along a border line, and a GEOS union and difference to learn that cost about 60 us each.
#pragma once
#include "core/no_postgres.hpp"

#include "core/streets/polyline.hpp"

#include <optional>

namespace streetgen::core {

// Rings closed or not (a repeated first point is ignored), at least three distinct points each.
// false only when the interiors certainly do not meet: no edge of one properly crosses an edge
// of the other, and no vertex or edge midpoint of either lies strictly inside the other (an
// overlap of two simple polygons without a proper crossing has a vertex of one strictly inside
// the other, or runs along an edge whose midpoint is inside). true when they may: callers then
// compute the overlay, so a doubtful case costs time, never a missed overlap of any size.
bool interiors_may_meet(const Polyline& ring_a, const Polyline& ring_b);

// An upper bound on the area two simple polygons share when they touch only up to rounding: a
// section's corners computed by GEOS's buffer and its junction's border points computed by hand
// are the same points but for a nanometre, so interiors_may_meet, being exact, says they may
// meet. Each vertex of `moved` within `snap` of a vertex of `fixed` is moved onto it; if the moved
// ring is simple and its interior certainly does not meet `fixed`'s, the shared area is at most
// the area the moves swept (two thin triangles a move). std::nullopt when that cannot be shown:
// the interiors meet after the moves, two vertices would land on one, or the moved ring is not
// simple. 0 when nothing moves and the interiors are apart.
std::optional<double> touching_overlap_bound(const Polyline& fixed, const Polyline& moved, double snap);

}  // namespace streetgen::core
