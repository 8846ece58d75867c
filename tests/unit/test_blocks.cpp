#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
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
  EXPECT_EQ(stats.winding_faces, 2u);    // each face in one pass: nothing clipped, nothing united
  EXPECT_EQ(stats.clipped_pairs, 0u);
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

// A face at a time, the pieces as EWKB: each face read for its box, then again when its turn
// comes, its cut handed over before the next is read, with the cuts the whole-vector call makes;
// a piece read only while the faces that need it are cut.
TEST(Blocks, FacesAreReadAndCutOneAtATime) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 100 0, 100 100, 0 100, 0 0))"));
  faces.push_back(test::wkt(ctx, "POLYGON((100 0, 200 0, 200 100, 100 100, 100 0))"));
  faces.push_back(test::wkt(ctx, "POLYGON((300 0, 310 0, 310 10, 300 10, 300 0))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "POLYGON((96 -10, 104 -10, 104 110, 96 110, 96 -10))"));
  pieces.push_back(test::wkt(ctx, "POLYGON((299 -1, 311 -1, 311 11, 299 11, 299 -1))"));  // covers the third
  auto whole = core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6);
  std::vector<core::Bytes> ewkb;
  for (const auto& p : pieces) ewkb.push_back(core::write_ewkb(ctx, p.get(), 2154));
  std::vector<core::WkbView> views;
  for (const auto& b : ewkb) views.push_back({b.data(), b.size()});
  std::vector<std::string> calls;
  std::vector<core::GeomPtr> cuts(faces.size());
  core::FaceCutStats stats;
  core::faces_minus_pieces(
      ctx, faces.size() + 1,
      [&](std::size_t f) {
        calls.push_back("read " + std::to_string(f));
        if (f == faces.size()) return core::GeomPtr(nullptr, core::GeomDeleter{ctx.handle()});  // no face: a null cut
        return core::own(ctx, GEOSGeom_clone_r(ctx.handle(), faces[f].get()), "clone");
      },
      views, 1e-6,
      [&](std::size_t f, core::GeomPtr cut) {
        calls.push_back("cut " + std::to_string(f) + (cut ? "" : " null"));
        if (f < cuts.size()) cuts[f] = std::move(cut);
      },
      &stats);
  // every face once for its box, then a face at a time (along the curve); the missing one, read
  // once, cut as null at the end
  ASSERT_EQ(calls.size(), 4u + 2 * 3u + 1u);
  EXPECT_EQ(std::vector<std::string>(calls.begin(), calls.begin() + 4),
            (std::vector<std::string>{"read 0", "read 1", "read 2", "read 3"}));
  for (std::size_t k = 4; k + 1 < calls.size(); k += 2) {
    std::string f = calls[k].substr(5);
    EXPECT_EQ(calls[k], "read " + f);
    EXPECT_EQ(calls[k + 1].rfind("cut " + f, 0), 0u) << calls[k + 1];
  }
  EXPECT_EQ(calls.back(), "cut 3 null");
  EXPECT_EQ(stats.faces, 3u);
  EXPECT_EQ(stats.pieces, 2u);
  EXPECT_EQ(stats.pieces_held_at_most, 1u);  // the street for the first two faces, then the cover of the third
  ASSERT_EQ(whole.size(), cuts.size());
  for (std::size_t f = 0; f < cuts.size(); ++f) {
    ASSERT_EQ(static_cast<bool>(whole[f]), static_cast<bool>(cuts[f])) << f;
    if (cuts[f]) {
      EXPECT_EQ(GEOSEqualsExact_r(ctx.handle(), whole[f].get(), cuts[f].get(), 0.0), 1) << f;
    }
  }
  ASSERT_TRUE(cuts[0]);
  EXPECT_NEAR(area(ctx, cuts[0].get()), 10000 - 400, 1e-6);
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

// A junction's sidewalk is one MultiPolygon with a part in each face around the junction: each
// part meets its own face only (whole, its box met the face between them too, and it was clipped
// against both faces it touches).
TEST(Blocks, EachPartOfAPieceMeetsOnlyItsOwnFace) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 100 0, 100 100, 0 100, 0 0))"));
  faces.push_back(test::wkt(ctx, "POLYGON((100 0, 200 0, 200 100, 100 100, 100 0))"));
  faces.push_back(test::wkt(ctx, "POLYGON((200 0, 300 0, 300 100, 200 100, 200 0))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "MULTIPOLYGON(((10 10, 20 10, 20 20, 10 20, 10 10)), ((280 80, 290 80, 290 90, 280 90, 280 80)))"));
  core::FaceCutStats stats;
  auto out = core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6, &stats);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_TRUE(out[0] && out[1] && out[2]);
  EXPECT_NEAR(area(ctx, out[0].get()), 10000 - 100, 1e-6);
  EXPECT_NEAR(area(ctx, out[1].get()), 10000, 1e-6);
  EXPECT_NEAR(area(ctx, out[2].get()), 10000 - 100, 1e-6);
  EXPECT_EQ(stats.candidate_pairs, 2u);
  EXPECT_EQ(stats.clipped_pairs, 0u);
  EXPECT_EQ(stats.winding_faces, 3u);
}

