// The two borders of a roadway: offset curves of the axis at half the width. A translation of
// the axis is wrong on polylines (the StreetGen paper, fig. 10); GEOS's offset curve follows
// each segment and joins them with arcs on the outer side of bends.
#pragma once
#include "core/no_postgres.hpp"

#include <vector>

#include "core/geos_context.hpp"

namespace streetgen::core {

enum class Side { left, right };  // seen walking along the axis in its digitised direction

const char* side_name(Side side) noexcept;

struct RoadwayBorder {
  Side side;
  GeomPtr line;  // LineString, or MultiLineString where a tight bend splits the offset
};

// Checks `axis` (require_axis_line) and `roadway_width` (> 0, finite), then returns the left
// border, then the right one, each in the direction of the axis.
std::vector<RoadwayBorder> roadway_borders(GeosContext& ctx, const GEOSGeometry* axis, double roadway_width);

}  // namespace streetgen::core
