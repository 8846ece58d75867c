#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/growth/grow_example.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::wkt;

namespace {

// A square grid of n x n blocks of `size` m, one edge per block side; rows are "avenue" every
// third line, "street" otherwise.
std::vector<ExampleEdge> grid(int n, double size) {
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j < n; ++j) {
      const char* cls = i % 3 == 0 ? "avenue" : "street";
      out.push_back({{{j * size, i * size}, {(j + 1) * size, i * size}}, cls, ++id});
      out.push_back({{{i * size, j * size}, {i * size, (j + 1) * size}}, cls, ++id});
    }
  }
  return out;
}

bool crosses_without_node(const GrownEdge& a, const GrownEdge& b) {
  auto orient = [](Point p, Point q, Point r) { return cross(q - p, r - p); };
  bool shared = a.from_node == b.from_node || a.from_node == b.to_node || a.to_node == b.from_node ||
                a.to_node == b.to_node;
  if (shared) return false;
  double d1 = orient(a.a, a.b, b.a), d2 = orient(a.a, a.b, b.b);
  double d3 = orient(b.a, b.b, a.a), d4 = orient(b.a, b.b, a.b);
  return d1 * d2 <= 0 && d3 * d4 <= 0 &&
         std::max(std::min(a.a.x, a.b.x), std::min(b.a.x, b.b.x)) <= std::min(std::max(a.a.x, a.b.x), std::max(b.a.x, b.b.x)) &&
         std::max(std::min(a.a.y, a.b.y), std::min(b.a.y, b.b.y)) <= std::min(std::max(a.a.y, a.b.y), std::max(b.a.y, b.b.y));
}

// No two edges of one growth cross without a shared node.
void expect_planar(const GrowResult& r, std::uint64_t seed) {
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < r.edges.size(); ++j) {
      EXPECT_FALSE(crosses_without_node(r.edges[i], r.edges[j])) << "seed " << seed << ": " << i << ", " << j;
    }
  }
}

// Growth parameters of the sliver-rule tests: the grid's own frame (no rotation), 400 edges.
GrowParams unrotated_params(std::uint64_t seed) {
  GrowParams p;
  p.seed = seed;
  p.rotation = false;
  p.max_edges = 400;
  return p;
}

// The same edges, bit for bit and in the same order (determinism by seed).
void expect_same_edges(const std::vector<GrownEdge>& again, const std::vector<GrownEdge>& first) {
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(again[i].a.x, first[i].a.x);
    EXPECT_EQ(again[i].a.y, first[i].a.y);
    EXPECT_EQ(again[i].b.x, first[i].b.x);
    EXPECT_EQ(again[i].b.y, first[i].b.y);
  }
}

double point_segment_distance_for_test(Point p, Point a, Point b) {
  Point d = b - a;
  double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return distance(p, a + t * d);
}

// A comb: a 500 m spine of ten 50 m edges with a 40 m dead-end tooth at each node.
std::vector<ExampleEdge> comb_with_dead_ends() {
  std::vector<ExampleEdge> out;
  for (int i = 0; i < 10; ++i) {
    out.push_back({{{i * 50.0, 0.0}, {(i + 1) * 50.0, 0.0}}, "street", i + 1});
    out.push_back({{{i * 50.0, 0.0}, {i * 50.0, 40.0}}, "street", 100 + i});
  }
  return out;
}

struct Fixture {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))");
  GeomPtr lake = wkt(geos, "POLYGON((600 600, 800 600, 800 800, 600 800, 600 600))");
  GrowInput input() {
    GrowInput in;
    in.example = grid(8, 80.0);
    in.region = region.get();
    in.seeds = {{500.0, 500.0}};
    return in;
  }
};

}  // namespace

TEST(GrowExample, GridExampleGrowsAPlanarNetworkInsideTheRegion) {
  Fixture f;
  GrowInput in = f.input();
  in.obstacles = {f.lake.get()};
  GrowParams p;
  p.seed = 7;
  p.rotation = false;
  p.max_edges = 400;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 100u);
  EXPECT_LE(r.edges.size(), 400u);
  for (const GrownEdge& e : r.edges) {
    for (Point q : {e.a, e.b}) {
      EXPECT_GE(q.x, 0.0);
      EXPECT_LE(q.x, 1000.0);
      EXPECT_GE(q.y, 0.0);
      EXPECT_LE(q.y, 1000.0);
    }
    // No edge enters the lake: both ends outside it and the segment misses its box edges.
    bool in_lake = std::max(e.a.x, e.b.x) > 600 && std::min(e.a.x, e.b.x) < 800 && std::max(e.a.y, e.b.y) > 600 &&
                   std::min(e.a.y, e.b.y) < 800;
    // Rotation off on a grid: every edge is axis-parallel, so box overlap means entering.
    EXPECT_FALSE(in_lake) << e.a.x << " " << e.a.y << " -> " << e.b.x << " " << e.b.y;
  }
  std::size_t bad = 0;
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < r.edges.size(); ++j) bad += crosses_without_node(r.edges[i], r.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
  // Rotation off on a grid: edges keep the grid's two directions (within epsilon of them).
  for (const GrownEdge& e : r.edges) {
    double a = std::fmod(std::abs(std::atan2(e.b.y - e.a.y, e.b.x - e.a.x)) * 180.0 / M_PI, 90.0);
    EXPECT_TRUE(a < 1e-6 || a > 90.0 - 1e-6) << a;
  }
}

TEST(GrowExample, SameSeedSameOutputDifferentSeedsDiffer) {
  Fixture f;
  GrowInput in = f.input();
  GrowParams p;
  p.max_edges = 200;
  p.seed = 1;
  GrowResult a = grow_example(f.geos, in, p);
  GrowResult b = grow_example(f.geos, in, p);
  p.seed = 2;
  GrowResult c = grow_example(f.geos, in, p);
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].a.x, b.edges[i].a.x);
    EXPECT_EQ(a.edges[i].b.y, b.edges[i].b.y);
    EXPECT_EQ(a.edges[i].to_node, b.edges[i].to_node);
  }
  bool differ = a.edges.size() != c.edges.size();
  for (std::size_t i = 0; !differ && i < a.edges.size(); ++i) differ = a.edges[i].b.x != c.edges[i].b.x;
  EXPECT_TRUE(differ);
}

TEST(GrowExample, DeadEndsOfTheExampleStayDeadEnds) {
  // A comb: a spine with teeth that end in dead ends.
  Fixture f;
  GrowInput in = f.input();
  in.example = comb_with_dead_ends();
  GrowParams p;
  p.seed = 3;
  p.rotation = false;  // a straight comb: the spine runs to the region's border both ways
  p.max_edges = 300;
  p.crop_margin = 0.0;  // the teeth end on the comb's hull: real dead ends, not a crop's cuts
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 20u);
  std::map<std::int64_t, int> degree;
  for (const GrownEdge& e : r.edges) {
    ++degree[e.from_node];
    ++degree[e.to_node];
  }
  std::size_t dead = 0;
  for (auto& [node, d] : degree) dead += d == 1;
  EXPECT_GT(dead, r.edges.size() / 5);  // teeth keep ending
  EXPECT_GT(r.stats.proposals, r.edges.size() / 2);
}

TEST(GrowExample, BadInputIsRejected) {
  Fixture f;
  GrowParams p;
  auto rejects = [&](GrowInput in, GrowParams params) {
    try {
      grow_example(f.geos, in, params);
    } catch (const Error& e) {
      return e.kind() == ErrorKind::invalid_argument;
    }
    return false;
  };
  GrowInput empty = f.input();
  empty.example.clear();
  EXPECT_TRUE(rejects(empty, p));
  GrowInput one_node = f.input();
  one_node.example = {{{{5, 5}, {5, 5}}, "street", 1}};
  EXPECT_TRUE(rejects(one_node, p));
  GrowInput outside = f.input();
  outside.seeds = {{2000, 2000}};
  EXPECT_TRUE(rejects(outside, p));
  GrowInput no_seed = f.input();
  no_seed.seeds.clear();
  EXPECT_TRUE(rejects(no_seed, p));
  GeomPtr bowtie = wkt(f.geos, "POLYGON((0 0, 10 10, 10 0, 0 10, 0 0))");
  GrowInput invalid = f.input();
  invalid.region = bowtie.get();
  invalid.seeds = {{2, 5}};
  EXPECT_TRUE(rejects(invalid, p));
  GeomPtr empty_region = wkt(f.geos, "POLYGON EMPTY");
  GrowInput no_area = f.input();
  no_area.region = empty_region.get();
  EXPECT_TRUE(rejects(no_area, p));
  GrowInput in_lake = f.input();
  in_lake.obstacles = {f.lake.get()};
  in_lake.seeds = {{700, 700}};
  EXPECT_TRUE(rejects(in_lake, p));
  GrowParams bad = p;
  bad.epsilon = 0;
  EXPECT_TRUE(rejects(f.input(), bad));
  bad = p;
  bad.radius = -1;
  EXPECT_TRUE(rejects(f.input(), bad));
}

TEST(GrowExample, ExtendsAnExistingNetworkWithoutCrossingIt) {
  // A 100 m grid over 1 km with a 400 m hole; growth starts on the nodes of the hole's border.
  Fixture f;
  GeomPtr hole = wkt(f.geos, "POLYGON((300 300, 700 300, 700 700, 300 700, 300 300))");
  GrowInput in = f.input();
  in.region = hole.get();
  in.seeds.clear();
  auto inside_hole = [](Point a, Point b) {
    Point m = 0.5 * (a + b);
    return m.x > 300 && m.x < 700 && m.y > 300 && m.y < 700;
  };
  for (const ExampleEdge& e : grid(10, 100.0)) {
    if (inside_hole(e.line.front(), e.line.back())) continue;
    in.existing.push_back(e.line);
    for (Point p : e.line) {
      bool on_border = (p.x == 300 || p.x == 700) ? p.y >= 300 && p.y <= 700 : (p.y == 300 || p.y == 700) && p.x >= 300 && p.x <= 700;
      if (on_border) in.seeds.push_back(p);
    }
  }
  GrowParams p;
  p.seed = 4;
  p.rotation = false;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 10u);
  std::size_t touching_border = 0;
  for (const GrownEdge& e : r.edges) {
    for (Point q : {e.a, e.b}) {
      EXPECT_TRUE(q.x >= 300 && q.x <= 700 && q.y >= 300 && q.y <= 700) << q.x << " " << q.y;
      touching_border += q.x == 300 || q.x == 700 || q.y == 300 || q.y == 700;
    }
    EXPECT_FALSE(e.road_class.empty());
    // No existing edge is returned, and none is crossed: existing edges lie outside the hole or
    // on its border, so a new edge may only touch them at its own ends.
    for (const std::vector<Point>& x : in.existing) {
      GrownEdge other{0, -1, -2, "", 0, x.front(), x.back()};
      EXPECT_FALSE(e.a.x == x.front().x && e.a.y == x.front().y && e.b.x == x.back().x && e.b.y == x.back().y);
      if (crosses_without_node(e, other)) {
        bool at_own_end = point_segment_distance_for_test(e.a, x.front(), x.back()) < 1e-9 ||
                          point_segment_distance_for_test(e.b, x.front(), x.back()) < 1e-9;
        EXPECT_TRUE(at_own_end);
      }
    }
  }
  EXPECT_GT(touching_border, 5u);  // the growth is attached to the network around the hole
}