// A piece with a hole: the hole is not the piece's, so what of the face lies in it is block (a
// courtyard inside a ring of roadway, as a junction round an island has).
TEST(Blocks, WhatLiesInAPiecesHoleIsBlock) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 100 0, 100 100, 0 100, 0 0))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "POLYGON((20 20, 80 20, 80 80, 20 80, 20 20), (40 40, 60 40, 60 60, 40 60, 40 40))"));
  pieces.push_back(test::wkt(ctx, "POLYGON((-5 -5, 105 -5, 105 5, -5 5, -5 -5))"));
  core::FaceCutStats stats;
  auto out = core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6, &stats);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(out[0]);
  EXPECT_EQ(GEOSGetNumGeometries_r(ctx.handle(), out[0].get()), 2);  // the block round the ring, the courtyard
  EXPECT_NEAR(area(ctx, out[0].get()), 100 * 95 - (3600 - 400), 1e-6);
  EXPECT_EQ(stats.winding_faces, 0u);  // a hole would count +1 in the winding pass
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), out[0].get()), 1);
}

// Paris (face 11,693 of the example graph, three of its pieces, coordinates as stored): a
// narrowed section with a hole of 12.8 m² outside the face, one vertex of the hole 1e-13 m from a
// vertex of a junction's ring. A winding pass that counted the hole +1 kept the hole as block
// (3,819.76 m² instead of 3,806.95); the face must come out as the face minus the two pieces.
TEST(Blocks, AHoleOfAPieceOutsideTheFaceIsNotBlock) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx,
      "POLYGON((-6340.913089984835 670.4526600916621,-6324.14 687.28,-6301.52 717,-6295.878116041869 726.6723751333479,"
      "-6285.53 738.87,-6262.1860559237675 770.5904122109906,-6249.858850956799 753.2926807266973,-6268.44 726.03,"
      "-6293.4025342454715 697.757135882396,-6316.41 672.25,-6357.96 613.16,-6378.327056555102 579.5447040506426,"
      "-6400.693693494208 577.005857209565,-6374.29 620.71,-6340.913089984835 670.4526600916621))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx,
      "POLYGON((-6315.340810701859 696.1579792101653,-6317.926962222433 698.1263085303332,"
      "-6313.868147916737 694.6466183908695,-6324.543873296778 703.7035984399789,-6281.115618520149 757.733809215394,"
      "-6280.544885749683 757.4538384130752,-6284.236408111745 752.4376932994525,-6272.960706862907 744.1395874103376,"
      "-6315.340810701859 696.1579792101653))"));
  pieces.push_back(test::wkt(ctx,
      "POLYGON((-6260.536632644045 761.0217712553319,-6272.960706862907 744.1395874103376,"
      "-6284.236408111745 752.4376932994525,-6271.8123338928835 769.3198771444468,-6260.536632644045 761.0217712553319),"
      "(-6275.591717314888 764.1843439347251,-6280.544885749683 757.4538384130753,-6278.197780071312 756.3024745981602,"
      "-6276.681080775582 759.394332691383,-6276.552058660336 759.764938698509,-6275.591717314888 764.1843439347251))"));
  auto out = core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(out[0]);
  EXPECT_NEAR(area(ctx, out[0].get()), 3806.9494, 1e-3);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), out[0].get()), 1);
}

// A face with a hole (an island of streets inside it that polygonize leaves out of it): the hole
// stays out of the block, and a piece across the hole's edge takes only what lies in the face.
TEST(Blocks, AFacesHoleStaysOutOfItsBlock) {
  core::GeosContext ctx;
  std::vector<core::GeomPtr> faces;
  faces.push_back(test::wkt(ctx, "POLYGON((0 0, 100 0, 100 100, 0 100, 0 0), (40 40, 60 40, 60 60, 40 60, 40 40))"));
  std::vector<core::GeomPtr> pieces;
  pieces.push_back(test::wkt(ctx, "POLYGON((35 45, 50 45, 50 55, 35 55, 35 45))"));  // 50 m² in the face, 50 in the hole
  pieces.push_back(test::wkt(ctx, "POLYGON((45 45, 55 45, 55 55, 45 55, 45 45))"));  // inside the hole only
  core::FaceCutStats stats;
  auto out = core::faces_minus_pieces(ctx, raw(faces), raw(pieces), 1e-6, &stats);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(out[0]);
  EXPECT_NEAR(area(ctx, out[0].get()), 10000 - 400 - 50, 1e-6);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), out[0].get()), 1);
  EXPECT_EQ(stats.winding_faces, 1u);
}

