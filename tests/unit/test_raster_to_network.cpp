// Raster -> graph (StreetGAN post-processing) on small fixed rasters drawn here the way the
// rasteriser draws roads (every pixel whose centre is within half the road width of an axis),
// with asserted node and edge counts; and the WKB raster reader on good and bad bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include "core/error.hpp"
#include "core/raster/binary_image.hpp"
#include "core/raster/raster_to_network.hpp"
#include "core/raster/wkb_raster.hpp"

using namespace streetgen::core;

namespace {

struct Canvas {
  BinaryImage image;
  GeoTransform transform;
};

// size x size pixels of `pixel` m, upper-left corner at (1000, 2000 + size * pixel).
Canvas canvas(int size, double pixel) {
  Canvas c{BinaryImage(size, size), {}};
  c.transform.scale_x = pixel;
  c.transform.scale_y = -pixel;
  c.transform.ip_x = 1000.0;
  c.transform.ip_y = 2000.0 + size * pixel;
  return c;
}

// A road of width_px pixels along the segment between two pixel-space points (col, row).
void road(Canvas& c, Point a, Point b, double width_px) {
  for (int r = 0; r < c.image.height; ++r) {
    for (int col = 0; col < c.image.width; ++col) {
      if (point_segment_distance({col + 0.5, r + 0.5}, a, b) <= width_px / 2) c.image.set(r, col, 1);
    }
  }
}

RasterNetwork run(const Canvas& c, RasterNetworkParams params = {}) {
  GeosContext geos;
  RoadRaster raster;
  raster.transform = c.transform;
  raster.mask = c.image;
  return raster_to_network(geos, raster, params);
}

std::map<std::int64_t, int> degrees(const RasterNetwork& net) {
  std::map<std::int64_t, int> d;
  for (const RasterEdge& e : net.edges) {
    d[e.from_node]++;
    d[e.to_node]++;
  }
  return d;
}

int count_degree(const RasterNetwork& net, int degree) {
  int n = 0;
  for (auto [node, d] : degrees(net)) n += d == degree;
  return n;
}

// True when two edges cross (a proper crossing of two of their segments; touching at a shared
// node does not count).
bool edges_cross(const RasterNetwork& net) {
  auto side = [](Point a, Point b, Point p) { return cross(b - a, p - a); };
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < net.edges.size(); ++j) {
      const Polyline& l1 = net.edges[i].line;
      const Polyline& l2 = net.edges[j].line;
      for (std::size_t a = 1; a < l1.size(); ++a) {
        for (std::size_t b = 1; b < l2.size(); ++b) {
          double s1 = side(l1[a - 1], l1[a], l2[b - 1]), s2 = side(l1[a - 1], l1[a], l2[b]);
          double s3 = side(l2[b - 1], l2[b], l1[a - 1]), s4 = side(l2[b - 1], l2[b], l1[a]);
          if (((s1 > 0 && s2 < 0) || (s1 < 0 && s2 > 0)) && ((s3 > 0 && s4 < 0) || (s3 < 0 && s4 > 0))) return true;
        }
      }
    }
  }
  return false;
}

double total_length(const RasterNetwork& net) {
  double sum = 0;
  for (const RasterEdge& e : net.edges) sum += length(e.line);
  return sum;
}

}  // namespace

TEST(BinaryImage, CrossErosionAndDilation) {
  BinaryImage img(7, 7);
  for (int r = 1; r <= 5; ++r)
    for (int c = 1; c <= 5; ++c) img.set(r, c, 1);
  erode(img, 1);
  EXPECT_EQ(img.count(), 9u);  // the 3 x 3 inside
  dilate(img, 1);
  EXPECT_EQ(img.count(), 21u);  // 3 x 3 plus the four 3-pixel arms of the cross
  EXPECT_EQ(img.at(1, 1), 0);   // a cross never reaches the diagonal corner
  dilate(img, 1);
  EXPECT_EQ(img.at(1, 1), 1);
}

