#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/error.hpp"
#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"
#include "core/growth/terrain.hpp"
#include "patch_fixtures.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::avenue_grid;
using streetgen::test::wkt;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// A DEM of 10 m cells over [-1000, 2000] x [-1000, 2000] with heights z(x, y).
GridField dem_of(const std::function<double(double, double)>& z) {
  GridField g;
  g.origin_x = -1000.0;
  g.origin_y = 2000.0;
  g.scale_x = 10.0;
  g.scale_y = -10.0;
  g.width = 300;
  g.height = 300;
  g.bands = 1;
  g.values.resize(300 * 300);
  for (int r = 0; r < 300; ++r) {
    for (int c = 0; c < 300; ++c) g.values[r * 300 + c] = z(-1000.0 + 10.0 * (c + 0.5), 2000.0 - 10.0 * (r + 0.5));
  }
  return g;
}

std::function<bool(Point, Point)> any_land() {
  return [](Point, Point) { return true; };
}

}  // namespace

TEST(Terrain, GradeOfATiltedPlane) {
  GridField dem = dem_of([](double x, double) { return 0.2 * x; });  // 20 % up to the east
  EXPECT_NEAR(grade(dem, {0, 0}, {100, 0}), 0.2, 1e-9);
  EXPECT_NEAR(grade(dem, {100, 0}, {0, 0}), 0.2, 1e-9);  // downhill is as steep
  EXPECT_NEAR(grade(dem, {0, 0}, {0, 100}), 0.0, 1e-9);  // along the contour
  EXPECT_NEAR(grade(dem, {0, 0}, {100, 100}), 0.2 / std::sqrt(2.0), 1e-9);
  Point g = terrain_gradient(dem, {0, 0});
  EXPECT_NEAR(g.x, 0.2, 1e-9);
  EXPECT_NEAR(g.y, 0.0, 1e-9);
  // Off the raster and on nodata: unknown terrain constrains nothing.
  EXPECT_EQ(grade(dem, {5000, 0}, {5100, 0}), 0.0);
  GridField unknown = dem_of([](double, double) { return NAN; });
  EXPECT_EQ(grade(unknown, {0, 0}, {100, 0}), 0.0);
  EXPECT_TRUE(std::isnan(terrain_gradient(unknown, {0, 0}).x));
  EXPECT_EQ(grade(GridField{}, {0, 0}, {100, 0}), 0.0);
}

TEST(Terrain, GradeFindsTheSteepPartOfAStreet) {
  // Flat west of x = 300, 40 % up east of it: a street across the step is as steep as its
  // steepest part, not its mean.
  GridField dem = dem_of([](double x, double) { return x > 300 ? 0.4 * (x - 300) : 0.0; });
  EXPECT_NEAR(grade(dem, {0, 0}, {200, 0}), 0.0, 1e-9);
  EXPECT_NEAR(grade(dem, {200, 0}, {400, 0}), 0.4, 0.02);
  EXPECT_GT(grade(dem, {200, 0}, {400, 0}), 0.3);  // the mean would be 0.2
}

