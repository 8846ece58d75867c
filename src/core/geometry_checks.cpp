#include "core/geometry_checks.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/interrupts.hpp"

namespace streetgen::core {
namespace {

void check_sequence(GeosContext& ctx, const GEOSCoordSequence* seq, const char* parameter, InterruptPoller& poller) {
  unsigned int size = 0;
  if (GEOSCoordSeq_getSize_r(ctx.handle(), seq, &size) == 0) ctx.fail("coordinate access");
  for (unsigned int i = 0; i < size; ++i) {
    poller.tick();
    double x = 0.0;
    double y = 0.0;
    if (GEOSCoordSeq_getXY_r(ctx.handle(), seq, i, &x, &y) == 0) ctx.fail("coordinate access");
    if (!std::isfinite(x) || !std::isfinite(y)) {
      throw_invalid_argument(std::string(parameter) + " has a non-finite coordinate",
                             "Vertex " + std::to_string(i + 1) + " is (" + std::to_string(x) + ", " +
                                 std::to_string(y) + ").",
                             "Remove NaN and infinite coordinates before calling streetgen.");
    }
  }
}

void check_geometry(GeosContext& ctx, const GEOSGeometry* geom, const char* parameter, InterruptPoller& poller) {
  switch (GEOSGeomTypeId_r(ctx.handle(), geom)) {
    case GEOS_POINT:
    case GEOS_LINESTRING:
    case GEOS_LINEARRING: {
      if (GEOSisEmpty_r(ctx.handle(), geom) == 1) return;
      const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx.handle(), geom);
      if (seq == nullptr) ctx.fail("coordinate access");
      check_sequence(ctx, seq, parameter, poller);
      return;
    }
    case GEOS_POLYGON: {
      if (GEOSisEmpty_r(ctx.handle(), geom) == 1) return;
      check_geometry(ctx, GEOSGetExteriorRing_r(ctx.handle(), geom), parameter, poller);
      int holes = GEOSGetNumInteriorRings_r(ctx.handle(), geom);
      for (int i = 0; i < holes; ++i) check_geometry(ctx, GEOSGetInteriorRingN_r(ctx.handle(), geom, i), parameter, poller);
      return;
    }
    default: {
      int parts = GEOSGetNumGeometries_r(ctx.handle(), geom);
      for (int i = 0; i < parts; ++i) check_geometry(ctx, GEOSGetGeometryN_r(ctx.handle(), geom, i), parameter, poller);
    }
  }
}

}  // namespace

std::string geometry_type_name(GeosContext& ctx, const GEOSGeometry* geom) {
  char* name = GEOSGeomType_r(ctx.handle(), geom);
  if (name == nullptr) ctx.fail("geometry type");
  std::string out(name);
  GEOSFree_r(ctx.handle(), name);
  return out;
}

void require_finite_coordinates(GeosContext& ctx, const GEOSGeometry* geom, const char* parameter) {
  InterruptPoller poller;
  check_geometry(ctx, geom, parameter, poller);
}

void require_axis_line(GeosContext& ctx, const GEOSGeometry* geom, const char* parameter) {
  if (GEOSGeomTypeId_r(ctx.handle(), geom) != GEOS_LINESTRING) {
    throw_invalid_argument(std::string(parameter) + " must be a LineString",
                           "Got a " + geometry_type_name(ctx, geom) + ".",
                           "Split multi-part axes with ST_Dump first.");
  }
  if (GEOSisEmpty_r(ctx.handle(), geom) == 1) throw_invalid_argument(std::string(parameter) + " is empty");
  require_finite_coordinates(ctx, geom, parameter);
  double length = 0.0;
  if (GEOSLength_r(ctx.handle(), geom, &length) == 0) ctx.fail("length");
  if (!(length > 0.0)) {
    throw_invalid_argument(std::string(parameter) + " has zero length", "All its vertices coincide.");
  }
}

void require_positive_finite(double value, const char* parameter) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw_invalid_argument(std::string(parameter) + " must be a finite number greater than 0",
                           "Got " + std::to_string(value) + ".");
  }
}

void append_linestrings(GeosContext& ctx, const GEOSGeometry* geom, const std::string& parameter,
                        const std::string& message, const std::string& hint, std::vector<Polyline>& out) {
  GEOSContextHandle_t h = ctx.handle();
  int type = GEOSGeomTypeId_r(h, geom);
  if (type == GEOS_MULTILINESTRING) {
    int n = GEOSGetNumGeometries_r(h, geom);
    for (int i = 0; i < n; ++i) append_linestrings(ctx, GEOSGetGeometryN_r(h, geom, i), parameter, message, hint, out);
    return;
  }
  if (type != GEOS_LINESTRING) {
    throw_invalid_argument(message, "The " + parameter + " is a " + geometry_type_name(ctx, geom) + ".", hint);
  }
  if (GEOSisEmpty_r(h, geom) != 0) return;
  require_finite_coordinates(ctx, geom, parameter.c_str());
  const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(h, geom);
  unsigned int n = 0;
  GEOSCoordSeq_getSize_r(h, seq, &n);
  Polyline line(n);
  for (unsigned int i = 0; i < n; ++i) GEOSCoordSeq_getXY_r(h, seq, i, &line[i].x, &line[i].y);
  out.push_back(std::move(line));
}

}  // namespace streetgen::core