TEST(BinaryImage, ErosionKeepsRoadsWhereTheyLeaveTheRaster) {
  BinaryImage img(5, 5);
  for (int c = 0; c < 5; ++c)
    for (int r = 1; r <= 3; ++r) img.set(r, c, 1);  // a 3-pixel road across the raster
  erode(img, 1);
  EXPECT_EQ(img.count(), 5u) << "its middle row stays, out to both edges";
  EXPECT_EQ(img.at(2, 0), 1);
  EXPECT_EQ(img.at(2, 4), 1);
  dilate(img, 1);
  EXPECT_EQ(img.count(), 15u) << "and grows back";
}

TEST(BinaryImage, ZhangSuenThinsARoadToOnePixel) {
  Canvas c = canvas(60, 1.0);
  road(c, {5, 30}, {55, 30}, 9);
  zhang_suen_thin(c.image);
  // One pixel per column over the road's length, less the ends eaten by the thinning.
  for (int col = 10; col < 50; ++col) {
    int n = 0;
    for (int r = 0; r < 60; ++r) n += c.image.at(r, col);
    EXPECT_EQ(n, 1) << "column " << col;
  }
  BinaryImage again = c.image;
  zhang_suen_thin(again);
  EXPECT_EQ(again.pixels, c.image.pixels) << "thinning a skeleton changes nothing";
}

TEST(RasterToNetwork, CrossGivesOneJunctionAndFourArms) {
  Canvas c = canvas(101, 3.0);
  road(c, {0, 50.5}, {101, 50.5}, 15);
  road(c, {50.5, 0}, {50.5, 101}, 15);
  RasterNetwork net = run(c);
  EXPECT_EQ(net.edges.size(), 4u);
  EXPECT_EQ(net.node_count, 5u);
  EXPECT_EQ(count_degree(net, 4), 1);
  EXPECT_EQ(count_degree(net, 1), 4);
  // The junction sits on the crossing of the axes (world (1151.5, 2151.5)) within a pixel.
  for (const RasterEdge& e : net.edges) {
    Point j = degrees(net)[e.from_node] == 4 ? e.line.front() : e.line.back();
    EXPECT_NEAR(j.x, 1000 + 50.5 * 3, 3.0);
    EXPECT_NEAR(j.y, 2000 + 50.5 * 3, 3.0);
  }
  // Straight arms: Douglas-Peucker leaves two vertices.
  for (const RasterEdge& e : net.edges) EXPECT_EQ(e.line.size(), 2u);
}

TEST(RasterToNetwork, TJunction) {
  Canvas c = canvas(101, 3.0);
  road(c, {0, 30.5}, {101, 30.5}, 15);
  road(c, {50.5, 30.5}, {50.5, 101}, 15);
  RasterNetwork net = run(c);
  EXPECT_EQ(net.edges.size(), 3u);
  EXPECT_EQ(net.node_count, 4u);
  EXPECT_EQ(count_degree(net, 3), 1);
  EXPECT_EQ(count_degree(net, 1), 3);
}

TEST(RasterToNetwork, GridOfThreeByThreeRoads) {
  Canvas c = canvas(161, 3.0);
  for (double at : {30.5, 80.5, 130.5}) {
    road(c, {0, at}, {161, at}, 15);
    road(c, {at, 0}, {at, 161}, 15);
  }
  RasterNetwork net = run(c);
  EXPECT_EQ(count_degree(net, 4), 9);   // the crossings
  EXPECT_EQ(count_degree(net, 1), 12);  // the roads leaving the raster
  EXPECT_EQ(net.node_count, 21u);
  EXPECT_EQ(net.edges.size(), 24u);
  // 12 inner edges of 50 px = 150 m; 12 outer ones of 30.5 px to the raster's edge: thinning
  // stops half a road width short, and the dead ends are carried on to where the paint ends.
  EXPECT_NEAR(total_length(net), 12 * 150 + 12 * 30.5 * 3, 12 * 2.0);
}