TEST(GrowExample, FreeEndsHalfASegmentShortOfAStreetJoinIt) {
  // The 80 m grid from (500, 500) with rotation off puts nodes at x = 500 + 80 k; an existing street
  // at x = 780 is 40 m beyond the column x = 740, half a mean segment. The default snap (0.55 mean
  // segments, 44 m) joins the ends copied towards it to the street; at 0.45 (36 m) they stayed
  // fronts 40 m short of it and grew a parallel street there.
  Fixture f;
  GrowInput in = f.input();
  in.existing = {{{780.0, 0.0}, {780.0, 1000.0}}};
  GrowParams p;
  p.seed = 4;
  p.rotation = false;
  p.max_edges = 400;
  GrowResult r = grow_example(f.geos, in, p);
  EXPECT_NEAR(r.stats.snap, 0.55 * 80.0, 1e-9);
  ASSERT_GT(r.edges.size(), 100u);
  std::size_t short_of_street = 0, joined = 0;
  for (const GrownEdge& e : r.edges) {
    for (Point q : {e.a, e.b}) {
      short_of_street += q.x > 730.0 && q.x < 770.0;
      joined += std::abs(q.x - 780.0) < 1e-6;
    }
  }
  EXPECT_EQ(short_of_street, 0u);
  EXPECT_GT(joined, 3u);
}

TEST(GrowParametric, GrowsAPlanarNetworkWithinTheParameters) {
  Fixture f;
  GrowInput in;
  in.region = f.region.get();
  in.obstacles = {f.lake.get()};
  in.seeds = {{500.0, 500.0}};
  GrowParams p;
  p.parametric = true;
  p.seed = 5;
  p.snap = 20.0;
  p.min_angle = 70.0;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 200u);
  std::map<std::int64_t, int> degree;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    const GrownEdge& e = r.edges[i];
    EXPECT_EQ(e.example, -1);
    EXPECT_EQ(e.road_class, "main");
    EXPECT_GE(distance(e.a, e.b), p.shape.min_length - 1e-9);
    ++degree[e.from_node];
    ++degree[e.to_node];
    for (std::size_t j = i + 1; j < r.edges.size(); ++j) bad += crosses_without_node(e, r.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
  int max_degree = 0;
  for (auto& [node, d] : degree) max_degree = std::max(max_degree, d);
  EXPECT_EQ(max_degree, p.shape.max_degree);
  GrowParams bad_shape = p;
  bad_shape.shape.min_degree = 5;
  EXPECT_THROW(grow_example(f.geos, in, bad_shape), Error);
}

TEST(GrowExample, BlendingFollowsTheGradient) {
  // A fine grid (example 0) and a coarse one (example 1): the west half grows mostly from the
  // first, the east half mostly from the second.
  Fixture f;
  GrowInput in = f.input();
  in.example = grid(8, 50.0);
  for (ExampleEdge e : grid(4, 140.0)) {
    e.example = 1;
    in.example.push_back(e);
  }
  in.seeds = {{250.0, 500.0}, {750.0, 500.0}};
  GrowParams p;
  p.seed = 6;
  p.rotation = false;
  p.max_edges = 600;
  p.blend.mode = BlendParams::Mode::gradient;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 200u);
  double first[2] = {0, 0}, all[2] = {0, 0};
  for (const GrownEdge& e : r.edges) {
    if (e.example < 0) continue;
    int half = 0.5 * (e.a.x + e.b.x) < 500.0 ? 0 : 1;
    all[half] += 1;
    first[half] += e.example == 0;
  }
  // By edges, not steps: the fine grid makes more edges per step, so its share runs above its weight.
  EXPECT_GT(first[0] / all[0], 0.6);
  EXPECT_LT(first[1] / all[1], 0.5);
  EXPECT_GT(first[0] / all[0] - first[1] / all[1], 0.25);
  GrowParams none = p;
  none.blend.mode = BlendParams::Mode::none;
  EXPECT_THROW(grow_example(f.geos, in, none), Error);
}

TEST(GrowExample, DeadEndsOnTheCropEdgeGrowOn) {
  // The comb again: its teeth end on its convex hull, as streets cut by a crop do. With the
  // default crop_margin they grow on; with 0 they stay dead ends.
  Fixture f;
  GrowInput in = f.input();
  in.example = comb_with_dead_ends();
  auto dead_share = [&](double margin) {
    GrowParams p;
    p.seed = 3;
    p.rotation = false;
    p.max_edges = 300;
    p.crop_margin = margin;
    GrowResult r = grow_example(f.geos, in, p);
    std::map<std::int64_t, int> degree;
    for (const GrownEdge& e : r.edges) {
      ++degree[e.from_node];
      ++degree[e.to_node];
    }
    double dead = 0;
    for (auto& [node, d] : degree) dead += d == 1;
    return dead / static_cast<double>(degree.size());
  };
  EXPECT_LT(dead_share(-1.0), 0.5 * dead_share(0.0));
}

namespace {
// The point (i, j) of an 80 m grid, moved by up to 20 m in x and y (a fixed hash of i and j).
Point skewed_grid_point(int i, int j) {
  unsigned h = static_cast<unsigned>(i * 7919 + j * 104729) * 2654435761u;
  return Point{i * 80.0 + static_cast<double>(h % 41) - 20.0, j * 80.0 + static_cast<double>((h >> 8) % 41) - 20.0};
}

// A 9 x 9 grid of 80 m blocks with its junctions moved by up to 20 m and T junctions on every
// third column (the top-up does not join every failed front); with a `spur_period`, a dead-end
// spur `spur_length` long at every T whose (i + j) is a multiple of it.
std::vector<ExampleEdge> skewed_t_grid_with_spurs(int spur_period, double spur_length) {
  auto at = skewed_grid_point;
  std::vector<ExampleEdge> example;
  std::int64_t id = 0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      example.push_back({{at(j, i), at(j + 1, i)}, "street", ++id});
      if (j % 3 == 0 && i > 0 && i < 8) {
        if (spur_period > 0 && (i + j) % spur_period == 0) {
          const Point a = at(i, j), b = at(i, j + 1);
          example.push_back({{a, a + (spur_length / distance(a, b)) * (b - a)}, "street", ++id});
        }
        continue;
      }
      example.push_back({{at(i, j), at(i, j + 1)}, "street", ++id});
    }
  }
  return example;
}
// With `spurs`, a 5 m dead-end spur at every other T (under the minimum edge: no copy makes one).
std::vector<ExampleEdge> skewed_t_grid(bool spurs) { return skewed_t_grid_with_spurs(spurs ? 2 : 0, 5.0); }
}  // namespace

TEST(GrowExample, FrontsThatCanNeitherGrowNorJoinAreCutBack) {
  // A grid with its junctions moved by up to 20 m has no dead ends (its crop-edge ends grow on),
  // so every dead end in the output is a front that failed (its skewed copies crowd each other):
  // away from the region's border and the lake, none is left, and the streets that led to them
  // are gone, not stubs.
  Fixture f;
  GrowInput in = f.input();
  in.obstacles = {f.lake.get()};
  in.example = skewed_t_grid(false);
  std::size_t pruned = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u}) {
    GrowParams p;
    p.seed = seed;
    p.max_edges = 3000;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u);
    pruned += r.stats.pruned;
    std::map<std::int64_t, std::pair<int, Point>> degree;
    for (const GrownEdge& e : r.edges) {
      degree[e.from_node] = {degree[e.from_node].first + 1, e.a};
      degree[e.to_node] = {degree[e.to_node].first + 1, e.b};
    }
    const double margin = 80.0;  // an example segment: clipped ends at the border or the lake stop there
    std::size_t interior_dead = 0;
    for (const auto& [node, dp] : degree) {
      const Point q = dp.second;
      bool near_border = q.x < margin || q.y < margin || q.x > 1000.0 - margin || q.y > 1000.0 - margin;
      bool near_lake = q.x > 600.0 - margin && q.x < 800.0 + margin && q.y > 600.0 - margin && q.y < 800.0 + margin;
      if (dp.first == 1 && !near_border && !near_lake) ++interior_dead;
    }
    EXPECT_EQ(interior_dead, 0u) << "seed " << seed;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < r.edges.size(); ++i) {
      for (std::size_t j = i + 1; j < r.edges.size(); ++j) bad += crosses_without_node(r.edges[i], r.edges[j]);
    }
    EXPECT_EQ(bad, 0u) << "seed " << seed;
  }
  EXPECT_GT(pruned, 0u);  // the case arises: fronts did fail and were cut back
}

TEST(GrowExample, FillReseedsWhereTheFrontsDied) {
  // The comb with real dead ends grows one spine and stops; with fill it starts again from new
  // seeds until no legal point is farther than r from every edge, and stays planar.
  Fixture f;
  GrowInput in = f.input();
  in.example = comb_with_dead_ends();
  GrowParams p;
  p.seed = 3;
  p.rotation = false;
  p.crop_margin = 0.0;
  p.fill = false;
  GrowResult once = grow_example(f.geos, in, p);
  p.fill = true;
  GrowResult filled = grow_example(f.geos, in, p);
  EXPECT_EQ(once.stats.reseeds, 0u);
  EXPECT_GT(filled.stats.reseeds, 3u);
  EXPECT_GT(filled.edges.size(), 2 * once.edges.size());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < filled.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < filled.edges.size(); ++j) bad += crosses_without_node(filled.edges[i], filled.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
}

