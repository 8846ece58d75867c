#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>

#include "core/streets/bisector.hpp"
#include "core/streets/polygon_contact.hpp"

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

// The same sites give the same segments to the last bit, whatever order they come in and
// wherever the triangulation's faces land in memory: the split line is noded with an overlap's
// boundary, where a last-bit change can change the faces (two Paris junctions changed shape from
// run to run). Sites as a junction's skeleton gives them: two bent polylines, sampled at
// uneven steps, so that faces are cocircular and circumcentres inexact.
TEST(Bisector, TheSameSitesGiveTheSameSegmentsInAnyOrder) {
  std::vector<Point> a, b;
  for (int k = 0; k <= 120; ++k) {
    double t = k / 120.0;
    a.push_back({-3727.0 + 31.7 * t, -936.8 + 13.1 * t + 2.0 * t * t});
    b.push_back({-3725.9 + 29.3 * t, -943.6 + 9.7 * t - 1.5 * t * t});
  }
  const Box clip{-3740, -960, -3680, -910};
  const std::vector<BisectorSegment> first = bisector_segments(a, b, clip);
  ASSERT_GT(first.size(), 50u);
  for (int round = 1; round <= 12; ++round) {
    std::vector<Point> ra = a, rb = b;
    std::rotate(ra.begin(), ra.begin() + (round * 17) % ra.size(), ra.end());
    if (round % 2 == 0) std::reverse(rb.begin(), rb.end());
    // Holes of assorted sizes in the heap, so that the triangulation's blocks of faces land
    // in another order in memory than they are allocated in.
    std::vector<std::unique_ptr<char[]>> ballast;
    for (int k = 0; k < 400; ++k) ballast.emplace_back(new char[1024 + static_cast<std::size_t>((k * 7919 + round * 104729) % 9000)]);
    for (std::size_t k = round % 3; k < ballast.size(); k += 2 + round % 3) ballast[k].reset();
    const std::vector<BisectorSegment> again = bisector_segments(ra, rb, clip);
    ASSERT_EQ(again.size(), first.size()) << "round " << round;
    for (std::size_t i = 0; i < first.size(); ++i) {
      EXPECT_EQ(std::memcmp(&again[i], &first[i], sizeof(BisectorSegment)), 0)
          << "round " << round << ", segment " << i << ": (" << again[i].from.x << " " << again[i].from.y << ", "
          << again[i].to.x << " " << again[i].to.y << ") against (" << first[i].from.x << " " << first[i].from.y << ", "
          << first[i].to.x << " " << first[i].to.y << ")";
    }
  }
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

// The exact "interiors meet" test that spares a junction its overlay with sections that only
// touch it.
TEST(PolygonContact, TouchingAlongAnEdgeIsApart) {
  Polyline junction{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}};
  Polyline section{{4, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 0}};
  EXPECT_FALSE(interiors_may_meet(junction, section));
  // Touching along part of an edge, with a vertex of one in the middle of the other's edge.
  Polyline stub{{4, 1}, {9, 1}, {9, 3}, {4, 3}};
  EXPECT_FALSE(interiors_may_meet(junction, stub));
  // Apart, and touching at a corner only.
  EXPECT_FALSE(interiors_may_meet(junction, {{5, 5}, {6, 5}, {6, 6}}));
  EXPECT_FALSE(interiors_may_meet(junction, {{4, 4}, {6, 4}, {6, 6}}));
}