TEST(Terrain, BendToContour) {
  GridField dem = dem_of([](double x, double) { return 0.2 * x; });
  auto all = [](double) { return true; };
  // East is 20 %; 10 % is reached at 60° from east: the first 5° step at or past it, towards the
  // nearer contour direction (north, from east).
  double a = bend_to_contour(dem, {0, 0}, 0.0, 100.0, 0.1 + 1e-9, 5.0 * kDeg, all);
  ASSERT_FALSE(std::isnan(a));
  EXPECT_NEAR(a, 60.0 * kDeg, 1e-9);
  EXPECT_LE(grade(dem, {0, 0}, Point{0, 0} + 100.0 * Point{std::cos(a), std::sin(a)}), 0.1 + 1e-9);
  // From a bit south of east, it bends south.
  double b = bend_to_contour(dem, {0, 0}, -10.0 * kDeg, 100.0, 0.1 + 1e-9, 5.0 * kDeg, all);
  EXPECT_NEAR(b, -60.0 * kDeg, 1e-6);
  // Bends the node does not allow, a flat DEM, an unknown one: discarded (NaN).
  EXPECT_TRUE(std::isnan(bend_to_contour(dem, {0, 0}, 0.0, 100.0, 0.1, 5.0 * kDeg, [](double x) { return x < 0.5; })));
  GridField flat = dem_of([](double, double) { return 3.0; });
  EXPECT_TRUE(std::isnan(bend_to_contour(flat, {0, 0}, 0.0, 100.0, 0.1, 5.0 * kDeg, all)));
  GridField unknown = dem_of([](double, double) { return NAN; });
  EXPECT_TRUE(std::isnan(bend_to_contour(unknown, {0, 0}, 0.0, 100.0, 0.1, 5.0 * kDeg, all)));
}

TEST(Terrain, WaterCrossingReachesTheFarBankShortestWay) {
  GeosContext geos;
  GeomPtr river = wkt(geos, "POLYGON((-1000 100, 1000 100, 1000 160, -1000 160, -1000 100))");  // 60 m wide
  // From (0, 50) north-east at 60°: turned up to 30°, the crossing straight north is shortest.
  std::vector<double> angles;
  for (int k = 0; k <= 6; ++k) angles.push_back((60.0 + 5.0 * k) * kDeg);
  WaterCrossing c = find_water_crossing(geos, river.get(), {0, 50}, angles, 100.0, 300.0, 20.0, any_land());
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.angle, 90.0 * kDeg, 1e-9);
  EXPECT_NEAR(c.entry, 50.0, 1e-6);
  EXPECT_NEAR(c.exit, 110.0, 1e-6);
  EXPECT_GT(c.setback, 0.0);
  // Unturned, along the first angle only: the oblique crossing.
  WaterCrossing d = find_water_crossing(geos, river.get(), {0, 50}, {60.0 * kDeg}, 100.0, 300.0, 20.0, any_land());
  ASSERT_TRUE(d.found);
  EXPECT_NEAR(d.exit - d.entry, 60.0 / std::sin(60.0 * kDeg), 1e-6);
  // Wider than bridge_distance, water not within the approach, the far bank refused: none.
  EXPECT_FALSE(find_water_crossing(geos, river.get(), {0, 50}, {90.0 * kDeg}, 100.0, 50.0, 20.0, any_land()).found);
  EXPECT_FALSE(find_water_crossing(geos, river.get(), {0, 50}, {90.0 * kDeg}, 20.0, 300.0, 20.0, any_land()).found);
  EXPECT_FALSE(find_water_crossing(geos, river.get(), {0, 50}, {90.0 * kDeg}, 100.0, 300.0, 20.0,
                                   [](Point, Point) { return false; })
                   .found);
  // Away from the water: none.
  EXPECT_FALSE(find_water_crossing(geos, river.get(), {0, 50}, {-90.0 * kDeg}, 100.0, 300.0, 20.0, any_land()).found);
}

TEST(Terrain, NoBridgeToTheSeaOrToASliverOfLand) {
  GeosContext geos;
  GeomPtr sea = wkt(geos, "POLYGON((-1000 100, 1000 100, 1000 5000, -1000 5000, -1000 100))");
  EXPECT_FALSE(find_water_crossing(geos, sea.get(), {0, 50}, {90.0 * kDeg}, 100.0, 300.0, 20.0, any_land()).found);
  // A river, 5 m of land, then another river: no room to land.
  GeomPtr two = wkt(geos, "MULTIPOLYGON(((-1000 100, 1000 100, 1000 160, -1000 160, -1000 100)),"
                          "((-1000 165, 1000 165, 1000 200, -1000 200, -1000 165)))");
  EXPECT_FALSE(find_water_crossing(geos, two.get(), {0, 50}, {90.0 * kDeg}, 100.0, 300.0, 20.0, any_land()).found);
}