TEST(RasterToNetwork, RingIsOneClosedEdge) {
  Canvas c = canvas(101, 3.0);
  const double pi = std::acos(-1.0);
  for (int k = 0; k < 72; ++k) {
    double a0 = 2 * pi * k / 72, a1 = 2 * pi * (k + 1) / 72;
    road(c, {50.5 + 35 * std::cos(a0), 50.5 + 35 * std::sin(a0)}, {50.5 + 35 * std::cos(a1), 50.5 + 35 * std::sin(a1)},
         11);
  }
  RasterNetwork net = run(c);
  ASSERT_EQ(net.edges.size(), 1u);
  EXPECT_EQ(net.node_count, 1u);
  const Polyline& line = net.edges[0].line;
  EXPECT_EQ(distance(line.front(), line.back()), 0.0);
  EXPECT_NEAR(length(line), 2 * pi * 35 * 3, 0.05 * 2 * pi * 35 * 3);
}

TEST(RasterToNetwork, ShortDeadEndSpurIsPrunedLongOneKept) {
  Canvas c = canvas(101, 3.0);
  road(c, {0, 50.5}, {101, 50.5}, 15);
  road(c, {30.5, 50.5}, {30.5, 64.5}, 15);  // reaches 14 px = 42 m from the axis: its skeleton is < 25 m
  RasterNetwork pruned = run(c);
  EXPECT_EQ(pruned.edges.size(), 1u);
  EXPECT_EQ(pruned.node_count, 2u);
  EXPECT_GE(pruned.stats.dead_ends_pruned, 1u);

  RasterNetworkParams keep;
  keep.min_dead_end_length = 0;
  RasterNetwork kept = run(c, keep);
  EXPECT_EQ(kept.edges.size(), 3u) << "without pruning the spur is a T";

  road(c, {70.5, 50.5}, {70.5, 101}, 15);  // a long side road stays
  RasterNetwork t = run(c);
  EXPECT_EQ(t.edges.size(), 3u);
  EXPECT_EQ(count_degree(t, 3), 1);
}

// Gap closing: 2 m pixels, roads 5 px = 10 m, no morphology (it would close small gaps itself),
// so that the gaps are exactly as drawn.
RasterNetworkParams no_morphology() {
  RasterNetworkParams p;
  p.erode = p.dilate = 0;
  return p;
}

TEST(RasterToNetwork, GapAheadOfADeadEndIsClosed) {
  // A side road that stops 14.5 px (29 m) of background short of the road it points at: a
  // generator's broken T. Its skeleton ends about 20 px = 40 m from the other road's axis.
  Canvas c = canvas(101, 2.0);
  road(c, {0, 20.5}, {101, 20.5}, 5);
  road(c, {50.5, 101}, {50.5, 40}, 5);
  RasterNetwork net = run(c, no_morphology());
  EXPECT_EQ(net.stats.gaps_closed, 1u);
  EXPECT_EQ(net.edges.size(), 3u) << "a T: the side road joined to the road ahead, which is split there";
  EXPECT_EQ(net.node_count, 4u);
  EXPECT_EQ(count_degree(net, 3), 1);
  EXPECT_EQ(count_degree(net, 1), 3) << "only the three ends at the raster's border";
  for (const RasterEdge& e : net.edges) {  // the junction on the road's axis, straight ahead
    Point j = degrees(net)[e.from_node] == 3 ? e.line.front() : e.line.back();
    EXPECT_NEAR(j.x, 1000 + 50.5 * 2, 2.0);
    EXPECT_NEAR(j.y, 2000 + (101 - 20.5) * 2, 2.0);
  }

  RasterNetworkParams off = no_morphology();
  off.max_gap = 0;
  RasterNetwork open = run(c, off);
  EXPECT_EQ(open.stats.gaps_closed, 0u);
  EXPECT_EQ(open.edges.size(), 2u) << "max_gap 0: the old behaviour, a road and a long dead end";
  EXPECT_EQ(count_degree(open, 1), 4);

  RasterNetworkParams near = no_morphology();
  near.max_gap = 30;  // shorter than the 40 m join
  EXPECT_EQ(run(c, near).edges.size(), 2u);
}