namespace {

TEST(GrowExample, FillLeavesGapsTheExampleHas) {
  // The comb's hull is a thin strip: fill reseeds wherever a point is farther than r from every
  // edge. With one more short street 560 m off the comb, the example's hull holds an empty space
  // about 200 m wide: gaps up to that size are the example's own and are not reseeded.
  Fixture f;
  GrowInput in = f.input();
  in.example = comb_with_dead_ends();
  GrowParams p;
  p.seed = 3;
  p.rotation = false;
  p.crop_margin = 0.0;
  p.fill = true;  // (as grow_example in SQL, by default)
  GrowResult strip = grow_example(f.geos, in, p);
  in.example.push_back({{{250.0, 600.0}, {290.0, 600.0}}, "street", 500});
  GrowResult gap = grow_example(f.geos, in, p);
  EXPECT_GT(strip.stats.reseeds, 3u);
  EXPECT_LT(gap.stats.reseeds, strip.stats.reseeds);
  EXPECT_LT(gap.edges.size(), strip.edges.size());
}

// A north-up raster over [0, 1000]² of 100 m cells, `bands` bands filled by f(band, x, y) at
// each cell centre.
template <typename F>
GridField field_over_region(int bands, F&& f) {
  GridField g;
  g.origin_x = 0.0;
  g.origin_y = 1000.0;
  g.scale_x = 100.0;
  g.scale_y = -100.0;
  g.width = 10;
  g.height = 10;
  g.bands = bands;
  for (int b = 0; b < bands; ++b) {
    for (int row = 0; row < 10; ++row) {
      for (int col = 0; col < 10; ++col) g.values.push_back(f(b, 50.0 + 100.0 * col, 950.0 - 100.0 * row));
    }
  }
  return g;
}

// The share of edges (by length) within `tolerance` degrees of `azimuth` modulo 90° (a grid's
// two directions), azimuths clockwise from north.
double share_along(const std::vector<GrownEdge>& edges, double azimuth, double tolerance) {
  double along = 0.0, all = 0.0;
  for (const GrownEdge& e : edges) {
    const double len = distance(e.a, e.b);
    double az = std::atan2(e.b.x - e.a.x, e.b.y - e.a.y) * 180.0 / 3.14159265358979323846;
    double off = std::fmod(std::fmod(az - azimuth, 90.0) + 90.0, 90.0);
    along += std::min(off, 90.0 - off) <= tolerance ? len : 0.0;
    all += len;
  }
  return along / all;
}

// The edges whose midpoints lie in the west and east parts of the 1 km test region (x < 380 m,
// x > 620 m), apart from the band around the middle where two controls meet.
std::pair<std::vector<GrownEdge>, std::vector<GrownEdge>> west_and_east_quarters(const std::vector<GrownEdge>& edges) {
  std::vector<GrownEdge> west, east;
  for (const GrownEdge& e : edges) {
    const double x = 0.5 * (e.a.x + e.b.x);
    if (x < 380.0) west.push_back(e);
    if (x > 620.0) east.push_back(e);
  }
  return {west, east};
}

}  // namespace

TEST(GrowExample, DirectionRasterSetsTheRotation) {
  // A uniform field of azimuth 30° (and 210°, the same undirected line): the grid example grows
  // turned onto it. Without the field and rotation off, the grid keeps the axes (0°).
  Fixture f;
  GrowInput in = f.input();
  in.direction = field_over_region(1, [](int, double, double) { return 210.0; });
  GrowParams p;
  p.seed = 4;
  p.max_edges = 400;
  p.rotation = false;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 150u);
  EXPECT_GT(share_along(r.edges, 30.0, 3.0), 0.9);
  EXPECT_GT(r.stats.directed, 0u);
  EXPECT_GT(r.stats.guided, 0u);
  GrowInput plain = f.input();
  GrowResult q = grow_example(f.geos, plain, p);
  EXPECT_GT(share_along(q.edges, 0.0, 3.0), 0.9);
  EXPECT_LT(share_along(q.edges, 30.0, 3.0), 0.1);
  // Parametric growth follows it too.
  GrowInput par;
  par.region = f.region.get();
  par.seeds = {{500.0, 500.0}};
  par.direction = in.direction;
  GrowParams pp;
  pp.parametric = true;
  pp.seed = 5;
  pp.snap = 20.0;
  pp.min_angle = 70.0;
  pp.shape.angle_deviation = 0.0;
  pp.max_edges = 300;
  GrowResult pr = grow_example(f.geos, par, pp);
  ASSERT_GT(pr.edges.size(), 100u);
  EXPECT_GT(share_along(pr.edges, 30.0, 3.0), 0.8);
}

TEST(GrowExample, DirectionRasterNodataFallsBackToNodeMatching) {
  // The field covers the west half only (nodata in the east): edges in the west follow 30°, edges
  // in the east keep the example's own axes (rotation off).
  Fixture f;
  GrowInput in = f.input();
  in.seeds = {{250.0, 500.0}, {750.0, 500.0}};
  in.direction = field_over_region(1, [](int, double x, double) { return x < 500.0 ? 30.0 : NAN; });
  GrowParams p;
  p.seed = 4;
  p.max_edges = 600;
  p.rotation = false;
  GrowResult r = grow_example(f.geos, in, p);
  const auto [west, east] = west_and_east_quarters(r.edges);
  ASSERT_GT(west.size(), 50u);
  ASSERT_GT(east.size(), 50u);
  EXPECT_GT(share_along(west, 30.0, 3.0), 0.8);
  EXPECT_GT(share_along(east, 0.0, 3.0), 0.8);
}

TEST(GrowExample, WeightRasterChoosesTheExample) {
  // Weights 1/0 in the west and 0/1 in the east: only example 0's edges in the west, only example
  // 1's in the east (away from the 100 m wide bilinear seam and an edge's length).
  Fixture f;
  GrowInput in = f.input();
  in.example = grid(8, 50.0);
  for (ExampleEdge e : grid(4, 140.0)) {
    e.example = 1;
    in.example.push_back(e);
  }
  in.seeds = {{250.0, 500.0}, {750.0, 500.0}};
  in.weights = field_over_region(2, [](int band, double x, double) { return (x < 500.0) == (band == 0) ? 1.0 : 0.0; });
  GrowParams p;
  p.seed = 6;
  p.rotation = false;
  p.max_edges = 600;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 200u);
  std::size_t west[2] = {0, 0}, east[2] = {0, 0};
  for (const GrownEdge& e : r.edges) {
    if (e.example < 0) continue;
    const double x = 0.5 * (e.a.x + e.b.x);
    if (x < 300.0) ++west[e.example];
    if (x > 700.0) ++east[e.example];
  }
  EXPECT_GT(west[0], 50u);
  EXPECT_EQ(west[1], 0u);
  EXPECT_GT(east[1], 20u);
  EXPECT_EQ(east[0], 0u);
  EXPECT_GT(r.stats.weighted, 0u);
  // The same raster swapped: the other way round, so the raster (not the seeds) decides.
  in.weights = field_over_region(2, [](int band, double x, double) { return (x < 500.0) == (band == 1) ? 1.0 : 0.0; });
  GrowResult s = grow_example(f.geos, in, p);
  std::size_t swapped_west0 = 0;
  for (const GrownEdge& e : s.edges) swapped_west0 += e.example == 0 && 0.5 * (e.a.x + e.b.x) < 300.0;
  EXPECT_EQ(swapped_west0, 0u);
}

TEST(GrowExample, WeightRasterNodataFallsBackToTheBlend) {
  // Weights (all example 1) on the west half only; the east half is nodata, where the gradient
  // decides (mostly example 1 there too, as it runs to the last example in the east). Without a
  // gradient, nodata means every example alike.
  Fixture f;
  GrowInput in = f.input();
  in.example = grid(8, 50.0);
  for (ExampleEdge e : grid(4, 140.0)) {
    e.example = 1;
    in.example.push_back(e);
  }
  in.seeds = {{250.0, 500.0}, {750.0, 500.0}};
  in.weights =
      field_over_region(2, [](int band, double x, double) { return x < 500.0 ? (band == 1 ? 1.0 : 0.0) : NAN; });
  GrowParams p;
  p.seed = 6;
  p.rotation = false;
  p.max_edges = 600;
  p.blend.mode = BlendParams::Mode::gradient;
  p.blend.angle = 180.0;  // the first example in the east
  GrowResult r = grow_example(f.geos, in, p);
  std::size_t west[2] = {0, 0}, east[2] = {0, 0};
  for (const GrownEdge& e : r.edges) {
    if (e.example < 0) continue;
    const double x = 0.5 * (e.a.x + e.b.x);
    if (x < 300.0) ++west[e.example];
    if (x > 800.0) ++east[e.example];
  }
  EXPECT_EQ(west[0], 0u);
  EXPECT_GT(west[1], 10u);
  EXPECT_GT(east[0], east[1]);
  GrowParams none = p;
  none.blend.mode = BlendParams::Mode::none;
  EXPECT_NO_THROW(grow_example(f.geos, in, none));
}

TEST(GrowExample, BadControlRastersAreRejected) {
  Fixture f;
  GrowInput in = f.input();
  in.example = grid(8, 50.0);
  for (ExampleEdge e : grid(4, 140.0)) {
    e.example = 1;
    in.example.push_back(e);
  }
  GrowParams p;
  p.max_edges = 50;
  GrowInput bands = in;
  bands.weights = field_over_region(3, [](int, double, double) { return 1.0; });
  EXPECT_THROW(grow_example(f.geos, bands, p), Error);
  GrowInput negative = in;
  negative.weights = field_over_region(2, [](int, double x, double) { return x < 300.0 ? -1.0 : 1.0; });
  EXPECT_THROW(grow_example(f.geos, negative, p), Error);
  GrowInput away = in;
  away.weights = field_over_region(2, [](int, double, double) { return 1.0; });
  away.weights.origin_x = 5000.0;
  EXPECT_THROW(grow_example(f.geos, away, p), Error);
  GrowInput fine = in;
  fine.weights = field_over_region(2, [](int, double, double) { return 1.0; });
  EXPECT_NO_THROW(grow_example(f.geos, fine, p));  // a weight raster is a blend of its own
  GrowInput direction = f.input();
  direction.direction = field_over_region(2, [](int, double, double) { return 0.0; });
  EXPECT_THROW(grow_example(f.geos, direction, p), Error);
  direction.direction = field_over_region(1, [](int, double, double) { return INFINITY; });
  EXPECT_THROW(grow_example(f.geos, direction, p), Error);
  direction.direction = field_over_region(1, [](int, double, double) { return 0.0; });
  direction.direction.origin_y = -5000.0;
  EXPECT_THROW(grow_example(f.geos, direction, p), Error);
}

