#pragma once
#include <string>

#include "core/ewkb.hpp"
#include "core/geos_context.hpp"

namespace streetgen::test {

// Geometry from WKT for tests (GEOS's own reader, so the fixture does not depend on our code).
inline core::GeomPtr wkt(core::GeosContext& ctx, const std::string& text) {
  GEOSWKTReader* reader = GEOSWKTReader_create_r(ctx.handle());
  GEOSGeometry* geom = GEOSWKTReader_read_r(ctx.handle(), reader, text.c_str());
  GEOSWKTReader_destroy_r(ctx.handle(), reader);
  return core::own(ctx, geom, "test WKT reading");
}

}  // namespace streetgen::test