TEST(PolygonContact, OverlapsAreFound) {
  Polyline junction{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  // Edges crossing properly.
  EXPECT_TRUE(interiors_may_meet(junction, {{3, 1}, {8, 1}, {8, 3}, {3, 3}}));
  // Inside, touching nothing; containing.
  EXPECT_TRUE(interiors_may_meet(junction, {{1, 1}, {2, 1}, {2, 2}}));
  EXPECT_TRUE(interiors_may_meet({{1, 1}, {2, 1}, {2, 2}}, junction));
  // The same polygon, and one with an extra vertex on an edge.
  EXPECT_TRUE(interiors_may_meet(junction, junction));
  EXPECT_TRUE(interiors_may_meet(junction, {{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}}));
  // Inscribed: every vertex of the triangle on the square's boundary, its edges through the inside.
  EXPECT_TRUE(interiors_may_meet(junction, {{0, 0}, {4, 2}, {2, 4}}));
  // A strip sharing two edges' lines with the square and overlapping it, every vertex of each on
  // the other's boundary or outside: only the middle of a cut edge is inside.
  EXPECT_TRUE(interiors_may_meet(junction, {{2, 0}, {6, 0}, {6, 4}, {2, 4}}));
  // Overlapping along a shared edge line where the overlap's edge runs between a vertex of each.
  EXPECT_TRUE(interiors_may_meet({{0, 0}, {4, 0}, {2, 2}}, {{2, 0}, {6, 0}, {4, 2}}));
}

// Two polygons sharing a segmentised arc (a curb shared by a junction and its sidewalk): the
// chords' middles, rounded to doubles, fall a hair inside either, yet a shared edge lies on both
// boundaries: apart. Moved inwards by a millimetre, the same arc overlaps.
TEST(PolygonContact, ASharedChainOfChordsIsABoundary) {
  const double r = 1.2602880658436213, pi = 3.14159265358979323846;
  Polyline arc;
  for (int k = 0; k <= 8; ++k) arc.push_back({r * std::cos(pi / 2 * k / 8), r * std::sin(pi / 2 * k / 8)});
  Polyline quarter_disc{{0, 0}};
  quarter_disc.insert(quarter_disc.end(), arc.begin(), arc.end());
  Polyline spandrel(arc.rbegin(), arc.rend());
  spandrel.push_back({r, r});
  EXPECT_FALSE(interiors_may_meet(quarter_disc, spandrel));
  EXPECT_FALSE(interiors_may_meet(spandrel, quarter_disc));
  Polyline dented = spandrel;
  dented[4] = 0.999 * dented[4];
  EXPECT_TRUE(interiors_may_meet(quarter_disc, dented));
}

// Only the edges near the other ring are looked at (where the two boxes meet); what lies there
// decides as before. A long roadway of 2,000 edges with a band along a stretch of its side,
// sharing its vertices there: apart; the band's vertex moved a nanometre into the roadway, or an
// arm of the roadway folded back into the band far from its own stretch, overlaps; a band beyond
// the roadway's box is apart.
TEST(PolygonContact, OnlyTheEdgesNearTheOtherRingAreTested) {
  Polyline roadway;
  for (int k = 0; k <= 1000; ++k) roadway.push_back({0.5 * k, 0.0});
  for (int k = 1000; k >= 0; --k) roadway.push_back({0.5 * k, -8.0});
  roadway.push_back(roadway.front());
  Polyline band{{100.0, 0.0}, {100.5, 0.0}, {101.0, 0.0}, {101.0, 2.0}, {100.0, 2.0}, {100.0, 0.0}};
  EXPECT_FALSE(interiors_may_meet(roadway, band));
  EXPECT_FALSE(interiors_may_meet(band, roadway));
  Polyline dented = band;
  dented[1].y = -1e-9;
  EXPECT_TRUE(interiors_may_meet(roadway, dented));
  EXPECT_TRUE(interiors_may_meet(dented, roadway));
  // The same roadway with an arm from its far end folded back over the band (a U-turn's curb).
  Polyline folded(roadway.begin(), roadway.begin() + 999);  // (the north side up to x = 499)
  for (Point p : Polyline{{499.0, 1.0}, {100.5, 1.0}, {100.5, 3.0}, {500.0, 3.0}}) folded.push_back(p);
  folded.insert(folded.end(), roadway.begin() + 1001, roadway.end());
  EXPECT_TRUE(interiors_may_meet(folded, band));
  Polyline beyond{{600.0, 0.0}, {601.0, 0.0}, {601.0, 2.0}, {600.0, 2.0}};
  EXPECT_FALSE(interiors_may_meet(roadway, beyond));
}

// A section whose flat end was computed apart from its junction's border line: its corners lie a
// hair inside the junction (UTM-sized coordinates, as on a real city), so the exact test says
// they may meet, and the overlap is a sliver of about 1e-8 m². Moved onto the junction's border
// points, the corners share the border edge: the bound covers the sliver and stays under a
// tenth of a square millimetre. A real overlap, a corner too far to move and two corners onto one
// point give no bound.
TEST(PolygonContact, TouchingButForRoundingIsBoundedBySweptArea) {
  const double x0 = 512345.25, y0 = 5412345.5;  // (a UTM position: a coordinate's ulp is 1e-9 m)
  auto at = [&](double x, double y) { return Point{x0 + x, y0 + y}; };
  const Polyline junction{at(0, 0), at(4, 0), at(4, 4), at(0, 4)};
  const double hair = 3e-9;
  const Polyline section{at(4 - hair, 0), at(30, 0), at(30, 4), at(4 - hair, 4)};
  ASSERT_TRUE(interiors_may_meet(junction, section));
  std::optional<double> bound = touching_overlap_bound(junction, section, 1e-6);
  ASSERT_TRUE(bound.has_value());
  const double sliver = hair * 4.0;  // (the true overlap: 4 m long, 3 nm wide)
  EXPECT_GE(*bound, sliver);
  EXPECT_LT(*bound, 1e-7);
  // Apart already: nothing to move, nothing shared.
  EXPECT_EQ(touching_overlap_bound(junction, Polyline{at(4, 0), at(30, 0), at(30, 4), at(4, 4)}, 1e-6), 0.0);
  // Overlapping by a metre: the moved ring still meets the junction.
  EXPECT_FALSE(touching_overlap_bound(junction, Polyline{at(3, 0), at(30, 0), at(30, 4), at(3, 4)}, 1e-6).has_value());
  // A corner a millimetre inside: beyond the snap, so it stays, and the interiors meet.
  EXPECT_FALSE(touching_overlap_bound(junction, Polyline{at(3.999, 0), at(30, 0), at(30, 4), at(4 - hair, 4)}, 1e-6).has_value());
  // Two corners of a sliver of a section within the snap of one junction vertex.
  EXPECT_FALSE(touching_overlap_bound(junction, Polyline{at(4 - hair, 0), at(4 - 2 * hair, hair), at(30, 2), at(4 - hair, 4)}, 1e-6)
                   .has_value());
}