namespace {
// Segment a-b meets the band y in [y0, y1] (the river spans the whole region).
bool meets_band(const GrownEdge& e, double y0, double y1) {
  return std::max(e.a.y, e.b.y) >= y0 && std::min(e.a.y, e.b.y) <= y1;
}

struct RiverFixture {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-600 -600, 1200 -600, 1200 1400, -600 1400, -600 -600))");
  GeomPtr river = wkt(geos, "POLYGON((-700 600, 1300 600, 1300 680, -700 680, -700 600))");  // 80 m wide, splits it
  GrowInput input() {
    GrowInput in;
    in.patches = extract_patches(geos, avenue_grid(), PatchParams{}).patches;
    in.region = region.get();
    in.water = {river.get()};
    in.seeds = {{300.0, 200.0}};
    return in;
  }
  GrowParams params() const {
    GrowParams p;
    p.use_patches = true;
    p.seed = 2;
    p.max_edges = 4000;
    return p;
  }
};
}  // namespace

TEST(GrowPatchesWater, ArterialsBridgeTheRiverLocalStreetsNeverCrossIt) {
  RiverFixture f;
  GrowInput in = f.input();
  GrowResult r = grow_example(f.geos, in, f.params());
  ASSERT_GT(r.edges.size(), 200u);
  std::size_t bridges = 0, north = 0, wet_non_bridges = 0;
  for (const GrownEdge& e : r.edges) {
    if (e.bridge) {
      ++bridges;
      EXPECT_EQ(e.road_class, "avenue");  // arterials only
      EXPECT_LE(distance(e.a, e.b), 300.0 + 2.0);
      // Both ends on land, on either bank.
      EXPECT_LT(std::min(e.a.y, e.b.y), 600.0);
      EXPECT_GT(std::max(e.a.y, e.b.y), 680.0);
    } else {
      wet_non_bridges += meets_band(e, 600.0, 680.0);
    }
    north += std::min(e.a.y, e.b.y) > 680.0;
  }
  EXPECT_GT(bridges, 0u);
  EXPECT_EQ(bridges, r.stats.bridges);
  EXPECT_EQ(wet_non_bridges, 0u);
  EXPECT_GT(north, 20u);  // the growth went on across the river
  // Without bridges, nothing reaches the far bank from the south.
  GrowParams off = f.params();
  off.bridge_distance = 0.0;
  GrowResult s = grow_example(f.geos, in, off);
  std::size_t north_off = 0;
  for (const GrownEdge& e : s.edges) {
    EXPECT_FALSE(e.bridge);
    EXPECT_FALSE(meets_band(e, 600.0, 680.0));
    north_off += std::max(e.a.y, e.b.y) > 680.0;
  }
  EXPECT_EQ(north_off, 0u);
  // A river wider than bridge_distance is not bridged either.
  GrowParams short_reach = f.params();
  short_reach.bridge_distance = 50.0;
  GrowResult t = grow_example(f.geos, in, short_reach);
  for (const GrownEdge& e : t.edges) EXPECT_FALSE(e.bridge);
  EXPECT_GT(t.stats.bridges_failed, 0u);
}

TEST(GrowPatchesWater, BadWaterIsRejected) {
  RiverFixture f;
  GrowInput in = f.input();
  GeomPtr flood = wkt(f.geos, "POLYGON((-700 -700, 1300 -700, 1300 1500, -700 1500, -700 -700))");
  in.water = {flood.get()};
  EXPECT_THROW(grow_example(f.geos, in, f.params()), Error);  // water covers the whole region
  in.water = {f.river.get()};
  in.seeds = {{300.0, 640.0}};
  EXPECT_THROW(grow_example(f.geos, in, f.params()), Error);  // a seed in the river
  GeomPtr line = wkt(f.geos, "LINESTRING(-700 640, 1300 640)");
  in = f.input();
  in.water = {line.get()};
  EXPECT_THROW(grow_example(f.geos, in, f.params()), Error);  // water must be polygonal
  in = f.input();
  GrowParams p = f.params();
  p.bridge_distance = -1.0;
  EXPECT_THROW(grow_example(f.geos, in, p), Error);
  p = f.params();
  p.max_slope = 0.0;
  EXPECT_THROW(grow_example(f.geos, in, p), Error);
  p = f.params();
  p.bridge_turn = 90.0;
  EXPECT_THROW(grow_example(f.geos, in, p), Error);
}

