#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/roadway_borders.hpp"
#include "test_support.hpp"

using namespace streetgen;

namespace {
double distance(core::GeosContext& ctx, const GEOSGeometry* a, const GEOSGeometry* b) {
  double d = -1.0;
  GEOSDistance_r(ctx.handle(), a, b, &d);
  return d;
}

// Every vertex of `border` lies at `expected` from `axis`, and vice versa the border is no
// farther than that anywhere (Hausdorff).
void expect_at_distance(core::GeosContext& ctx, const GEOSGeometry* border, const GEOSGeometry* axis, double expected) {
  const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx.handle(), border);
  ASSERT_NE(seq, nullptr);
  unsigned int n = 0;
  GEOSCoordSeq_getSize_r(ctx.handle(), seq, &n);
  ASSERT_GE(n, 2u);
  for (unsigned int i = 0; i < n; ++i) {
    double x = 0;
    double y = 0;
    GEOSCoordSeq_getXY_r(ctx.handle(), seq, i, &x, &y);
    core::GeomPtr p = core::own(ctx, GEOSGeom_createPointFromXY_r(ctx.handle(), x, y), "point");
    EXPECT_NEAR(distance(ctx, p.get(), axis), expected, 1e-6) << "vertex " << i;
  }
}

// Signed side of the border's first vertex relative to the axis's first segment (+ is left).
double side_of_start(core::GeosContext& ctx, const GEOSGeometry* border, const GEOSGeometry* axis) {
  const GEOSCoordSequence* a = GEOSGeom_getCoordSeq_r(ctx.handle(), axis);
  const GEOSCoordSequence* b = GEOSGeom_getCoordSeq_r(ctx.handle(), border);
  double ax0, ay0, ax1, ay1, bx, by;
  GEOSCoordSeq_getXY_r(ctx.handle(), a, 0, &ax0, &ay0);
  GEOSCoordSeq_getXY_r(ctx.handle(), a, 1, &ax1, &ay1);
  GEOSCoordSeq_getXY_r(ctx.handle(), b, 0, &bx, &by);
  return (ax1 - ax0) * (by - ay0) - (ay1 - ay0) * (bx - ax0);
}
}  // namespace

TEST(RoadwayBorders, StraightAxis) {
  core::GeosContext ctx;
  core::GeomPtr axis = test::wkt(ctx, "LINESTRING(0 0, 100 0)");
  auto borders = core::roadway_borders(ctx, axis.get(), 7.0);
  ASSERT_EQ(borders.size(), 2u);
  EXPECT_EQ(borders[0].side, core::Side::left);
  EXPECT_EQ(borders[1].side, core::Side::right);
  core::GeomPtr left = test::wkt(ctx, "LINESTRING(0 3.5, 100 3.5)");
  core::GeomPtr right = test::wkt(ctx, "LINESTRING(0 -3.5, 100 -3.5)");
  EXPECT_EQ(GEOSEqualsExact_r(ctx.handle(), borders[0].line.get(), left.get(), 1e-9), 1);
  EXPECT_EQ(GEOSEqualsExact_r(ctx.handle(), borders[1].line.get(), right.get(), 1e-9), 1);
}

// The paper's point: on a polyline, a translated axis is not at constant distance; the offset is.
TEST(RoadwayBorders, PolylineBordersStayAtHalfWidthAndKeepDirection) {
  core::GeosContext ctx;
  core::GeomPtr axis = test::wkt(ctx, "LINESTRING(0 0, 40 0, 60 25, 60 70, 20 90)");
  const double width = 9.0;
  auto borders = core::roadway_borders(ctx, axis.get(), width);
  ASSERT_EQ(borders.size(), 2u);
  for (const auto& border : borders) {
    ASSERT_EQ(GEOSGeomTypeId_r(ctx.handle(), border.line.get()), GEOS_LINESTRING);
    expect_at_distance(ctx, border.line.get(), axis.get(), width / 2);
  }
  EXPECT_GT(side_of_start(ctx, borders[0].line.get(), axis.get()), 0.0);
  EXPECT_LT(side_of_start(ctx, borders[1].line.get(), axis.get()), 0.0);
  // Same direction as the axis: each border starts next to the axis start, ends next to its end.
  for (const auto& border : borders) {
    core::GeomPtr start = core::own(ctx, GEOSGeomGetStartPoint_r(ctx.handle(), border.line.get()), "start");
    core::GeomPtr axis_start = core::own(ctx, GEOSGeomGetStartPoint_r(ctx.handle(), axis.get()), "start");
    EXPECT_NEAR(distance(ctx, start.get(), axis_start.get()), width / 2, 1e-6);
  }
}

TEST(RoadwayBorders, RejectsBadWidthAndBadAxis) {
  core::GeosContext ctx;
  core::GeomPtr axis = test::wkt(ctx, "LINESTRING(0 0, 10 0)");
  EXPECT_THROW(core::roadway_borders(ctx, axis.get(), 0.0), core::Error);
  EXPECT_THROW(core::roadway_borders(ctx, axis.get(), -2.0), core::Error);
  core::GeomPtr point = test::wkt(ctx, "POINT(0 0)");
  EXPECT_THROW(core::roadway_borders(ctx, point.get(), 5.0), core::Error);
}