TEST(RasterToNetwork, RoadBrokenInTheMiddleIsWholeAgain) {
  // A straight road across the raster with 10 px = 20 m of background in its middle: two dead
  // ends facing each other. The first join reaches the other dead end itself (its end node), so
  // the road is one edge again, not a T with a stub.
  Canvas c = canvas(101, 2.0);
  road(c, {0, 50.5}, {45, 50.5}, 5);
  road(c, {56, 50.5}, {101, 50.5}, 5);
  RasterNetwork net = run(c, no_morphology());
  EXPECT_EQ(net.stats.gaps_closed, 1u);
  ASSERT_EQ(net.edges.size(), 1u);
  EXPECT_EQ(net.node_count, 2u);
  EXPECT_NEAR(length(net.edges[0].line), 101 * 2.0, 2 * 2.0) << "border to border";

  RasterNetworkParams off = no_morphology();
  off.max_gap = 0;
  EXPECT_EQ(run(c, off).edges.size(), 2u);
}

TEST(RasterToNetwork, GapClosingFollowsTheDeadEndsDirection) {
  // A side road turns to run 20 px = 40 m beside a road and ends there: the road is within
  // max_gap, but at 90 degrees from the dead end's direction (30 degrees ahead, it is 80 m away).
  Canvas c = canvas(101, 2.0);
  road(c, {0, 20.5}, {101, 20.5}, 5);
  road(c, {30.5, 101}, {30.5, 40.5}, 5);
  road(c, {30.5, 40.5}, {60, 40.5}, 5);
  RasterNetwork net = run(c, no_morphology());
  EXPECT_EQ(net.stats.gaps_closed, 0u);
  EXPECT_EQ(net.edges.size(), 2u);

  RasterNetworkParams wide = no_morphology();
  wide.gap_angle = 90;  // the whole half-plane ahead, the road beside it included
  RasterNetwork joined = run(c, wide);
  EXPECT_EQ(joined.stats.gaps_closed, 1u);
  EXPECT_EQ(joined.edges.size(), 3u);
  EXPECT_EQ(count_degree(joined, 3), 1);
}

TEST(RasterToNetwork, GapClosingNeverCrossesAnEdge) {
  // Two broken roads rise towards a road at 45 degrees, converging; the nearest point of the road
  // inside each one's 30-degree sector lies past the other's, so their two joins would cross.
  // The first (shortest) is made; the second would cross it, an edge by then, and is not.
  Canvas c = canvas(101, 2.0);
  road(c, {0, 20.5}, {101, 20.5}, 5);
  road(c, {0, 86}, {46, 40}, 5);
  road(c, {101, 86}, {55, 40}, 5);
  RasterNetwork net = run(c, no_morphology());
  EXPECT_EQ(net.stats.gaps_closed, 1u);
  EXPECT_FALSE(edges_cross(net)) << "no two edges cross";
  EXPECT_EQ(count_degree(net, 3), 1);
  EXPECT_EQ(net.edges.size(), 4u) << "the road in two, one broken road joined to it, the other still a dead end";
}

TEST(RasterToNetwork, TinyArtefactLoopIsRemoved) {
  // A 7 px road with a one-pixel hole: thinning goes around the hole, a loop of about 3 x 3 m.
  Canvas c = canvas(61, 1.0);
  road(c, {0, 30.5}, {61, 30.5}, 7);
  c.image.set(30, 30, 0);
  RasterNetworkParams raw;
  raw.erode = raw.dilate = 0;  // the paper's clean-up would close the hole before thinning
  raw.min_block_area = 0;
  raw.min_dead_end_length = 0;
  RasterNetwork loop = run(c, raw);
  EXPECT_EQ(loop.edges.size(), 4u) << "two ends, two junctions, a loop of two chains";

  RasterNetworkParams clean = raw;
  clean.min_block_area = 100;
  RasterNetwork net = run(c, clean);
  EXPECT_EQ(net.stats.small_faces, 1u);
  EXPECT_EQ(net.edges.size(), 1u);
  EXPECT_EQ(net.node_count, 2u);
}