// The polygons' boxes read from the bytes are GEOS's envelopes of the same polygons, in the same
// order, whatever the byte order, dimensions and SRID flag; bytes it does not know are refused.
TEST(Blocks, PolygonBoxesReadFromWkbAreGeosEnvelopes) {
  core::GeosContext ctx;
  GEOSContextHandle_t h = ctx.handle();
  const char* cases[] = {
      "POLYGON((0 0, 10 0, 10 5, 0 5, 0 0), (1 1, 2 1, 2 2, 1 1))",
      "MULTIPOLYGON(((0 0, 1 0, 1 1, 0 0)), EMPTY, ((5 5, 9 5, 9 7, 5 5)))",
      "GEOMETRYCOLLECTION(POINT(100 100), LINESTRING(-50 0, 50 0), POLYGON((3 3, 4 3, 4 8, 3 3)),"
      " GEOMETRYCOLLECTION(MULTIPOLYGON(((-7 -7, -6 -7, -6 -6, -7 -7)))))",
      "POLYGON Z((0 0 1, 10 0 2, 10 5 3, 0 0 1))",
      "POLYGON EMPTY",
  };
  std::function<void(const GEOSGeometry*, std::vector<core::Box>&)> envelopes = [&](const GEOSGeometry* g,
                                                                                   std::vector<core::Box>& out) {
    int type = GEOSGeomTypeId_r(h, g);
    if (type == GEOS_POLYGON) {
      if (GEOSisEmpty_r(h, g) != 0) return;
      core::Box b{};
      GEOSGeom_getXMin_r(h, g, &b.xmin);
      GEOSGeom_getYMin_r(h, g, &b.ymin);
      GEOSGeom_getXMax_r(h, g, &b.xmax);
      GEOSGeom_getYMax_r(h, g, &b.ymax);
      out.push_back(b);
    } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
      for (int i = 0; i < GEOSGetNumGeometries_r(h, g); ++i) envelopes(GEOSGetGeometryN_r(h, g, i), out);
    }
  };
  int polygons = 0;
  for (const char* wkt : cases) {
    core::GeomPtr g = test::wkt(ctx, wkt);
    GEOSSetSRID_r(h, g.get(), 2154);
    std::vector<core::Box> expected;
    envelopes(g.get(), expected);
    polygons += static_cast<int>(expected.size());
    for (int order : {GEOS_WKB_NDR, GEOS_WKB_XDR}) {
      for (bool with_srid : {false, true}) {
        GEOSWKBWriter* writer = GEOSWKBWriter_create_r(h);
        GEOSWKBWriter_setByteOrder_r(h, writer, order);
        GEOSWKBWriter_setOutputDimension_r(h, writer, 3);
        GEOSWKBWriter_setIncludeSRID_r(h, writer, with_srid ? 1 : 0);
        std::size_t size = 0;
        unsigned char* bytes = GEOSWKBWriter_write_r(h, writer, g.get(), &size);
        GEOSWKBWriter_destroy_r(h, writer);
        ASSERT_NE(bytes, nullptr);
        std::vector<core::Box> boxes, short_boxes;
        bool read = core::wkb_polygon_boxes({bytes, size}, boxes);
        bool cut_short = core::wkb_polygon_boxes({bytes, size - 1}, short_boxes);
        GEOSFree_r(h, bytes);
        ASSERT_TRUE(read) << wkt << " " << order << " " << with_srid;
        EXPECT_FALSE(cut_short) << wkt;
        ASSERT_EQ(boxes.size(), expected.size()) << wkt;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
          EXPECT_EQ(boxes[i].xmin, expected[i].xmin) << wkt << " " << i;
          EXPECT_EQ(boxes[i].ymin, expected[i].ymin) << wkt << " " << i;
          EXPECT_EQ(boxes[i].xmax, expected[i].xmax) << wkt << " " << i;
          EXPECT_EQ(boxes[i].ymax, expected[i].ymax) << wkt << " " << i;
        }
      }
    }
  }
  EXPECT_EQ(polygons, 1 + 2 + 2 + 1 + 0);
  const std::uint8_t unknown[] = {1, 99, 0, 0, 0};
  std::vector<core::Box> boxes;
  EXPECT_FALSE(core::wkb_polygon_boxes({unknown, sizeof unknown}, boxes));
}
