// The StreetGen arc centre: the point at distance da from road axis A and db from road axis B
// (da = half width of A + radius, db likewise), on the corner's side, nearest the node. The
// paper finds it by intersecting buffer boundaries; on polylines those boundaries are offset
// segments and circles around vertices, which this computes with CGAL's exact circular kernel
// instead of from segmentised GEOS buffers.
#pragma once
#include "core/no_postgres.hpp"

#include <optional>

#include "core/streets/polyline.hpp"

namespace streetgen::core {

// `a` and `b` leave the node (their first point is the node) and the corner is swept
// counter-clockwise from a to b: the centre lies left of a and right of b. Returns nothing when
// no such point exists (parallel axes, a reflex corner, one road contained in the other).
//
// Filtered like CGAL's own kernels: a double-precision pass first, whose candidates are checked
// before use; only when it finds nothing and met a near-degenerate case on the way (nearly
// parallel offsets, near-tangent circles, a candidate rejected by a hair) does the exact pass run.
std::optional<Point> arc_centre(const Polyline& a, double da, const Polyline& b, double db);

// The two passes on their own (tests compare them; the radius search uses the fast one).
std::optional<Point> arc_centre_fast(const Polyline& a, double da, const Polyline& b, double db);
std::optional<Point> arc_centre_exact(const Polyline& a, double da, const Polyline& b, double db);

}  // namespace streetgen::core