TEST(GrowExample, DirectionRasterComesBeforeTheGuide) {
  // The raster (30°) covers the west half; a guide at azimuth 60° runs across the whole region:
  // the west follows the raster, the east (raster nodata) the guide.
  Fixture f;
  GrowInput in = f.input();
  in.seeds = {{250.0, 500.0}, {750.0, 500.0}};
  in.direction = field_over_region(1, [](int, double x, double) { return x < 500.0 ? 30.0 : NAN; });
  const double rad = 60.0 * 3.14159265358979323846 / 180.0, s = std::sin(rad), c = std::cos(rad);
  in.guide = {{{500.0 - 800.0 * s, 500.0 - 800.0 * c}, {500.0 + 800.0 * s, 500.0 + 800.0 * c}}};
  GrowParams p;
  p.seed = 4;
  p.max_edges = 600;
  p.rotation = false;
  GrowResult r = grow_example(f.geos, in, p);
  const auto [west, east] = west_and_east_quarters(r.edges);
  ASSERT_GT(west.size(), 50u);
  ASSERT_GT(east.size(), 50u);
  EXPECT_GT(share_along(west, 30.0, 3.0), 0.8);
  EXPECT_GT(share_along(east, 60.0, 3.0), 0.8);
}

TEST(GrowExample, ShortSegmentsGoOnPastTheirOwnStreet) {
  // A ladder: streets 150 m apart, each cut into a 200 m segment and three 15 m ones, again and
  // again, joined by cross streets every 245 m. The snap (0.55 x the 79.6 m mean segment, 43.8 m)
  // is wider than two short segments, so the end of a 15 m continuation lies within it of the node
  // its own street came from. That node is the street itself, not a road to join: the
  // continuation goes on and the short segments are copied (they were refused, so the short runs
  // were cut and their streets pruned).
  Fixture f;
  GrowInput in = f.input();
  in.example.clear();
  std::int64_t id = 0;
  for (int row = 0; row < 6; ++row) {
    const double y = row * 150.0;
    double x = 0.0;
    for (int k = 0; k < 4; ++k) {
      for (double len : {200.0, 15.0, 15.0, 15.0}) {
        in.example.push_back({{{x, y}, {x + len, y}}, "street", ++id});
        x += len;
      }
    }
  }
  for (int col = 0; col <= 4; ++col) {
    for (int row = 0; row < 5; ++row) {
      in.example.push_back({{{col * 245.0, row * 150.0}, {col * 245.0, (row + 1) * 150.0}}, "street", ++id});
    }
  }
  std::size_t short_edges = 0, edges = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    GrowParams p;
    p.seed = seed;
    p.rotation = false;
    p.max_edges = 2000;
    GrowResult r = grow_example(f.geos, in, p);
    EXPECT_NEAR(r.stats.snap, 0.55 * 9630.0 / 121.0, 1e-9);
    EXPECT_EQ(r.stats.restarts, 0u) << "seed " << seed;
    for (const GrownEdge& e : r.edges) {
      ++edges;
      short_edges += distance(e.a, e.b) < 20.0;
    }
  }
  ASSERT_GT(edges, 150u);
  EXPECT_GT(static_cast<double>(short_edges) / static_cast<double>(edges), 0.3) << short_edges << " of " << edges;
}

TEST(GrowExample, JoinsKeepTheExampleJunctionMix) {
  // A grid of 80 m blocks with a third of its inner cross streets' segments left out: junctions
  // are 3 in 4 T (56 T, 14 crossings), 2 in 5 crossings away from its crop edge (10 of 25). Joining
  // a T node is allowed with the example's probability that a node of degree 3 has a fourth edge,
  // drawn once per node and degree: refused joins are asked again (fronts retry, neighbours'
  // proposals end there), and a fresh draw each time made more crossings (29.7 % of the output's
  // junctions over these 20 seeds, against 26.2 %). Since growth16 a join onto a T is made while
  // the output is short of the example's crossings away from the crop edge (40 %) and refused once
  // it has them, whatever the draw says: the output has 36.9 % (growth16's one-sided top-up: 38.0 %,
  // with fresh draws 38.3 %), and the test checks that it does not pass the example.
  Fixture f;
  GrowInput in = f.input();
  in.example.clear();
  std::int64_t id = 0;
  const int n = 8;
  const double size = 80.0;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j < n; ++j) {
      in.example.push_back({{{j * size, i * size}, {(j + 1) * size, i * size}}, "street", ++id});
      if ((3 * i + j) % 3 == 0 && i > 0 && i < n) continue;
      in.example.push_back({{{i * size, j * size}, {i * size, (j + 1) * size}}, "street", ++id});
    }
  }
  std::size_t tees = 0, crossings = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.rotation = false;
    p.max_edges = 3000;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    std::map<std::int64_t, int> degree;
    for (const GrownEdge& e : r.edges) {
      ++degree[e.from_node];
      ++degree[e.to_node];
    }
    for (const auto& [node, d] : degree) {
      tees += d == 3;
      crossings += d >= 4;
    }
  }
  ASSERT_GT(tees + crossings, 1000u);
  EXPECT_LT(static_cast<double>(crossings) / static_cast<double>(tees + crossings), 0.40)
      << crossings << " crossings, " << tees << " T junctions";
}

TEST(GrowExample, StreetsMeetingNearAJunctionJoinIt) {
  // An existing street along y = 500 with a shape point every 10 m and a side street going north
  // from (500, 500). The 80 m grid grown from (525, 210), rotation off, crosses y = 500 at
  // x = 525 (from y = 450 to 530), 25 m from that junction: within the snap (44 m), it joins the
  // junction (a crossing) instead of the shape point 5 m away (a second T junction 20 m from the
  // first, which the example does not have).
  Fixture f;
  GrowInput in = f.input();
  Polyline street;
  for (int i = 0; i <= 100; ++i) street.push_back({i * 10.0, 500.0});
  in.existing = {street, {{500.0, 500.0}, {500.0, 1000.0}}};
  in.seeds = {{525.0, 210.0}};
  std::size_t offset = 0, at_junction = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    GrowParams p;
    p.seed = seed;
    p.rotation = false;
    p.max_edges = 400;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 50u) << "seed " << seed;
    for (const GrownEdge& e : r.edges) {
      for (Point q : {e.a, e.b}) {
        if (std::abs(q.y - 500.0) > 1e-6) continue;
        const double dx = std::abs(q.x - 500.0);
        offset += dx > 1e-6 && dx < r.stats.snap;
        at_junction += dx <= 1e-6;
      }
    }
  }
  EXPECT_EQ(offset, 0u);
  EXPECT_GT(at_junction, 0u);
}

namespace {

// Grown edges with an end at q, and of those, the ones whose other end lies off both of q's grid
// lines (a join that turned a copied edge of the axis-parallel grid onto q).
std::pair<std::size_t, std::size_t> edges_at(const GrowResult& r, Point q) {
  std::size_t at = 0, turned = 0;
  for (const GrownEdge& e : r.edges) {
    for (auto [end, other] : {std::pair{e.a, e.b}, std::pair{e.b, e.a}}) {
      if (distance(end, q) > 1e-6) continue;
      ++at;
      turned += std::abs(other.x - q.x) > 1.0 && std::abs(other.y - q.y) > 1.0;
    }
  }
  return {at, turned};
}

// An existing street along x = 855 and a side street from it to a dead end at kSideEnd.
constexpr Point kSideEnd{822.0, 537.0};
std::vector<Polyline> side_streets() {
  return {{{855.0, 200.0}, {855.0, 570.0}}, {{855.0, 570.0}, {855.0, 800.0}}, {kSideEnd, {855.0, 570.0}}};
}

// The growth both snap-band tests run: the grid without rotation, a 44 m snap.
GrowParams band_params(std::uint64_t seed) {
  GrowParams p;
  p.seed = seed;
  p.rotation = false;
  p.max_edges = 400;
  p.snap = 44.0;
  return p;
}

}  // namespace

TEST(GrowExample, FreeEndsSnapToNodesOnlyNearTheCopiedLine) {
  // The 80 m grid grown from (500, 500), rotation off, has a node at (820, 500). An existing street
  // runs along x = 855 (35 m east of it), and a side street leaves it for a dead end at (822, 537):
  // 37 m from (820, 500), the nearest node within the snap (44 m, set: the next test's example has
  // shorter segments), but 37 m off the copied lines through it, beyond the band (22 m). Ends
  // copied towards (820, 500) meet the street at (855, 500) straight on (a T) instead; none turns
  // onto the dead end. The example's dead-end share is 0 (a grid), so the band applies.
  Fixture f;
  GrowInput in = f.input();
  in.existing = side_streets();
  std::size_t turned = 0, straight_t = 0;
  std::vector<GrownEdge> first;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    GrowResult r = grow_example(f.geos, in, band_params(seed));
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_EQ(r.stats.dead_end_share, 0.0);
    turned += edges_at(r, kSideEnd).second;
    straight_t += edges_at(r, {855.0, 500.0}).first;
    expect_planar(r, seed);
    if (seed == 1u) first = r.edges;
  }
  EXPECT_EQ(turned, 0u);
  EXPECT_GT(straight_t, 0u);
  // Determinism with the band.
  expect_same_edges(grow_example(f.geos, in, band_params(1)).edges, first);
}

namespace {

// The 80 m grid with a 40 m dead-end tooth at the middle of the block sides of its inner rows:
// every side, or every other one.
std::vector<ExampleEdge> grid_with_teeth(bool every_other_side) {
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double x = j * 80.0, y = i * 80.0;
      out.push_back({{{i * 80.0, x}, {i * 80.0, x + 80.0}}, "street", ++id});
      if (i == 0 || i == 8 || (every_other_side && (i + j) % 2 == 0)) {
        out.push_back({{{x, y}, {x + 80.0, y}}, "street", ++id});
        continue;
      }
      out.push_back({{{x, y}, {x + 40.0, y}}, "street", ++id});
      out.push_back({{{x + 40.0, y}, {x + 80.0, y}}, "street", ++id});
      out.push_back({{{x + 40.0, y}, {x + 40.0, y + 40.0}}, "street", ++id});
    }
  }
  return out;
}

}  // namespace

