#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/geometry_checks.hpp"
#include "test_support.hpp"

using namespace streetgen;

namespace {
core::ErrorKind kind_of_axis_check(core::GeosContext& ctx, const GEOSGeometry* geom) {
  try {
    core::require_axis_line(ctx, geom, "axis");
  } catch (const core::Error& e) {
    return e.kind();
  }
  return core::ErrorKind::internal;  // "no error" for these tests
}

core::GeomPtr line_through(core::GeosContext& ctx, double x2, double y2) {
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx.handle(), 2, 2);
  GEOSCoordSeq_setXY_r(ctx.handle(), seq, 0, 0.0, 0.0);
  GEOSCoordSeq_setXY_r(ctx.handle(), seq, 1, x2, y2);
  return core::own(ctx, GEOSGeom_createLineString_r(ctx.handle(), seq), "test line");
}
}  // namespace

TEST(GeometryChecks, AcceptsAnOrdinaryAxis) {
  core::GeosContext ctx;
  core::GeomPtr line = test::wkt(ctx, "LINESTRING(0 0, 10 0, 10 5)");
  EXPECT_NO_THROW(core::require_axis_line(ctx, line.get(), "axis"));
}

TEST(GeometryChecks, RejectsWrongTypeEmptyAndZeroLength) {
  core::GeosContext ctx;
  core::GeomPtr point = test::wkt(ctx, "POINT(1 1)");
  core::GeomPtr empty = test::wkt(ctx, "LINESTRING EMPTY");
  core::GeomPtr zero = test::wkt(ctx, "LINESTRING(2 2, 2 2, 2 2)");
  core::GeomPtr multi = test::wkt(ctx, "MULTILINESTRING((0 0, 1 1))");
  EXPECT_EQ(kind_of_axis_check(ctx, point.get()), core::ErrorKind::invalid_argument);
  EXPECT_EQ(kind_of_axis_check(ctx, empty.get()), core::ErrorKind::invalid_argument);
  EXPECT_EQ(kind_of_axis_check(ctx, zero.get()), core::ErrorKind::invalid_argument);
  EXPECT_EQ(kind_of_axis_check(ctx, multi.get()), core::ErrorKind::invalid_argument);
}

TEST(GeometryChecks, RejectsNanAndInfinityAnywhere) {
  core::GeosContext ctx;
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    core::GeomPtr line = line_through(ctx, bad, 1.0);
    EXPECT_EQ(kind_of_axis_check(ctx, line.get()), core::ErrorKind::invalid_argument) << bad;
    core::GeomPtr line_y = line_through(ctx, 1.0, bad);
    EXPECT_EQ(kind_of_axis_check(ctx, line_y.get()), core::ErrorKind::invalid_argument) << bad;
  }
}

TEST(GeometryChecks, FiniteCheckWalksPolygonRingsAndCollections) {
  core::GeosContext ctx;
  core::GeomPtr ok = test::wkt(ctx, "GEOMETRYCOLLECTION(POLYGON((0 0, 4 0, 4 4, 0 0), (1 1, 2 1, 2 2, 1 1)), POINT(5 5))");
  EXPECT_NO_THROW(core::require_finite_coordinates(ctx, ok.get(), "g"));
  core::GeomPtr bad_point = line_through(ctx, std::nan(""), 0.0);
  const GEOSGeometry* parts[] = {GEOSGeom_clone_r(ctx.handle(), ok.get()), GEOSGeom_clone_r(ctx.handle(), bad_point.get())};
  core::GeomPtr collection = core::own(
      ctx, GEOSGeom_createCollection_r(ctx.handle(), GEOS_GEOMETRYCOLLECTION, const_cast<GEOSGeometry**>(parts), 2),
      "test collection");
  EXPECT_THROW(core::require_finite_coordinates(ctx, collection.get(), "g"), core::Error);
}

TEST(GeometryChecks, PositiveFinite) {
  EXPECT_NO_THROW(core::require_positive_finite(0.5, "w"));
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(core::require_positive_finite(bad, "w"), core::Error) << bad;
  }
}
