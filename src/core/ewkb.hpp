// Geometry crosses the PostgreSQL boundary as EWKB (ST_AsEWKB / ST_GeomFromEWKB in the SQL
// wrappers), so the extension never links PostGIS internals. GEOS reads and writes the SRID.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geos_context.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct SridGeometry {
  GeomPtr geom;
  int srid = 0;
};

using Bytes = std::vector<std::uint8_t>;

// Parses EWKB (or plain WKB, SRID 0). Throws ErrorKind::bad_data naming `parameter` on garbage.
SridGeometry read_ewkb(GeosContext& ctx, const std::uint8_t* data, std::size_t size, const char* parameter);

// Writes 2D little-endian EWKB carrying `srid` (no SRID flag when srid is 0).
// Sets the SRID on `geom` (GEOS writers take it from the geometry).
Bytes write_ewkb(GeosContext& ctx, GEOSGeometry* geom, int srid);

// EWKB written straight from coordinates (no GEOS geometry in between): a Point, a LineString,
// or a CircularString (which GEOS 3.11 cannot represent; PostGIS reads it as a true arc).
enum class WkbType : std::uint32_t { point = 1, line_string = 2, circular_string = 8 };
Bytes write_ewkb_coordinates(WkbType type, const double* xy, std::size_t point_count, int srid);

// The same from a polyline (a LineString, or a CircularString of its points).
Bytes write_ewkb_polyline(WkbType type, const Polyline& line, int srid);

}  // namespace streetgen::core