TEST(GrowExample, ACityOfCulDeSacsSnapsWithoutTheBand) {
  // The same set-up (snap 44 m) with a 40 m dead-end tooth at the middle of every block side of the
  // grid's inner rows: its dead ends are over 15 % of its street ends, so free ends snap to any node
  // within the snap, and some turn onto the existing street's dead end.
  Fixture f;
  GrowInput in = f.input();
  in.example = grid_with_teeth(false);
  in.existing = side_streets();
  std::size_t turned = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    GrowResult r = grow_example(f.geos, in, band_params(seed));
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_GT(r.stats.dead_end_share, 0.15);
    EXPECT_EQ(r.stats.small_block, 0.0);  // nor the small-cycle rule
    turned += edges_at(r, kSideEnd).second;
  }
  EXPECT_GT(turned, 0u);
}

namespace {

// The shortest cycle through any grown edge of r, in the graph of the grown edges and the existing
// streets (split at the grown ends that lie on them): for each grown edge, the shortest path
// between its ends without it, plus its length.
double shortest_cycle(const GrowResult& r, const std::vector<Polyline>& existing) {
  std::map<std::pair<long long, long long>, std::size_t> ids;
  auto id = [&](Point p) {
    const auto key = std::make_pair(std::llround(p.x * 1000.0), std::llround(p.y * 1000.0));
    return ids.emplace(key, ids.size()).first->second;
  };
  struct Link {
    std::size_t a, b;
    double length;
  };
  std::vector<Link> links;
  for (const GrownEdge& e : r.edges) links.push_back({id(e.a), id(e.b), distance(e.a, e.b)});
  const std::size_t grown = links.size();
  for (const Polyline& line : existing) {
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Point a = line[k], b = line[k + 1];
      std::vector<std::pair<double, Point>> cuts{{0.0, a}, {distance(a, b), b}};
      for (const GrownEdge& e : r.edges) {
        for (Point q : {e.a, e.b}) {
          if (point_segment_distance_for_test(q, a, b) < 1e-6) cuts.push_back({distance(a, q), q});
        }
      }
      std::sort(cuts.begin(), cuts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const std::size_t u = id(cuts[c].second), w = id(cuts[c + 1].second);
        if (u != w) links.push_back({u, w, cuts[c + 1].first - cuts[c].first});
      }
    }
  }
  std::vector<std::vector<std::size_t>> at(ids.size());
  for (std::size_t k = 0; k < links.size(); ++k) {
    at[links[k].a].push_back(k);
    at[links[k].b].push_back(k);
  }
  double best = INFINITY;
  for (std::size_t skip = 0; skip < grown; ++skip) {
    std::vector<double> dist(ids.size(), INFINITY);
    std::set<std::pair<double, std::size_t>> queue{{0.0, links[skip].a}};
    dist[links[skip].a] = 0.0;
    while (!queue.empty()) {
      const auto [d, u] = *queue.begin();
      queue.erase(queue.begin());
      if (u == links[skip].b || d + links[skip].length >= best) break;
      for (std::size_t k : at[u]) {
        if (k == skip) continue;
        const std::size_t t = links[k].a == u ? links[k].b : links[k].a;
        if (d + links[k].length < dist[t]) {
          queue.erase({dist[t], t});
          dist[t] = d + links[k].length;
          queue.insert({dist[t], t});
        }
      }
    }
    best = std::min(best, dist[links[skip].b] + links[skip].length);
  }
  return best;
}

}  // namespace

TEST(GrowExample, NoJoinClosesACycleShorterThanTheExamplesBlocks) {
  // The 80 m grid from (500, 500), rotation off: its blocks are 320 m around, the rule's limit. An
  // existing street runs diagonally across the grid (x + y = 1530), so ends copied towards it
  // join it by cutting the grid's cells: corner triangles and short trapezoids of 150-300 m
  // around unless refused. With the rule, no cycle through a grown edge is shorter than 320 m, and
  // the growth still joins the street.
  Fixture f;
  GrowInput in = f.input();
  in.existing = {{{530.0, 1000.0}, {1000.0, 530.0}}};
  std::size_t refused = 0, on_street = 0;
  std::vector<GrownEdge> first;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    GrowResult r = grow_example(f.geos, in, unrotated_params(seed));
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_EQ(r.stats.small_block, 320.0);
    refused += r.stats.small_cycles_refused;
    EXPECT_GE(shortest_cycle(r, in.existing), 320.0 - 1e-6) << "seed " << seed;
    for (const GrownEdge& e : r.edges) {
      for (Point q : {e.a, e.b}) on_street += std::abs(q.x + q.y - 1530.0) < 1e-6;
    }
    expect_planar(r, seed);
    if (seed == 1u) first = r.edges;
  }
  EXPECT_GT(refused, 0u);
  EXPECT_GT(on_street, 4u);
  // Determinism with the rule.
  expect_same_edges(grow_example(f.geos, in, unrotated_params(1)).edges, first);
}

namespace {

// Columns every 80 m, rows 40, 120 and 120 m apart in turn, junctions moved by up to 8 m: blocks
// of about 240 m around (a third) and 400 m (two thirds), nearly square (φ about 0.98).
std::vector<ExampleEdge> grid_with_narrow_rows() {
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  std::vector<double> ys{0.0};
  for (int k = 0; k < 7; ++k) ys.push_back(ys.back() + (k % 3 == 0 ? 40.0 : 120.0));
  auto at = [&](int j, std::size_t i) {
    unsigned h = static_cast<unsigned>(static_cast<int>(i) * 7919 + j * 104729) * 2654435761u;
    return Point{j * 80.0 + static_cast<double>(h % 17) - 8.0, ys[i] + static_cast<double>((h >> 8) % 9) - 4.0};
  };
  for (std::size_t i = 0; i < ys.size(); ++i) {
    for (int j = 0; j < 8; ++j) out.push_back({{at(j, i), at(j + 1, i)}, "street", ++id});
  }
  for (int j = 0; j <= 8; ++j) {
    for (std::size_t i = 0; i + 1 < ys.size(); ++i) out.push_back({{at(j, i), at(j, i + 1)}, "street", ++id});
  }
  return out;
}

// A spider's web: 24 spokes and 7 rings, the rings 40 and 120 m apart in turn from 100 m out, each
// ring a 24-gon: blocks of 143-511 m around in six sizes, in every direction (φ about 0.2, as
// unordered as strasbourg's 0.185).
std::vector<ExampleEdge> web_with_narrow_rings() {
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  std::vector<double> radii{100.0};
  for (int k = 0; k < 6; ++k) radii.push_back(radii.back() + (k % 2 == 0 ? 40.0 : 120.0));
  auto at = [&](std::size_t ring, int spoke) {
    const double a = spoke * M_PI / 12.0;
    return Point{1000.0 + radii[ring] * std::cos(a), 1000.0 + radii[ring] * std::sin(a)};
  };
  for (std::size_t r = 0; r < radii.size(); ++r) {
    for (int k = 0; k < 24; ++k) {
      out.push_back({{at(r, k), at(r, (k + 1) % 24)}, "street", ++id});
      if (r + 1 < radii.size()) out.push_back({{at(r, k), at(r + 1, k)}, "street", ++id});
    }
  }
  return out;
}

}  // namespace

TEST(GrowExample, FailedFrontsDoNotCloseBlocksUnderTheExamplesMedian) {
  // web_with_narrow_rings grown over a 2 km square with one random candidate and no coherent
  // copying, so that fronts fail and close_front joins them ahead or to the nearest node: a join
  // that closes a cycle shorter than the example's median block (344 m around; its small blocks
  // 143 m) is refused (about 10 per growth, seeds 1-6). A nearly square grid (grid_with_narrow_rows,
  // φ 0.98) keeps its fronts' joins: there the rule is off.
  Fixture f;
  GrowInput in = f.input();
  in.example = web_with_narrow_rings();
  GeomPtr region = wkt(f.geos, "POLYGON((0 0, 2000 0, 2000 2000, 0 2000, 0 0))");
  in.region = region.get();
  in.seeds = {{1000.0, 1000.0}};
  std::size_t refused = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.max_edges = 3000;
    p.candidates = 1;
    p.coherence = 0.0;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 500u) << "seed " << seed;
    EXPECT_NEAR(r.stats.small_block, 142.7, 0.5);
    EXPECT_NEAR(r.stats.median_block, 344.4, 0.5);
    expect_planar(r, seed);
    refused += r.stats.median_joins_refused;
  }
  EXPECT_GT(refused, 20u);
  in.example = grid_with_narrow_rows();
  GrowParams p;
  p.seed = 1;
  p.max_edges = 3000;
  GrowResult r = grow_example(f.geos, in, p);
  EXPECT_GT(r.stats.small_block, 200.0);
  EXPECT_EQ(r.stats.median_block, 0.0);
  EXPECT_EQ(r.stats.median_joins_refused, 0u);
}

TEST(GrowExample, FailedFrontsJoinNoNodeOffTheirHeadingWhileLessOrdered) {
  // The growth of FailedFrontsDoNotCloseBlocksUnderTheExamplesMedian: while its output is less
  // ordered than the web it copies, a failed front joins only nodes within 30° of its heading or
  // of square to it; the others are refused (hundreds over seeds 1-6).
  Fixture f;
  GrowInput in = f.input();
  in.example = web_with_narrow_rings();
  GeomPtr region = wkt(f.geos, "POLYGON((0 0, 2000 0, 2000 2000, 0 2000, 0 0))");
  in.region = region.get();
  in.seeds = {{1000.0, 1000.0}};
  std::size_t refused = 0, joined = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.max_edges = 3000;
    p.candidates = 1;
    p.coherence = 0.0;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 500u) << "seed " << seed;
    expect_planar(r, seed);
    refused += r.stats.fronts_off_heading_refused;
    joined += r.stats.fronts_near_node;
  }
  EXPECT_GT(refused, 100u) << joined << " joined";
}

