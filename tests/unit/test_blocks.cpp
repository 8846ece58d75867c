#include <gtest/gtest.h>

#include <vector>

#include "core/error.hpp"
#include "core/streets/blocks.hpp"
#include "test_support.hpp"

using namespace streetgen;

namespace {
double area(core::GeosContext& ctx, const GEOSGeometry* g) {
  double a = -1;
  GEOSArea_r(ctx.handle(), g, &a);
  return a;
}
std::vector<const GEOSGeometry*> raw(const std::vector<core::GeomPtr>& v) {
  std::vector<const GEOSGeometry*> out;
  for (const auto& g : v) out.push_back(g.get());
  return out;
}
}  // namespace

// Two 100 m faces side by side; a street along the shared edge (half on each), a sidewalk inside
// the left face, one piece far away, and one that covers the right face's corner from outside.
TEST(Blocks, EachFaceLosesWhatLiesOnIt) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 100 0, 100 100, 0 100, 0 0))"));
  faces.push_back(test::wkt(ctx, "POLYGON((100 0, 200 0, 200 100, 100 100, 100 0))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "POLYGON((96 -10, 104 -10, 104 110, 96 110, 96 -10))"));  // 4 m on each face
  pieces.push_back(test::wkt(ctx, "POLYGON((10 10, 20 10, 20 20, 10 20, 10 10))"));           // inside the left one
  pieces.push_back(test::wkt(ctx, "POLYGON((500 500, 510 500, 510 510, 500 510, 500 500))"));  // far away
  pieces.push_back(test::wkt(ctx, "POLYGON((190 90, 210 90, 210 110, 190 110, 190 90))"));     // 100 m2 of the right one
  core::FaceCutStats stats;
  auto out = core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6, &stats);
  ASSERT_EQ(out.size(), 2u);
  ASSERT_TRUE(out[0]);
  ASSERT_TRUE(out[1]);
  EXPECT_EQ(GEOSGeomTypeId_r(ctx.handle(), out[0].get()), GEOS_MULTIPOLYGON);
  EXPECT_NEAR(area(ctx, out[0].get()), 10000 - 400 - 100, 1e-6);
  EXPECT_NEAR(area(ctx, out[1].get()), 10000 - 400 - 100, 1e-6);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), out[0].get()), 1);
  EXPECT_EQ(stats.faces, 2u);
  EXPECT_EQ(stats.candidate_pairs, 4u);  // the street on both, the sidewalk on the left, the corner on the right
  EXPECT_EQ(stats.clipped_pairs, 3u);    // the sidewalk inside needs no overlay
  EXPECT_EQ(stats.grid_faces, 0u);
}

TEST(Blocks, NothingLeftIsNullAndNoPiecesIsTheFace) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 10 0, 10 10, 0 10, 0 0))"));
  faces.push_back(test::wkt(ctx, "POLYGON((100 0, 110 0, 110 10, 100 10, 100 0))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "POLYGON((-1 -1, 11 -1, 11 11, -1 11, -1 -1))"));
  std::vector<const GEOSGeometry*> face_ptrs = raw(faces);
  face_ptrs.push_back(nullptr);
  auto out = core::faces_minus_pieces(ctx, face_ptrs, raw(pieces), 1e-6);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_FALSE(out[0]);
  ASSERT_TRUE(out[1]);
  EXPECT_EQ(GEOSGeomTypeId_r(ctx.handle(), out[1].get()), GEOS_MULTIPOLYGON);
  EXPECT_NEAR(area(ctx, out[1].get()), 100, 1e-9);
  EXPECT_FALSE(out[2]);
}

TEST(Blocks, RefusesABadGrid) {
  core::GeosContext ctx;
  try {
    core::faces_minus_pieces(ctx, {}, {}, 0.0);
    FAIL() << "expected an error";
  } catch (const core::Error& e) {
    EXPECT_EQ(e.kind(), core::ErrorKind::invalid_argument);
  }
}

namespace {
// A 100 m square face with a street along its bottom edge (its roadway up to y = 5) and
// `sidewalk` beside it: the face minus both.
std::vector<core::GeomPtr> square_minus_street_and(core::GeosContext& ctx, const char* sidewalk) {
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 100 0, 100 100, 0 100, 0 0))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "POLYGON((-10 -5, 110 -5, 110 5, -10 5, -10 -5))"));
  pieces.push_back(test::wkt(ctx, sidewalk));
  return core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6);
}
}  // namespace

// Two surfaces whose edges meet up to rounding leave a gap nanometres wide between them: the
// block keeps the real part only, not that sliver.
TEST(Blocks, SliversBetweenSurfacesAreNotPartsOfTheBlock) {
  core::GeosContext ctx;
  // A sidewalk along the street 1e-7 m off its edge: a gap across the face, 100 m long, of
  // 1e-5 m2, cut off from the rest of the face by the sidewalk.
  auto out = square_minus_street_and(ctx, "POLYGON((-10 5.0000001, 110 5.0000001, 110 8, -10 8, -10 5.0000001))");
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(out[0]);
  EXPECT_EQ(GEOSGetNumGeometries_r(ctx.handle(), out[0].get()), 1);
  EXPECT_NEAR(area(ctx, out[0].get()), 100 * 92, 1e-3);
}

// Where a sidewalk meets its roadway up to rounding and ends short of the next street, the gap
// between them opens onto the block: a channel of no width, 50 m long, that the block must not
// keep (it doubled the perimeter of some blocks; the block is rounded to the grid, which closes it).
TEST(Blocks, AGapBetweenSurfacesOpeningOntoTheBlockIsNotPartOfIt) {
  core::GeosContext ctx;
  auto out = square_minus_street_and(ctx, "POLYGON((-10 5.0000001, 50 5.0000001, 50 8, -10 8, -10 5.0000001))");
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(out[0]);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), out[0].get()), 1);
  EXPECT_NEAR(area(ctx, out[0].get()), 100 * 95 - 50 * 3, 1e-3);
  double perimeter = 0.0;
  GEOSLength_r(ctx.handle(), out[0].get(), &perimeter);
  EXPECT_NEAR(perimeter, 50 + 3 + 50 + 95 + 100 + 92, 1e-3);
}