TEST(RasterToNetwork, RasterWithRowsGoingNorthGivesTheSameGraph) {
  // The same artefact loop with scale_y > 0 (row 0 at the south): faces are found in world
  // coordinates, so the flip changes nothing but the coordinates.
  Canvas c = canvas(61, 1.0);
  c.transform.scale_y = 1.0;
  c.transform.ip_y = 2000.0;
  road(c, {0, 30.5}, {61, 30.5}, 7);
  c.image.set(30, 30, 0);
  RasterNetworkParams params;
  params.erode = params.dilate = 0;
  params.min_dead_end_length = 0;
  RasterNetwork net = run(c, params);
  EXPECT_EQ(net.stats.small_faces, 1u);
  EXPECT_EQ(net.edges.size(), 1u);
  ASSERT_EQ(net.node_count, 2u);
  EXPECT_NEAR(net.edges[0].line.front().y, 2030.5, 0.5);
}

TEST(RasterToNetwork, DiagonalRoadHasNoStaircaseTriangles) {
  Canvas c = canvas(101, 3.0);
  road(c, {0, 0}, {101, 101}, 15);
  road(c, {0, 101}, {40, 61}, 15);  // a diagonal side road meeting it at a right angle
  RasterNetworkParams params;
  params.min_block_area = 0;  // no face clean-up: the graph must not have faces at all
  RasterNetwork net = run(c, params);
  EXPECT_EQ(net.edges.size(), 3u);
  EXPECT_EQ(net.node_count, 4u);
  EXPECT_EQ(net.stats.small_faces, 0u);
}

TEST(RasterToNetwork, EmptyAndFullMasks) {
  Canvas c = canvas(20, 3.0);
  EXPECT_TRUE(run(c).edges.empty()) << "no road, no edge";
  std::fill(c.image.pixels.begin(), c.image.pixels.end(), 1);
  try {
    run(c);
    FAIL() << "an all-road raster must be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::bad_data);
    EXPECT_STREQ(e.what(), "rast has no background pixel");
  }
}

TEST(RasterToNetwork, BadParams) {
  Canvas c = canvas(20, 3.0);
  for (auto set : {+[](RasterNetworkParams& p) { p.simplify_tolerance = -1; },
                   +[](RasterNetworkParams& p) { p.min_block_area = NAN; },
                   +[](RasterNetworkParams& p) { p.min_dead_end_length = -0.5; },
                   +[](RasterNetworkParams& p) { p.erode = -1; }, +[](RasterNetworkParams& p) { p.dilate = 101; },
                   +[](RasterNetworkParams& p) { p.max_gap = -1; },
                   +[](RasterNetworkParams& p) { p.max_gap = INFINITY; },
                   +[](RasterNetworkParams& p) { p.gap_angle = 90.5; },
                   +[](RasterNetworkParams& p) { p.gap_angle = NAN; }}) {
    RasterNetworkParams p;
    set(p);
    try {
      run(c, p);
      FAIL() << "bad params accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
    }
  }
}

// ---- WKB rasters ----

namespace {

std::vector<std::uint8_t> header(std::uint16_t bands, std::uint16_t w, std::uint16_t h) {
  std::vector<std::uint8_t> out;
  auto put = [&out](const auto& v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), b, b + sizeof(v));
  };
  put(std::uint8_t{1});
  put(std::uint16_t{0});
  put(bands);
  for (double v : {3.0, -3.0, 500.0, 900.0, 0.0, 0.0}) put(v);
  put(std::int32_t{32633});
  put(w);
  put(h);
  return out;
}