namespace {

// A triangular lattice of 80 m edges (every block a triangle of 240 m around): a step at a node
// copies its six arms at once, and a later step at an arm's end copies an edge that ends on the
// next arm's end.
std::vector<ExampleEdge> triangular_lattice(int n, double size) {
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  const double h = size * std::sqrt(3.0) / 2.0;
  auto at = [&](int i, int j) { return Point{j * size + (i % 2) * size / 2.0, i * h}; };
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      if (j < n) out.push_back({{at(i, j), at(i, j + 1)}, "street", ++id});
      if (i == n) continue;
      const int k = i % 2 == 0 ? j - 1 : j;  // the row above is shifted by half an edge
      if (k >= 0) out.push_back({{at(i, j), at(i + 1, k)}, "street", ++id});
      if (k + 1 <= n) out.push_back({{at(i, j), at(i + 1, k + 1)}, "street", ++id});
    }
  }
  return out;
}

// Triangles (3-cycles) of the grown graph.
std::size_t triangles(const GrowResult& r) {
  std::map<std::int64_t, std::set<std::int64_t>> adj;
  for (const GrownEdge& e : r.edges) {
    adj[e.from_node].insert(e.to_node);
    adj[e.to_node].insert(e.from_node);
  }
  std::size_t n = 0;
  for (const GrownEdge& e : r.edges) {
    for (std::int64_t c : adj[e.from_node]) n += c != e.to_node && adj[e.to_node].count(c);
  }
  return n / 3;
}

}  // namespace

TEST(GrowExample, NoJoinClosesATriangleWithTwoSiblingEdges) {
  // Two edges one step made at one node are siblings; a later join between their far ends would
  // close a triangle the copied junction does not have. The lattice's own blocks are such
  // triangles, so growth from it is refused those joins (the small-cycle rule's limit, 240 m, is
  // not under them).
  Fixture f;
  GrowInput in = f.input();
  in.example = triangular_lattice(10, 80.0);
  std::size_t refused = 0;
  std::vector<GrownEdge> first;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    GrowResult r = grow_example(f.geos, in, unrotated_params(seed));
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_NEAR(r.stats.small_block, 240.0, 1e-6);
    refused += r.stats.sibling_joins_refused;
    // Without the rule, half the lattice's triangles close: 187-208 in 400 edges (seeds 1-4); with
    // it 2-9 remain (joins of edges made in different steps).
    EXPECT_LT(triangles(r), r.edges.size() / 10) << "seed " << seed;
    expect_planar(r, seed);
    if (seed == 1u) first = r.edges;
  }
  EXPECT_GT(refused, 0u);
  // Determinism with the rule.
  expect_same_edges(grow_example(f.geos, in, unrotated_params(1)).edges, first);
}

namespace {

// Output nodes by degree (index 4: 4 or more).
std::vector<std::size_t> degree_counts(const GrowResult& r) {
  std::map<std::int64_t, int> degree;
  for (const GrownEdge& e : r.edges) {
    ++degree[e.from_node];
    ++degree[e.to_node];
  }
  std::vector<std::size_t> out(5, 0);
  for (const auto& [node, d] : degree) ++out[std::min(d, 4)];
  return out;
}

}  // namespace

TEST(GrowExample, JunctionMixCountsAddUp) {
  // The DEBUG1 counts of where dead ends and junctions are made or lost (growth13) against the
  // output: the 80 m grid with a 40 m dead-end tooth at the middle of every other inner block side.
  Fixture f;
  GrowInput in = f.input();
  in.example = grid_with_teeth(true);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    GrowResult r = grow_example(f.geos, in, unrotated_params(seed));
    const GrowStats& s = r.stats;
    ASSERT_GT(r.edges.size(), 20u) << "seed " << seed;
    ASSERT_GT(s.dead_end_proposals, 0u) << "seed " << seed;
    // Every dead-end copy is made or lost for one of the four reasons.
    EXPECT_EQ(s.dead_end_made + s.dead_end_lost[0] + s.dead_end_lost[1] + s.dead_end_lost[2] + s.dead_end_lost[3],
              s.dead_end_proposals)
        << "seed " << seed;
    // Every join (a node join or a split) is a snapped proposal or a failed front's join.
    std::size_t joins = 0;
    for (const auto& cause : s.node_joins) {
      for (std::size_t n : cause) joins += n;
    }
    for (std::size_t n : s.splits) joins += n;
    EXPECT_EQ(joins, s.snapped) << "seed " << seed;
    std::size_t rejected = 0;
    for (std::size_t n : s.reject_reason) rejected += n;
    EXPECT_EQ(rejected, s.rejected) << "seed " << seed;
    EXPECT_EQ(s.fronts_ahead_node + s.fronts_ahead_split + s.fronts_near_node,
              s.node_joins[2][0] + s.node_joins[2][1] + s.node_joins[2][2] + s.node_joins[2][3] +
                  s.node_joins[2][4] + s.splits[2])
        << "seed " << seed;
    EXPECT_LE(s.fronts_ahead_node + s.fronts_ahead_split + s.fronts_near_node + s.fronts_dead_end + s.fronts_pruned,
              s.fronts_failed)
        << "seed " << seed;
    // A copied dead end not joined since is still a degree-1 node of the output.
    std::size_t joined = s.dead_ends_joined[0] + s.dead_ends_joined[1] + s.dead_ends_joined[2];
    EXPECT_GE(degree_counts(r)[1] + joined, s.dead_end_made) << "seed " << seed;
  }
}

namespace {

// An n x n grid of `size` m blocks whose interior crossings are drawn as two Ts `jog` m apart
// (OSM's staggered crossings): each column is a polyline through (x, y - jog/2) and
// (x, y + jog/2) at an interior crossing; the row edge from the west ends at the first, the one
// to the east starts at the second. Border crossings are plain points.
std::vector<ExampleEdge> staggered_grid(int n, double size, double jog) {
  auto interior = [n](int i, int j) { return i > 0 && i < n && j > 0 && j < n; };
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  for (int i = 0; i <= n; ++i) {  // column x = i * size
    Polyline line;
    for (int j = 0; j <= n; ++j) {
      if (interior(i, j)) {
        line.push_back({i * size, j * size - jog / 2});
        line.push_back({i * size, j * size + jog / 2});
      } else {
        line.push_back({i * size, j * size});
      }
    }
    out.push_back({line, "street", ++id});
  }
  for (int j = 0; j <= n; ++j) {  // row y = j * size, one edge per block side
    for (int i = 0; i < n; ++i) {
      Point a{i * size, j * size + (interior(i, j) ? jog / 2 : 0.0)};
      Point b{(i + 1) * size, j * size - (interior(i + 1, j) ? jog / 2 : 0.0)};
      out.push_back({{a, b}, "street", ++id});
    }
  }
  return out;
}

// Degrees of the example's nodes (points within a millimetre are one), segments counted once.
std::map<std::pair<long long, long long>, int> example_degrees(const std::vector<ExampleEdge>& edges) {
  auto key = [](Point p) { return std::make_pair(std::llround(p.x * 1000.0), std::llround(p.y * 1000.0)); };
  std::set<std::pair<std::pair<long long, long long>, std::pair<long long, long long>>> seen;
  std::map<std::pair<long long, long long>, int> degree;
  for (const ExampleEdge& e : edges) {
    for (std::size_t i = 0; i + 1 < e.line.size(); ++i) {
      auto a = key(e.line[i]), b = key(e.line[i + 1]);
      if (a == b || !seen.insert({std::min(a, b), std::max(a, b)}).second) continue;
      ++degree[a];
      ++degree[b];
    }
  }
  return degree;
}

}  // namespace

TEST(GrowExample, ShortExampleSegmentsAreContractedIntoOneNode) {
  const int n = 4;
  const double size = 80.0, jog = 4.0;
  std::vector<ExampleEdge> example = staggered_grid(n, size, jog);
  // Two short segments that are not between junctions, so they stay: a 3 m dead end off a corner
  // (which becomes a T), and a shape point 3 m from a border T.
  example.push_back({{{0.0, 0.0}, {-3.0, 0.0}}, "street", 1000});
  for (ExampleEdge& e : example) {
    if (e.line.size() == 2 && e.line[0].x == size && e.line[0].y == 0.0 && e.line[1].x == 2 * size) {
      e.line.insert(e.line.begin() + 1, Point{size + 3.0, 0.0});
    }
  }
  auto before = example_degrees(example);
  std::size_t segments = 0;
  double total = 0.0;
  for (const ExampleEdge& e : example) {
    for (std::size_t i = 0; i + 1 < e.line.size(); ++i, ++segments) total += distance(e.line[i], e.line[i + 1]);
  }
  for (const auto& [p, d] : before) EXPECT_LE(d, 3);  // as drawn: Ts only
  ContractedExample c = contract_short_segments(example, 0.15);
  EXPECT_NEAR(c.mean_length, total / static_cast<double>(segments), 1e-9);  // the example as given
  EXPECT_EQ(c.contracted, static_cast<std::size_t>((n - 1) * (n - 1)));
  EXPECT_EQ(c.edges.size(), example.size());
  auto after = example_degrees(c.edges);
  EXPECT_EQ(after.size(), before.size() - static_cast<std::size_t>((n - 1) * (n - 1)));
  // Every interior crossing is one node of degree 4 at the midpoint of its two Ts; the border
  // nodes keep their place and degree.
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      auto k = std::make_pair(std::llround(i * size * 1000.0), std::llround(j * size * 1000.0));
      ASSERT_TRUE(after.count(k)) << i << " " << j;
      bool interior = i > 0 && i < n && j > 0 && j < n;
      bool corner = (i == 0 || i == n) && (j == 0 || j == n);
      const int spur = i == 0 && j == 0;
      EXPECT_EQ(after[k], (interior ? 4 : corner ? 2 : 3) + spur) << i << " " << j;
    }
  }
  EXPECT_EQ(after[std::make_pair(std::llround(-3000.0), 0LL)], 1);
  EXPECT_EQ(after[std::make_pair(std::llround((size + 3.0) * 1000.0), 0LL)], 2);
  std::size_t short_left = 0;
  for (const ExampleEdge& e : c.edges) {
    for (std::size_t i = 0; i + 1 < e.line.size(); ++i) short_left += distance(e.line[i], e.line[i + 1]) < 0.15 * c.mean_length;
  }
  EXPECT_EQ(short_left, 2u);  // the dead end and the shape point's
  // Nothing under the factor: the example comes back as given.
  ContractedExample none = contract_short_segments(example, 0.01);
  EXPECT_EQ(none.contracted, 0u);
  EXPECT_EQ(example_degrees(none.edges), before);
}

