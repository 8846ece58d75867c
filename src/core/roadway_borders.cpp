#include "core/roadway_borders.hpp"

#include "core/geometry_checks.hpp"

namespace streetgen::core {
namespace {
// Round joins: a vehicle's path, and the curb, have no mitred corners. Eight segments per
// quarter circle is what PostGIS's ST_Buffer uses by default.
constexpr int kQuadrantSegments = 8;
constexpr double kMitreLimit = 5.0;  // unused with round joins; GEOS still takes one
}  // namespace

const char* side_name(Side side) noexcept { return side == Side::left ? "left" : "right"; }

std::vector<RoadwayBorder> roadway_borders(GeosContext& ctx, const GEOSGeometry* axis, double roadway_width) {
  require_axis_line(ctx, axis, "axis");
  require_positive_finite(roadway_width, "roadway_width");
  std::vector<RoadwayBorder> borders;
  borders.reserve(2);
  for (Side side : {Side::left, Side::right}) {
    // GEOS: positive distances offset to the left, negative to the right; since GEOS 3.11 both
    // keep the direction of the input (checked by the unit tests).
    double distance = (side == Side::left ? 0.5 : -0.5) * roadway_width;
    borders.push_back({side, own(ctx,
                                 GEOSOffsetCurve_r(ctx.handle(), axis, distance, kQuadrantSegments,
                                                   GEOSBUF_JOIN_ROUND, kMitreLimit),
                                 "offset curve")});
  }
  return borders;
}

}  // namespace streetgen::core