void expect_error(const std::vector<std::uint8_t>& bytes, ErrorKind kind, const char* message) {
  try {
    read_wkb_raster(bytes.data(), bytes.size(), 0.5);
    ADD_FAILURE() << "accepted: " << message;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    EXPECT_STREQ(e.what(), message);
  }
}

}  // namespace

TEST(WkbRaster, RoundTripOf8BUI) {
  Canvas c = canvas(9, 3.0);
  road(c, {0, 4.5}, {9, 4.5}, 3);
  std::vector<std::uint8_t> bytes = write_wkb_raster(c.image, c.transform, 25832);
  RoadRaster r = read_wkb_raster(bytes.data(), bytes.size(), 0.5);
  EXPECT_EQ(r.srid, 25832);
  EXPECT_EQ(r.mask.width, 9);
  EXPECT_EQ(r.mask.pixels, c.image.pixels);
  EXPECT_DOUBLE_EQ(r.transform.ip_y, c.transform.ip_y);
  EXPECT_DOUBLE_EQ(r.transform.pixel_area(), 9.0);
}

TEST(WkbRaster, Float32WithThresholdAndNodata) {
  std::vector<std::uint8_t> bytes = header(1, 3, 1);
  bytes.push_back(0x40 | 10);  // 32BF with a nodata value
  float values[4] = {-9999.0f, 0.2f, -0.7f, -9999.0f};  // nodata, then the pixels
  const auto* b = reinterpret_cast<const std::uint8_t*>(values);
  bytes.insert(bytes.end(), b, b + sizeof(values));
  RoadRaster r = read_wkb_raster(bytes.data(), bytes.size(), 0.0);
  EXPECT_EQ(r.mask.pixels, (std::vector<std::uint8_t>{1, 0, 0}));
  EXPECT_EQ(r.srid, 32633);
  RoadRaster low = read_wkb_raster(bytes.data(), bytes.size(), -1.0);
  EXPECT_EQ(low.mask.pixels, (std::vector<std::uint8_t>{1, 1, 0})) << "nodata is never road";
}

TEST(WkbRaster, BadInput) {
  std::vector<std::uint8_t> two = header(2, 1, 1);
  expect_error(two, ErrorKind::invalid_argument, "rast must have exactly one band");
  std::vector<std::uint8_t> none = header(0, 1, 1);
  expect_error(none, ErrorKind::invalid_argument, "rast must have exactly one band");
  std::vector<std::uint8_t> empty = header(0, 0, 0);
  expect_error(empty, ErrorKind::invalid_argument, "rast is empty");
  std::vector<std::uint8_t> u16 = header(1, 1, 1);
  u16.insert(u16.end(), {6, 0, 0, 1, 0});  // 16BUI
  expect_error(u16, ErrorKind::invalid_argument, "rast must have pixel type 8BUI, 32BF, 64BF or 1BB");
  std::vector<std::uint8_t> offline = header(1, 1, 1);
  offline.insert(offline.end(), {0x80 | 4, 0, 1, 'x', 0});
  expect_error(offline, ErrorKind::invalid_argument, "rast must be an in-database raster");
  std::vector<std::uint8_t> cut = header(1, 4, 4);
  cut.insert(cut.end(), {4, 0, 1, 1});  // 2 of 16 pixels
  expect_error(cut, ErrorKind::bad_data, "rast is not a valid WKB raster");
  expect_error({}, ErrorKind::bad_data, "rast is not a valid WKB raster");
  std::vector<std::uint8_t> huge = header(1, 20000, 20000);
  huge.insert(huge.end(), {4, 0});
  expect_error(huge, ErrorKind::invalid_argument, "rast has too many pixels");
  std::vector<std::uint8_t> ok = header(1, 1, 1);
  ok.insert(ok.end(), {4, 0, 1});
  EXPECT_THROW(read_wkb_raster(ok.data(), ok.size(), NAN), Error);
  EXPECT_EQ(read_wkb_raster(ok.data(), ok.size(), 0.5).mask.count(), 1u);
}