TEST(GrowExample, CrossingsDrawnAsTwoTsGrowAsCrossings) {
  // The example has no node of degree 4 as drawn, so without the contraction no output node
  // can have four streets (snapping never makes a node busier than the example's).
  Fixture f;
  GrowInput in = f.input();
  in.example = staggered_grid(8, 80.0, 4.0);
  for (std::uint64_t seed : {1u, 2u}) {
    GrowParams p = unrotated_params(seed);
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u);
    std::map<std::int64_t, int> degree;
    for (const GrownEdge& e : r.edges) {
      ++degree[e.from_node];
      ++degree[e.to_node];
    }
    std::size_t four = 0, three = 0;
    for (const auto& [node, d] : degree) {
      four += d >= 4;
      three += d == 3;
    }
    EXPECT_GT(four, three) << "seed " << seed;  // the example's junctions (49 of 81 nodes) are all crossings
    expect_planar(r, seed);
  }
}

namespace {
// Grows the 1 km square from `in`'s example with seeds 1-6 (no rotation, 3,000 edges, fill on:
// growth that cannot go north through a crossing goes on from new seeds), checks each is planar
// and a city of cul-de-sacs or not (dead-end share over 0.15), and counts its T junctions and
// crossings farther than 100 m from the square's edge.
void count_junctions_away_from_edge(Fixture& f, const GrowInput& in, bool cul_de_sacs, std::size_t& tees,
                                    std::size_t& crossings) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.rotation = false;
    p.max_edges = 3000;
    p.fill = true;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_EQ(r.stats.dead_end_share > 0.15, cul_de_sacs) << "seed " << seed;
    expect_planar(r, seed);
    std::map<std::int64_t, int> degree;
    std::map<std::int64_t, Point> at;
    for (const GrownEdge& e : r.edges) {
      ++degree[e.from_node];
      ++degree[e.to_node];
      at[e.from_node] = e.a;
      at[e.to_node] = e.b;
    }
    for (const auto& [node, d] : degree) {
      const Point q = at[node];
      if (std::min({q.x, q.y, 1000.0 - q.x, 1000.0 - q.y}) < 100.0) continue;
      tees += d == 3;
      crossings += d >= 4;
    }
  }
}
}  // namespace

TEST(GrowExample, ACityOfCulDeSacsKeepsItsCrossingsThroughJoins) {
  // The cul-de-sac grid (grid_with_teeth) with every crossing's northern arm starting with a 3 m
  // segment to a shape point, under the minimum edge: a copy of a crossing loses that arm and makes a
  // T, so crossings come only from joins onto T's. The example's draw alone (its share of junctions
  // with a fourth edge) left the output far short of that share; a refused join is now allowed while
  // the output (away from the region's edge) is short of it (canberra: 4-way share -59 -> -2 %).
  // Away from the region's edge (100 m), over seeds 1-6.
  Fixture f;
  GrowInput in = f.input();
  in.example.clear();
  std::int64_t id = 0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double x = j * 80.0, y = i * 80.0;
      in.example.push_back({{{i * 80.0, x}, {i * 80.0, x + 3.0}, {i * 80.0, x + 80.0}}, "street", ++id});
      if (i == 0 || i == 8) {
        in.example.push_back({{{x, y}, {x + 80.0, y}}, "street", ++id});
        continue;
      }
      in.example.push_back({{{x, y}, {x + 40.0, y}}, "street", ++id});
      in.example.push_back({{{x + 40.0, y}, {x + 80.0, y}}, "street", ++id});
      in.example.push_back({{{x + 40.0, y}, {x + 40.0, y + 40.0}}, "street", ++id});
    }
  }
  std::size_t tees = 0, crossings = 0;
  count_junctions_away_from_edge(f, in, true, tees, crossings);
  ASSERT_GT(tees + crossings, 300u);
  const double share = static_cast<double>(crossings) / static_cast<double>(tees + crossings);
  // 113 crossings and 670 T's over these seeds (14 %); with the draw alone 50 and 650 (7 %).
  EXPECT_GT(share, 0.11) << crossings << " crossings, " << tees << " T junctions";
}

namespace {
// A 9 x 9 grid of 80 m blocks whose crossings each start their northern arm with a 3 m segment
// to a shape point (under the minimum edge: a copy of a crossing loses that arm).
std::vector<ExampleEdge> grid_with_short_northern_arms() {
  std::vector<ExampleEdge> example;
  std::int64_t id = 0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double x = j * 80.0;
      example.push_back({{{i * 80.0, x}, {i * 80.0, x + 3.0}, {i * 80.0, x + 80.0}}, "street", ++id});
      example.push_back({{{x, i * 80.0}, {x + 80.0, i * 80.0}}, "street", ++id});
    }
  }
  return example;
}
}  // namespace

TEST(GrowExample, CrossingsLostByCopiesAreToppedUpByJoins) {
  // A grid (not a city of cul-de-sacs) whose crossings each start their northern arm with a 3 m
  // segment to a shape point, under the minimum edge: a copy of a crossing loses that arm and makes
  // a T, so the example's crossings come back only through joins onto T's. A join onto a T that the
  // example's draw refused is made while the output (away from the region's edge) has fewer
  // crossings among its junctions than the example as given (growth16: strasbourg's 4-way share
  // -27 -> -4 %). Away from the region's edge (100 m), over seeds 1-6.
  Fixture f;
  GrowInput in = f.input();
  in.example = grid_with_short_northern_arms();
  std::size_t tees = 0, crossings = 0;
  count_junctions_away_from_edge(f, in, false, tees, crossings);  // not a city of cul-de-sacs
  ASSERT_GT(tees + crossings, 150u);
  const double share = static_cast<double>(crossings) / static_cast<double>(tees + crossings);
  // 50 crossings and 164 T's over these seeds (23 %); with the draw alone 32 and 186 (15 %).
  EXPECT_GT(share, 0.19) << crossings << " crossings, " << tees << " T junctions";
}

TEST(GrowExample, NoNewTWhileShortOfCrossings) {
  // The grid of CrossingsLostByCopiesAreToppedUpByJoins (copies of its crossings lose their 3 m
  // northern arm, so the output is short of its crossings): a free end's snap or a contact that
  // would join a node of degree 2 (a shape point, a corner) and make a new T is refused while the
  // output is short of the example's crossing share, unless it goes straight on from the joining
  // node's street (growth18: new-york grew 54-89 T's inside its hull against the example's 26).
  // Seeds 1-6, no rotation, 3,000 edges, fill on.
  Fixture f;
  GrowInput in = f.input();
  in.example = grid_with_short_northern_arms();
  std::size_t new_ts = 0, refused = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.rotation = false;
    p.max_edges = 3000;
    p.fill = true;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    expect_planar(r, seed);
    new_ts += r.stats.node_joins[0][2] + r.stats.node_joins[1][2];  // by snap, by contact
    refused += r.stats.new_ts_refused;
  }
  EXPECT_GT(refused, 0u);
  // 12 such joins over these seeds (35 refused); without the rule 33.
  EXPECT_LT(new_ts, 22u) << refused << " refused";
}

TEST(GrowExample, FailedFrontsKeepTheExamplesDeadEndShare) {
  // The grid of FrontsThatCanNeitherGrowNorJoinAreCutBack (junctions moved by up to 20 m, T's on
  // every third column, the lake), with a 5 m dead-end spur at every other T: the example's street
  // ends are 11.5 % dead ends, but a spur is under the minimum edge, so no copy makes one, and the
  // output's dead ends away from the region's edge can only be failed fronts that close_front could
  // not join. Such a front used to stay a dead end with the example's probability (so barcelona,
  // whose copied dead ends are also lost to joins and the angle rule, grew half its dead ends); it
  // now stays one while the output, counted away from the region's edge, has fewer dead ends among
  // its street ends than the example, and is cut back otherwise. One random candidate and no
  // coherent copying, so that fronts fail. Seeds 1-6.
  Fixture f;
  GrowInput in = f.input();
  in.obstacles = {f.lake.get()};
  in.example = skewed_t_grid(true);
  std::size_t kept = 0, cut = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.max_edges = 3000;
    p.candidates = 1;
    p.coherence = 0.0;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_NEAR(r.stats.dead_end_share, 0.115, 0.01) << "seed " << seed;
    expect_planar(r, seed);
    kept += r.stats.fronts_dead_end;
    cut += r.stats.fronts_pruned;
  }
  // 7 failed fronts left dead ends, none cut back; with the example's probability 1 and 8.
  EXPECT_GE(kept, 4u) << cut << " cut back";
  EXPECT_EQ(cut, 0u) << kept << " left dead ends";
}

namespace {
// skewed_t_grid with a 30 m dead-end spur at every third T (long enough to be copied): the
// example's street ends are 8 % dead ends.
std::vector<ExampleEdge> skewed_t_grid_long_spurs() { return skewed_t_grid_with_spurs(3, 30.0); }
}  // namespace

TEST(GrowExample, FailedFrontsLeftDeadEndsAreCutBackWhenTheOutputHasTheExamplesShare) {
  // A failed front is left a dead end while the output is short of the example's dead ends
  // (FailedFrontsKeepTheExamplesDeadEndShare), counted at that moment; the dead ends copied later
  // and the junctions lost to later cut-backs can leave the finished output above the example's
  // share (strasbourg: 0.9 dead ends per growth, growth32). When the growth has finished, such
  // fronts, last kept first, are cut back while the output is not short of the example's dead
  // ends, and no further: the output keeps at least the example's share less half a dead end.
  // Counted away from the region's edge (a mean segment, r / 3) as the growth counts them. Two
  // random candidates and no coherent copying, so that fronts fail; seeds 1-20 (7 fronts kept, 3
  // of them cut back at the end, on seeds 3, 15 and 20).
  Fixture f;
  GrowInput in = f.input();
  in.obstacles = {f.lake.get()};
  in.example = skewed_t_grid_long_spurs();
  std::size_t trimmed = 0, kept = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.max_edges = 3000;
    p.candidates = 2;
    p.coherence = 0.0;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    EXPECT_NEAR(r.stats.dead_end_share, 0.08, 0.01) << "seed " << seed;
    expect_planar(r, seed);
    EXPECT_LE(r.stats.fronts_trimmed, r.stats.fronts_dead_end) << "seed " << seed;
    trimmed += r.stats.fronts_trimmed;
    kept += r.stats.fronts_dead_end;
    if (r.stats.fronts_trimmed == 0) continue;
    const double margin = r.stats.radius / 3.0;
    std::map<std::int64_t, int> degree;
    std::map<std::int64_t, Point> at;
    for (const GrownEdge& e : r.edges) {
      ++degree[e.from_node];
      ++degree[e.to_node];
      at[e.from_node] = e.a;
      at[e.to_node] = e.b;
    }
    double dead = 0.0, ends = 0.0;
    for (const auto& [node, d] : degree) {
      const Point q = at[node];
      if (d == 2 || std::min({q.x, q.y, 1000.0 - q.x, 1000.0 - q.y}) <= margin) continue;
      ends += 1.0;
      dead += d == 1;
    }
    EXPECT_GT(dead + 0.5, r.stats.dead_end_share * ends) << "seed " << seed << ": cut back below the example's share";
  }
  EXPECT_GE(trimmed, 2u) << kept << " kept";
}

