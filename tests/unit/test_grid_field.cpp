// Sampling a control raster (core/raster/grid_field): cell centres, bilinear weights, nodata,
// the raster's edge, north-up orientation, and axial interpolation of undirected angles.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/raster/grid_field.hpp"

using namespace streetgen::core;

namespace {

// 3 x 2 cells of 10 m, north-up, upper-left corner (100, 220): row 0 spans y 210-220.
GridField three_by_two() {
  GridField g;
  g.origin_x = 100.0;
  g.origin_y = 220.0;
  g.scale_x = 10.0;
  g.scale_y = -10.0;
  g.width = 3;
  g.height = 2;
  g.bands = 1;
  g.values = {1, 2, 3,    // row 0 (north)
              4, 5, 6};   // row 1 (south)
  return g;
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TEST(GridField, CellCentresGiveTheirValuesNorthUp) {
  GridField g = three_by_two();
  g.check("test");
  EXPECT_DOUBLE_EQ(sample_nearest(g, 0, {105, 215}), 1.0);
  EXPECT_DOUBLE_EQ(sample_nearest(g, 0, {125, 205}), 6.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {105, 215}), 1.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {115, 205}), 5.0);
}

TEST(GridField, BilinearBetweenCentresAndConstantToTheEdge) {
  GridField g = three_by_two();
  // Halfway between the centres of cells 1 and 2 of row 0, then the middle of four centres.
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {110, 215}), 1.5);
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {110, 210}), (1 + 2 + 4 + 5) / 4.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {112.5, 215}), 1.75);
  // Between the raster's edge and the first centre, the edge cells' values hold.
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {101, 219}), 1.0);
  // Nearest: the cell that holds the point.
  EXPECT_DOUBLE_EQ(sample_nearest(g, 0, {109.9, 210.1}), 1.0);
  EXPECT_DOUBLE_EQ(sample_nearest(g, 0, {110.1, 209.9}), 5.0);
}

TEST(GridField, OutsideAndNodataAreNaN) {
  GridField g = three_by_two();
  EXPECT_TRUE(std::isnan(sample_bilinear(g, 0, {99, 215})));
  EXPECT_TRUE(std::isnan(sample_bilinear(g, 0, {105, 221})));
  EXPECT_TRUE(std::isnan(sample_nearest(g, 0, {131, 205})));
  EXPECT_TRUE(std::isnan(sample_bilinear(GridField{}, 0, {105, 215})));
  g.values[1] = NAN;  // cell (1, 0)
  EXPECT_TRUE(std::isnan(sample_bilinear(g, 0, {115, 215})));
  EXPECT_TRUE(std::isnan(sample_nearest(g, 0, {115, 215})));
  // A nodata neighbour (weight 0.2) is left out and the others' weights renormalised.
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 0, {109, 210}), (0.3 * 1 + 0.3 * 4 + 0.2 * 5) / 0.8);
}

TEST(GridField, SouthUpRasterAndSecondBand) {
  GridField g = three_by_two();
  g.origin_y = 200.0;
  g.scale_y = 10.0;  // row 0 spans y 200-210
  g.bands = 2;
  g.values.insert(g.values.end(), {10, 20, 30, 40, 50, 60});
  g.check("test");
  EXPECT_DOUBLE_EQ(sample_nearest(g, 0, {105, 205}), 1.0);
  EXPECT_DOUBLE_EQ(sample_nearest(g, 1, {125, 215}), 60.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(g, 1, {110, 210}), (10 + 20 + 40 + 50) / 4.0);
}

TEST(GridField, AxialInterpolationOfUndirectedAngles) {
  GridField g = three_by_two();
  const double d = kPi / 180.0;
  g.values = {1 * d, 179 * d, 90 * d, 30 * d, 30 * d, 0};
  // 1° and 179° are 2° apart as undirected lines: their mean is 0° (mod 180°), not 90°.
  double a = sample_axial_bilinear(g, 0, {110, 215});
  EXPECT_NEAR(std::sin(2.0 * a), 0.0, 1e-12);
  EXPECT_NEAR(std::cos(2.0 * a), 1.0, 1e-12);
  EXPECT_NEAR(sample_axial_bilinear(g, 0, {110, 205}), 30 * d, 1e-12);
  // The same in degrees (a direction raster's unit), the result in radians.
  g.values = {1, 179, 90, 30, 30, 0};
  EXPECT_NEAR(std::sin(2.0 * sample_axial_bilinear(g, 0, {110, 215}, d)), 0.0, 1e-12);
  EXPECT_NEAR(sample_axial_bilinear(g, 0, {110, 205}, d), 30 * d, 1e-12);
  // 0° and 90° cancel out halfway: the nearest cell's angle (cell 1 on a tie).
  g.values = {0, 90 * d, 0, 0, 90 * d, 0};
  EXPECT_NEAR(sample_axial_bilinear(g, 0, {110, 215}), 90 * d, 1e-12);
  EXPECT_NEAR(sample_axial_bilinear(g, 0, {109, 215}), 0.0, 1e-12);
}

TEST(GridField, BadRastersAreRejected) {
  GridField g = three_by_two();
  g.values.pop_back();
  EXPECT_THROW(g.check("test"), Error);
  g = three_by_two();
  g.scale_x = 0.0;
  EXPECT_THROW(g.check("test"), Error);
  EXPECT_THROW(GridField{}.check("test"), Error);
  g = three_by_two();
  g.values[2] = -1.0;
  EXPECT_THROW(check_weights(g, "weights"), Error);
  g.values[2] = INFINITY;
  EXPECT_THROW(check_weights(g, "weights"), Error);
  EXPECT_THROW(check_directions(g, "direction"), Error);
  g.values[2] = NAN;  // nodata
  EXPECT_NO_THROW(check_weights(g, "weights"));
  EXPECT_NO_THROW(check_directions(g, "direction"));
  EXPECT_TRUE(overlaps(g, 120, 200, 500, 500));
  EXPECT_FALSE(overlaps(g, 130, 200, 500, 500));
  EXPECT_FALSE(overlaps(g, 0, 0, 99, 99));
}
