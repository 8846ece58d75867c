// grow_patches' operations (Nishida et al. 2016, section 5): warping along a guide, interpolation
// of two patch libraries with weight t, blending; bad parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"
#include "patch_fixtures.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::avenue_grid;
using streetgen::test::crossings_without_node;
using streetgen::test::expect_same_graph;
using streetgen::test::interior_dead_ends;
using streetgen::test::wkt;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The avenue grid (100 m blocks) as patches, and the same grid scaled by `scale` (a second style
// with longer streets).
std::vector<Patch> grid_patches(GeosContext& geos, double scale) {
  std::vector<PatchInputEdge> edges = avenue_grid();
  for (PatchInputEdge& e : edges) {
    for (Point& q : e.line) q = {q.x * scale, q.y * scale};
  }
  return extract_patches(geos, edges, PatchParams{}).patches;
}

struct Fixture {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-1500 -1500, 1500 -1500, 1500 1500, -1500 1500, -1500 -1500))");
  GrowInput input() {
    GrowInput in;
    in.patches = grid_patches(geos, 1.0);
    in.region = region.get();
    in.seeds = {{0.0, 0.0}};
    return in;
  }
};

// Share of the length of edges whose direction is within `tol` degrees of `angle` or of its
// perpendicular (a grid's two families).
double aligned_share(const GrowResult& r, double angle, double tol) {
  double in = 0.0, all = 0.0;
  for (const GrownEdge& e : r.edges) {
    const double len = distance(e.a, e.b);
    double d = std::fmod(std::atan2(e.b.y - e.a.y, e.b.x - e.a.x) - angle, kPi / 2.0);
    if (d < 0) d += kPi / 2.0;
    d = std::min(d, kPi / 2.0 - d);
    all += len;
    if (d <= tol * kPi / 180.0) in += len;
  }
  return all > 0.0 ? in / all : 0.0;
}

}  // namespace

TEST(PatchOperations, WarpingTurnsTheGridToTheGuide) {
  Fixture f;
  GrowInput in = f.input();
  GrowParams p;
  p.use_patches = true;
  p.seed = 2;
  p.max_edges = 800;
  GrowResult free = grow_example(f.geos, in, p);
  in.guide = {{{-1500.0, -1500.0 * std::tan(kPi / 6.0)}, {1500.0, 1500.0 * std::tan(kPi / 6.0)}}};  // 30 degrees
  GrowResult warped = grow_example(f.geos, in, p);
  ASSERT_GT(free.edges.size(), 200u);
  ASSERT_GT(warped.edges.size(), 200u);
  const double turned = aligned_share(warped, kPi / 6.0, 3.0);
  const double kept = aligned_share(free, kPi / 6.0, 3.0);
  EXPECT_GT(turned, 0.8) << "warped: length share along the guide's directions";
  EXPECT_LT(kept, 0.2) << "unguided: the grid keeps the example's axes";
  EXPECT_GT(aligned_share(free, 0.0, 3.0), 0.8);
  EXPECT_GT(warped.stats.guided, 0u);
  // guide_reach: a guide farther than it turns nothing.
  in.guide = {{{5000.0, 5000.0}, {6000.0, 5500.0}}};
  p.guide_reach = 100.0;
  GrowResult far = grow_example(f.geos, in, p);
  EXPECT_GT(aligned_share(far, 0.0, 3.0), 0.8);
}

TEST(PatchOperations, InterpolationMovesFromOneStyleToTheOther) {
  Fixture f;
  GrowInput in = f.input();
  in.patches_b = grid_patches(f.geos, 2.5);
  GrowParams p;
  p.use_patches = true;
  p.seed = 4;
  p.max_edges = 600;
  double share[3];
  double mean[3];
  const double ts[3] = {0.0, 0.5, 1.0};
  for (int i = 0; i < 3; ++i) {
    p.patch.t = ts[i];
    GrowResult r = grow_example(f.geos, in, p);
    ASSERT_GT(r.edges.size(), 100u) << "t = " << ts[i];
    double len = 0.0;
    for (const GrownEdge& e : r.edges) len += distance(e.a, e.b);
    // Patches placed from the second library (by count: its patches are 2.5 times larger).
    share[i] = static_cast<double>(r.stats.patches_b_placed) / static_cast<double>(r.stats.patches_placed);
    mean[i] = len / static_cast<double>(r.edges.size());
  }
  EXPECT_EQ(share[0], 0.0);
  EXPECT_EQ(share[2], 1.0);
  EXPECT_GT(share[1], 0.2);
  EXPECT_LT(share[1], 0.8);
  EXPECT_LT(mean[0], mean[1]);
  EXPECT_LT(mean[1], mean[2]);
  EXPECT_GT(mean[2], 1.8 * mean[0]);
}