namespace {
// skewed_t_grid's jittered 80 m grid with T's on every third column, each street drawn as four
// segments through shape points up to 6 m off its chord: streets with shape points, as strasbourg's
// curves are, so copies lose arms at junctions and joins onto shape points and splits make T's
// elsewhere along the streets.
std::vector<ExampleEdge> wobbly_t_grid() {
  auto at = skewed_grid_point;
  auto street = [](Point a, Point b, int salt) {
    const Point d = b - a;
    const Point normal{-d.y / distance(a, b), d.x / distance(a, b)};
    Polyline line{a};
    for (int k = 1; k < 4; ++k) line.push_back(a + (k / 4.0) * d + ((salt * 31 + k * 17) % 3 - 1) * 6.0 * normal);
    line.push_back(b);
    return line;
  };
  std::vector<ExampleEdge> example;
  std::int64_t id = 0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      example.push_back({street(at(j, i), at(j + 1, i), i * 9 + j), "street", ++id});
      if (j % 3 == 0 && i > 0 && i < 8) continue;
      example.push_back({street(at(i, j), at(i, j + 1), 100 + i * 9 + j), "street", ++id});
    }
  }
  return example;
}
}  // namespace

TEST(GrowExample, NewTsKeepTheExamplesJunctionsPerMetre) {
  // A new T (a join onto a shape point, a split) is refused while the output has as many junctions
  // per metre of street as the example (both counted away from the edge), failed fronts' joins
  // included (growth21: strasbourg grew 97-126 T's inside its shrunk hull against its example's 86).
  // The example has 6.6 junctions per km; away from the region's edge (100 m), over seeds 1-6, no
  // rotation, 3,000 edges, fill on, the output has 6.48 per km (185 new T's refused as dense);
  // without the rule 6.91.
  Fixture f;
  GrowInput in = f.input();
  in.example = wobbly_t_grid();
  auto inside = [](Point q) { return std::min({q.x, q.y, 1000.0 - q.x, 1000.0 - q.y}) >= 100.0; };
  std::size_t junctions = 0, dense = 0;
  double length = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    GrowParams p;
    p.seed = seed;
    p.rotation = false;
    p.max_edges = 3000;
    p.fill = true;
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
    expect_planar(r, seed);
    dense += r.stats.dense_ts_refused;
    EXPECT_LE(r.stats.dense_ts_refused, r.stats.new_ts_refused) << "seed " << seed;
    std::map<std::int64_t, int> degree;
    std::map<std::int64_t, Point> at;
    for (const GrownEdge& e : r.edges) {
      ++degree[e.from_node];
      ++degree[e.to_node];
      at[e.from_node] = e.a;
      at[e.to_node] = e.b;
      length += 0.5 * (inside(e.a) + inside(e.b)) * distance(e.a, e.b);
    }
    for (const auto& [node, d] : degree) junctions += d >= 3 && inside(at[node]);
  }
  ASSERT_GT(length, 0.0);
  EXPECT_GT(dense, 0u);
  EXPECT_LT(1000.0 * static_cast<double>(junctions) / length, 6.7) << junctions << " junctions in " << length << " m";
}

TEST(GrowExample, StraightOnJoinsAreRefusedWhereJunctionsAreDense) {
  // A new T is refused as dense (the output's junctions per metre above the example's) also when
  // it goes straight on (growth22; growth21 let those through: strasbourg's junctions +9 / +11 /
  // +6 %, with this 0 %). Grid fronts from (500, 300) run north into an existing street at y = 600
  // with shape points every 20 m; an existing comb (a junction every 5 m) makes the output dense.
  // Over seeds 1-6 (400 edges), 58 ends joined the street without the rule, none with it (534 new
  // T's refused as dense); without the comb it is joined either way (62 without the rule, 58 with).
  Fixture f;
  for (bool comb : {true, false}) {
    std::size_t on_street = 0, near_street = 0, dense = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      GrowInput in = f.input();
      in.seeds = {{500.0, 300.0}};
      Polyline street;
      for (double x = 100.0; x <= 900.0; x += 20.0) street.push_back({x, 600.0});
      in.existing.push_back(street);
      if (comb) {
        Polyline base;
        for (double x = 200.0; x <= 800.0; x += 5.0) base.push_back({x, 850.0});
        in.existing.push_back(base);
        for (double x = 205.0; x < 800.0; x += 5.0) in.existing.push_back({{x, 850.0}, {x, 860.0}});
      }
      GrowParams p;
      p.seed = seed;
      p.rotation = false;
      p.max_edges = 400;
      GrowResult r = grow_example(f.geos, in, p);
      expect_planar(r, seed);
      dense += r.stats.dense_ts_refused;
      for (const GrownEdge& e : r.edges) {
        for (Point q : {e.a, e.b}) {
          on_street += std::abs(q.y - 600.0) < 1e-6 && q.x > 100.0 && q.x < 900.0;
          near_street += q.y > 520.0 && q.y < 600.0 - 1e-6;
        }
      }
    }
    if (comb) {
      EXPECT_GT(near_street, 20u);  // the fronts got there
      EXPECT_GT(dense, 0u);
      EXPECT_EQ(on_street, 0u) << "new T's on the street while dense";
    } else {
      EXPECT_GT(on_street, 10u) << "without the comb the street is joined";
    }
  }
}

namespace {
// grid(8, 80) with an L at every fourth inner node (its west and south streets left out): nodes of
// degree 2 whose street turns by 90°, whose chains' chords run 45° off the grid.
std::vector<ExampleEdge> grid_with_corners() {
  std::vector<ExampleEdge> out;
  std::int64_t id = 0;
  auto corner = [](int i, int j) { return i > 0 && i < 8 && j > 0 && j < 8 && (i + 2 * j) % 4 == 0; };
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      // (j, i) -> (j + 1, i) is the west street of node (j + 1, i); (i, j) -> (i, j + 1) the south
      // street of node (i, j + 1).
      if (!corner(j + 1, i)) out.push_back({{{j * 80.0, i * 80.0}, {(j + 1) * 80.0, i * 80.0}}, "street", ++id});
      if (!corner(i, j + 1)) out.push_back({{{i * 80.0, j * 80.0}, {i * 80.0, (j + 1) * 80.0}}, "street", ++id});
    }
  }
  return out;
}
// The corners of a growth (nodes of degree 2 whose street turns by more than 45°) farther than an
// example segment from the region's border.
std::size_t corners_inside(const GrowResult& r) {
  std::map<std::int64_t, std::vector<Point>> at;  // per node: its position and its edges' far ends
  for (const GrownEdge& e : r.edges) {
    at[e.from_node].insert(at[e.from_node].end(), {e.a, e.b});
    at[e.to_node].insert(at[e.to_node].end(), {e.b, e.a});
  }
  std::size_t corners = 0;
  for (const auto& [node, v] : at) {
    const Point p = v[0];
    if (v.size() != 4 || p.x < 80.0 || p.y < 80.0 || p.x > 920.0 || p.y > 920.0) continue;
    const Point a = unit(p - v[1]), b = unit(v[3] - p);
    corners += std::acos(std::clamp(dot(a, b), -1.0, 1.0)) > std::atan(1.0);  // 45°
  }
  return corners;
}
}  // namespace

TEST(GrowExample, FrontsDoNotKeepTurningStreetsWhileLessOrderedThanTheExample) {
  // A front whose step copied an example junction but kept only a turning street takes it back and
  // goes straight on (or tries again) while the output's orientation order is under its example's;
  // once it is at least the example's, the corner stays (tokyo grew 53 corners per growth against
  // its example's few and a φ 18 % under it; barcelona, grown more ordered than its example, keeps
  // its corners). Seeds 1-6, 3,000 edges each.
  Fixture f;
  auto run = [&](const std::vector<ExampleEdge>& example, std::size_t& kept, std::size_t& back,
                 std::size_t& straight, std::size_t& corners) {
    GrowInput in = f.input();
    in.example = example;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      GrowParams p;
      p.seed = seed;
      p.max_edges = 3000;
      GrowResult r = grow_example(f.geos, in, p);
      ASSERT_GT(r.edges.size(), 100u) << "seed " << seed;
      expect_planar(r, seed);
      kept += r.stats.front_corners_kept;
      back += r.stats.front_corners_taken_back;
      straight += r.stats.front_corners_straight;
      corners += corners_inside(r);
    }
  };
  // The skewed T grid (junctions moved by up to 20 m, no corners): its growths stay less ordered.
  std::size_t kept = 0, back = 0, straight = 0, corners = 0;
  run(skewed_t_grid(false), kept, back, straight, corners);
  EXPECT_GT(back, 0u);
  EXPECT_GT(straight, 0u);
  // 15 corners inside over these seeds (74 taken back, 19 straight on, 1 kept); without the rule 31.
  EXPECT_LT(corners, 23u) << kept << " kept, " << back << " taken back, " << straight << " straight on";
  // A grid whose L corners make it less ordered than its growths soon are: corners are kept.
  std::size_t kept_l = 0, back_l = 0, straight_l = 0, corners_l = 0;
  run(grid_with_corners(), kept_l, back_l, straight_l, corners_l);
  EXPECT_GT(kept_l, 0u) << back_l << " taken back";
}
