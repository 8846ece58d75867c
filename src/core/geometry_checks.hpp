// Input checks shared by every function that takes geometry: each names the parameter it
// rejects, so the SQL error says which argument was wrong.
#pragma once
#include "core/no_postgres.hpp"

#include <string>
#include <vector>

#include "core/geos_context.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

// GEOS type name as users know it from PostGIS ("LineString", "Point", ...).
std::string geometry_type_name(GeosContext& ctx, const GEOSGeometry* geom);

// Throws invalid_argument if any coordinate is NaN or infinite. Polls interrupts: geometries
// can hold millions of vertices.
void require_finite_coordinates(GeosContext& ctx, const GEOSGeometry* geom, const char* parameter);

// A road axis: a non-empty LineString with finite coordinates and positive length.
void require_axis_line(GeosContext& ctx, const GEOSGeometry* geom, const char* parameter);

// Appends the LineStrings of geom (a LineString or MultiLineString, empty ones skipped) to out;
// anything else is rejected with `message` (the detail names `parameter`, `hint` says what to do).
void append_linestrings(GeosContext& ctx, const GEOSGeometry* geom, const std::string& parameter,
                        const std::string& message, const std::string& hint, std::vector<Polyline>& out);

// A finite number > 0.
void require_positive_finite(double value, const char* parameter);

}  // namespace streetgen::core