TEST(PatchOperations, BlendingByGaussianFallOffFromEachStylesSeed) {
  Fixture f;
  GrowInput in = f.input();
  in.patches_b = grid_patches(f.geos, 2.5);
  in.seeds = {{-1000.0, 0.0}, {1000.0, 0.0}};
  GrowParams p;
  p.use_patches = true;
  p.seed = 4;
  p.max_edges = 1500;
  p.blend.mode = BlendParams::Mode::points;
  p.blend.points = {{-1000.0, 0.0}, {1000.0, 0.0}};
  p.blend.sigma = 500.0;
  GrowResult r = grow_example(f.geos, in, p);
  double west[2] = {0, 0}, east[2] = {0, 0};
  for (const GrownEdge& e : r.edges) {
    if (e.example < 0) continue;
    const double x = 0.5 * (e.a.x + e.b.x);
    if (x < -400) west[e.example] += distance(e.a, e.b);
    if (x > 400) east[e.example] += distance(e.a, e.b);
  }
  ASSERT_GT(west[0] + west[1], 0.0);
  ASSERT_GT(east[0] + east[1], 0.0);
  EXPECT_LT(west[1] / (west[0] + west[1]), 0.2);
  EXPECT_GT(east[1] / (east[0] + east[1]), 0.8);
}

TEST(PatchOperations, BadParametersAreRejected) {
  Fixture f;
  GrowInput in = f.input();
  GrowParams p;
  p.use_patches = true;
  p.max_edges = 10;
  auto message = [&](const GrowInput& input, const GrowParams& params) -> std::string {
    try {
      grow_example(f.geos, input, params);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
      return e.what();
    }
    return "accepted";
  };
  GrowParams bad_t = p;
  bad_t.patch.t = 1.5;
  EXPECT_NE(message(in, bad_t).find("t must be in [0, 1]"), std::string::npos);
  bad_t.patch.t = NAN;
  EXPECT_NE(message(in, bad_t).find("t must be in [0, 1]"), std::string::npos);
  GrowParams blend = p;
  blend.blend.mode = BlendParams::Mode::gradient;
  EXPECT_NE(message(in, blend).find("blend needs a second patch library"), std::string::npos);
  GrowInput two = in;
  two.patches_b = grid_patches(f.geos, 2.0);
  blend.blend.mode = BlendParams::Mode::points;
  blend.blend.points = {{0.0, 0.0}};
  EXPECT_NE(message(two, blend).find("blend_points must hold two points"), std::string::npos);
  GrowInput closed = two;
  for (Patch& patch : closed.patches_b) {
    for (PatchEdge& e : patch.edges) {
      if (e.role == PatchEdgeRole::connector) e.role = PatchEdgeRole::inner;
    }
  }
  EXPECT_NE(message(closed, p).find("interpolate library has a connector"), std::string::npos);
  GrowInput point_guide = in;
  point_guide.guide = {{{5.0, 5.0}, {5.0, 5.0}}};
  EXPECT_NE(message(point_guide, p).find("guide has no segment"), std::string::npos);
}

TEST(PatchOperations, PruneDanglingLeavesNoDeadEndTheExampleDoesNotHave) {
  Fixture f;
  GrowInput in = f.input();  // the avenue grid has no dead end
  GrowParams p;
  p.use_patches = true;
  p.seed = 4;
  p.max_edges = 800;  // stops with open fronts inside the region
  p.patch.prune_without_own_dead_ends = false;  // (else pruned by default: the grid has no dead end)
  GrowResult kept = grow_example(f.geos, in, p);
  p.patch.prune_dangling = true;
  GrowResult pruned = grow_example(f.geos, in, p);
  EXPECT_GT(interior_dead_ends(kept), 10);
  EXPECT_EQ(interior_dead_ends(pruned), 0);
  EXPECT_GT(pruned.stats.dangling_pruned, 10u);
  EXPECT_LT(pruned.edges.size(), kept.edges.size());
  EXPECT_GT(pruned.edges.size(), kept.edges.size() / 2);
}