TEST(GrowPatchesTerrain, NoStreetSteeperThanMaxSlope) {
  RiverFixture f;
  GrowInput in = f.input();
  in.water.clear();
  // Flat west of x = 500, 30 % up to the east beyond it.
  in.dem = dem_of([](double x, double) { return x > 500 ? 0.3 * (x - 500) : 0.0; });
  GrowParams p = f.params();
  p.max_slope = 10.0;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 200u);
  std::size_t steep = 0;
  for (const GrownEdge& e : r.edges) steep += grade(in.dem, e.a, e.b) > 0.1 + 1e-9;
  EXPECT_EQ(steep, 0u);
  // Patches that climb are illegal; their open connectors stop at the foot of the slope and stay
  // fronts, where the statistical fallback bends along the contour (here: joining those ends
  // along the foot).
  EXPECT_GT(r.stats.bent, 0u);
  // The same growth without the DEM climbs it.
  GrowInput flat = f.input();
  flat.water.clear();
  GrowResult s = grow_example(f.geos, flat, f.params());
  std::size_t climbing = 0;
  for (const GrownEdge& e : s.edges) climbing += grade(in.dem, e.a, e.b) > 0.1 + 1e-9;
  EXPECT_GT(climbing, 10u);
}

TEST(GrowParametricTerrain, StatisticalStreetsBendAlongTheContour) {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-600 -600, 1200 -600, 1200 1400, -600 1400, -600 -600))");
  GrowInput in;
  in.region = region.get();
  in.seeds = {{0.0, 0.0}};
  in.dem = dem_of([](double x, double) { return x > 300 ? 0.3 * (x - 300) : 0.0; });
  GrowParams p;
  p.parametric = true;
  p.seed = 4;
  p.max_edges = 1500;
  p.max_slope = 10.0;
  GrowResult r = grow_example(geos, in, p);
  ASSERT_GT(r.edges.size(), 100u);
  EXPECT_GT(r.stats.bent, 0u);
  std::size_t steep = 0, along = 0;
  for (const GrownEdge& e : r.edges) {
    steep += grade(in.dem, e.a, e.b) > 0.1 + 1e-9;
    // On the slope: streets within 35° of north-south (the contour), not up it.
    if (std::min(e.a.x, e.b.x) > 320.0) {
      Point d = e.b - e.a;
      along += std::abs(d.y) >= std::abs(d.x) * std::tan(55.0 * kDeg);
    }
  }
  EXPECT_EQ(steep, 0u);
  EXPECT_GT(along, 5u);
}

TEST(GrowPatchesTerrain, BadDemIsRejected) {
  RiverFixture f;
  GrowInput in = f.input();
  in.dem = dem_of([](double, double) { return 0.0; });
  in.dem.origin_x = 1e6;  // far east of the region
  EXPECT_THROW(grow_example(f.geos, in, f.params()), Error);
  in.dem = dem_of([](double, double) { return 0.0; });
  in.dem.values[7] = INFINITY;
  EXPECT_THROW(grow_example(f.geos, in, f.params()), Error);
  in.dem = dem_of([](double, double) { return 0.0; });
  in.dem.bands = 2;
  in.dem.values.resize(2 * 300 * 300, 0.0);
  EXPECT_THROW(grow_example(f.geos, in, f.params()), Error);
}
