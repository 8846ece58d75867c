#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "core/streets/bisector.hpp"

using namespace streetgen::core;

namespace {
std::vector<Point> samples(Point from, Point to, int n) {
  std::vector<Point> out;
  for (int k = 0; k < n; ++k) {
    double t = static_cast<double>(k) / (n - 1);
    out.push_back({from.x + t * (to.x - from.x), from.y + t * (to.y - from.y)});
  }
  return out;
}
double covered_length(const std::vector<BisectorSegment>& segments) {
  double sum = 0.0;
  for (const BisectorSegment& s : segments) sum += distance(s.from, s.to);
  return sum;
}
}  // namespace

// Two parallel axes 10 m apart: the split runs along their midline, all across the clip box.
TEST(Bisector, ParallelLinesSplitOnTheirMidline) {
  std::vector<BisectorSegment> split = bisector_segments(samples({0, 0}, {100, 0}, 51), samples({0, 10}, {100, 10}, 51),
                                                         {20, -20, 80, 30});
  ASSERT_FALSE(split.empty());
  for (const BisectorSegment& s : split) {
    EXPECT_NEAR(s.from.y, 5.0, 1e-9);
    EXPECT_NEAR(s.to.y, 5.0, 1e-9);
    EXPECT_GE(std::min(s.from.x, s.to.x), 20.0 - 1e-9);
    EXPECT_LE(std::max(s.from.x, s.to.x), 80.0 + 1e-9);
  }
  EXPECT_NEAR(covered_length(split), 60.0, 1e-6);
}

// Crossing axes: the split is the two angle bisectors' arms between a site of each (|x| = |y|
// near the crossing), never an edge between two sites of one axis.
TEST(Bisector, CrossingLinesSplitAlongTheDiagonals) {
  std::vector<BisectorSegment> split = bisector_segments(samples({-50, 0}, {50, 0}, 101), samples({0, -50}, {0, 50}, 101),
                                                         {-10, -10, 10, 10});
  ASSERT_FALSE(split.empty());
  for (const BisectorSegment& s : split) {
    for (Point p : {s.from, s.to}) EXPECT_NEAR(std::abs(p.x), std::abs(p.y), 1.01) << p.x << " " << p.y;
  }
}

// Sites all on one line (two junctions' stubs along one straight axis): the triangulation has no
// faces, and the split is the perpendicular between the last site of one and the first of the other.
TEST(Bisector, CollinearSitesSplitByAPerpendicular) {
  std::vector<BisectorSegment> split = bisector_segments(samples({0, 0}, {10, 0}, 11), samples({20, 0}, {30, 0}, 11),
                                                         {-5, -5, 35, 5});
  ASSERT_EQ(split.size(), 1u);
  EXPECT_NEAR(split[0].from.x, 15.0, 1e-9);
  EXPECT_NEAR(split[0].to.x, 15.0, 1e-9);
  EXPECT_NEAR(std::abs(split[0].from.y - split[0].to.y), 10.0, 1e-9);
}

// Nothing to split from: one set empty, or the split outside the clip box.
TEST(Bisector, NoSplitWithoutTwoSetsInTheBox) {
  EXPECT_TRUE(bisector_segments(samples({0, 0}, {10, 0}, 11), {}, {-5, -5, 15, 5}).empty());
  EXPECT_TRUE(bisector_segments({}, samples({0, 0}, {10, 0}, 11), {-5, -5, 15, 5}).empty());
  EXPECT_TRUE(bisector_segments(samples({0, 0}, {100, 0}, 51), samples({0, 10}, {100, 10}, 51), {20, 6, 80, 30}).empty());
  // Sites with a NaN coordinate are ignored, never handed to the exact predicates.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(bisector_segments({{nan, 0}, {0, nan}}, samples({0, 0}, {10, 0}, 11), {-5, -5, 15, 5}).empty());
  EXPECT_EQ(bisector_segments({{nan, 0}, {0, 0}}, {{10, 0}}, {-5, -5, 15, 5}).size(), 1u);
  // A point in both sets is the first set's: no split between it and itself.
  EXPECT_TRUE(bisector_segments({{1, 1}}, {{1, 1}}, {-5, -5, 5, 5}).empty());
}