// fallback_curvature: the statistical fallback bends its streets by the example's curvature (Nishida
// et al.: procedural growth from the length and curvature distributions). A grid of 100 m blocks whose every street is
// an arc turning by 40 degrees (four segments): with each patch usable once, most of the network
// is statistical. With fallback_curvature those streets turn at their shape points by about the
// example's curvature per metre; without it they run straight. Planar and deterministic either way.
TEST(PatchOperations, FallbackStreetsBendByTheExamplesCurvature) {
  Fixture f;
  const double turn = 40.0 * kPi / 180.0;
  auto arc = [&](Point a, Point b, int side) {
    // four segments along the circular arc from a to b that turns by `turn` (bulging to `side`)
    const Point d = b - a;
    const double chord = std::hypot(d.x, d.y), heading = std::atan2(d.y, d.x);
    double along = 0.0;  // the segments' projections on the chord, per unit length
    for (int i = 0; i < 4; ++i) along += std::cos(turn * ((i + 0.5) / 4.0 - 0.5));
    const double step = chord / along;
    std::vector<Point> line{a};
    Point q = a;
    for (int i = 0; i < 4; ++i) {
      const double h = heading + side * turn * ((i + 0.5) / 4.0 - 0.5);
      q = q + step * Point{std::cos(h), std::sin(h)};
      line.push_back(q);
    }
    line.back() = b;  // (equal up to rounding)
    return line;
  };
  std::vector<PatchInputEdge> example;
  std::int64_t id = 0;
  for (int i = 0; i <= 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const int side = (i + j) % 2 ? 1 : -1;
      example.push_back({arc({j * 100.0, i * 100.0}, {(j + 1) * 100.0, i * 100.0}, side), "street", ++id, false});
      example.push_back({arc({i * 100.0, j * 100.0}, {i * 100.0, (j + 1) * 100.0}, side), "street", ++id, false});
    }
  }
  double example_curvature = 0.0;
  for (const PatchInputEdge& e : example) example_curvature += curvature(e.line) / static_cast<double>(example.size());
  ASSERT_GT(example_curvature, 0.003);  // (40 degrees over about 100 m: 0.007 rad/m)

  GrowInput in = f.input();
  in.patches = extract_patches(f.geos, example, PatchParams{}).patches;
  GrowParams p;
  p.use_patches = true;
  p.seed = 3;
  p.max_edges = 1500;
  p.patch.max_uses = 1;
  p.patch.fallback_curvature = false;
  const GrowResult straight = grow_example(f.geos, in, p);
  p.patch.fallback_curvature = true;
  const GrowResult bent = grow_example(f.geos, in, p);

  // The statistical streets' gentle turns: nodes of degree 2 between two statistical edges that
  // turn by 1-16 degrees (an arc's shape points turn by at most 15; joins and snaps, which also
  // leave such nodes, mostly turn by more or not at all), and their turn per metre of statistical
  // street.
  struct Turns {
    int gentle = 0;
    double per_metre = 0.0;
  };
  auto gentle_turns = [](const GrowResult& r) {
    std::map<std::int64_t, std::vector<const GrownEdge*>> at;
    double length = 0.0;
    for (const GrownEdge& e : r.edges) {
      at[e.from_node].push_back(&e);
      at[e.to_node].push_back(&e);
      if (e.example < 0) length += distance(e.a, e.b);
    }
    Turns t;
    for (const auto& [node, edges] : at) {
      if (edges.size() != 2 || edges[0]->example >= 0 || edges[1]->example >= 0) continue;
      auto away = [node = node](const GrownEdge* e) { return e->from_node == node ? e->b - e->a : e->a - e->b; };
      const Point u = away(edges[0]), v = away(edges[1]);
      const double turn = kPi - std::acos(std::clamp(dot(u, v) / (norm(u) * norm(v)), -1.0, 1.0));
      if (turn < 1.0 * kPi / 180.0 || turn > 16.0 * kPi / 180.0) continue;
      ++t.gentle;
      t.per_metre += turn;
    }
    if (length > 0.0) t.per_metre /= length;
    return t;
  };
  EXPECT_EQ(straight.stats.fallback_curved, 0u);
  ASSERT_GT(bent.stats.fallback, 50u);
  EXPECT_GT(bent.stats.fallback_curved, 20u);
  const Turns off = gentle_turns(straight), on = gentle_turns(bent);
  EXPECT_GT(on.gentle, 4 * off.gentle + 20);
  EXPECT_LT(off.per_metre, 0.2 * example_curvature);
  EXPECT_GT(on.per_metre, 0.4 * example_curvature);
  EXPECT_LT(on.per_metre, 1.5 * example_curvature);
  EXPECT_EQ(crossings_without_node(bent), 0);
  expect_same_graph(grow_example(f.geos, in, p), bent);
}
