#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"
#include "core/streets/polyline.hpp"
#include "patch_fixtures.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::avenue_grid;
using streetgen::test::crosses_without_node;
using streetgen::test::expect_same_edges;
using streetgen::test::wkt;

namespace {

constexpr double kPi = 3.14159265358979323846;

bool has(const std::vector<std::string>& tags, const char* tag) {
  return std::find(tags.begin(), tags.end(), tag) != tags.end();
}

// A 5 x 5 node grid of 100 m blocks ("avenue" on the outer ring, "street" inside) whose junction
// at (200, 200) is a roundabout of radius 20 m, plus a dead end leaving the corner (0, 0).
std::vector<PatchInputEdge> grid_with_roundabout(bool flag) {
  std::vector<PatchInputEdge> out;
  std::int64_t id = 0;
  const Point centre{200, 200};
  const double r = 20.0;
  auto end_at = [&](Point p) {  // streets into the roundabout stop on its ring
    if (distance(p, centre) < 1e-9) return p;
    return p;
  };
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const char* cls = (i == 0 || i == 4) ? "avenue" : "street";
      Point a{j * 100.0, i * 100.0}, b{(j + 1) * 100.0, i * 100.0};
      Point c{i * 100.0, j * 100.0}, d{i * 100.0, (j + 1) * 100.0};
      for (auto [p, q] : {std::pair{a, b}, std::pair{c, d}}) {
        if (distance(p, centre) < 1e-9) p = p + r * unit(q - p);
        if (distance(q, centre) < 1e-9) q = q + r * unit(p - q);
        out.push_back({{end_at(p), end_at(q)}, cls, ++id, false});
      }
    }
  }
  for (int quarter = 0; quarter < 4; ++quarter) {  // the ring, four arcs of 8 chords
    Polyline arc;
    for (int k = 0; k <= 8; ++k) {
      double t = (quarter + k / 8.0) * 0.5 * kPi;
      arc.push_back({centre.x + r * std::cos(t), centre.y + r * std::sin(t)});
    }
    out.push_back({arc, "street", ++id, flag});
  }
  out.push_back({{{0, 0}, {-30, -40}}, "street", ++id, false});
  return out;
}

}  // namespace

TEST(ExtractPatches, GridWithRoundaboutAndDeadEnd) {
  for (bool flag : {true, false}) {  // from the example's flag, or found as a compact face
    GeosContext geos;
    PatchExtraction x = extract_patches(geos, grid_with_roundabout(flag), PatchParams{});
    ASSERT_GT(x.patches.size(), 10u);
    std::size_t roundabouts = 0, cul_de_sacs = 0;
    std::map<std::pair<std::pair<long, long>, std::pair<long, long>>, int> connector_ends;
    auto key = [](Point p) { return std::pair<long, long>{std::lround(p.x * 1000), std::lround(p.y * 1000)}; };
    for (const Patch& p : x.patches) {
      if (has(p.tags, "roundabout")) {
        ++roundabouts;
        EXPECT_TRUE(has(p.tags, "loop"));
        EXPECT_TRUE(has(p.tags, "curved"));
        std::size_t ring = 0, connectors = 0;
        for (const PatchEdge& e : p.edges) {
          ring += has(e.tags, "roundabout");
          connectors += e.role == PatchEdgeRole::connector;
        }
        EXPECT_EQ(ring, 4u);
        EXPECT_EQ(connectors, 4u);  // the four approaches
      }
      if (has(p.tags, "cul-de-sac")) {
        ++cul_de_sacs;
        bool dead = false;
        for (const PatchEdge& e : p.edges) {
          if (e.role == PatchEdgeRole::dead_end) {
            dead = true;
            EXPECT_TRUE(has(e.tags, "dead-end"));
            EXPECT_TRUE(has(e.end_tags, "dead-end"));
            EXPECT_NEAR(e.line.back().x, -30.0, 1e-9);  // oriented towards the dead end
          }
        }
        EXPECT_TRUE(dead);
      }
      EXPECT_TRUE(has(p.tags, "main") || has(p.tags, "local"));
      EXPECT_TRUE(has(p.tags, "curved") != has(p.tags, "straight"));
      for (const PatchEdge& e : p.edges) {
        if (e.role != PatchEdgeRole::connector) continue;
        EXPECT_TRUE(has(e.end_tags, "connectable"));
        EXPECT_TRUE(has(e.tags, "connector"));
        connector_ends[{key(e.line.front()), key(e.line.back())}] += 1;
      }
    }
    EXPECT_EQ(roundabouts, 1u) << "flag " << flag;
    EXPECT_EQ(cul_de_sacs, 1u);
    // Connectors are shared: each one appears reversed in the neighbouring patch.
    ASSERT_FALSE(connector_ends.empty());
    for (const auto& [ends, count] : connector_ends) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(connector_ends.count({ends.second, ends.first}), 1u);
    }
    // Every street belongs to one patch, or to two as a connector.
    std::map<std::int64_t, int> uses;
    for (const Patch& p : x.patches) {
      for (const PatchEdge& e : p.edges) uses[e.example_id] += e.role == PatchEdgeRole::connector ? 1 : 2;
    }
    for (const auto& [id, n] : uses) EXPECT_EQ(n, 2) << "street " << id;
  }
}

TEST(ExtractPatches, ShortEdgesJoinJunctionsIntoOnePatch) {
  // Two junctions 10 m apart (a staggered crossing) are one patch, not two.
  std::vector<PatchInputEdge> ex = {
      {{{0, 0}, {100, 0}}, "street", 1, false},    {{{100, 0}, {110, 0}}, "street", 2, false},
      {{{110, 0}, {210, 0}}, "street", 3, false},  {{{100, 0}, {100, 100}}, "street", 4, false},
      {{{110, 0}, {110, -100}}, "street", 5, false}, {{{0, 0}, {0, 100}}, "street", 6, false},
      {{{0, 0}, {0, -100}}, "street", 7, false},     {{{0, 100}, {100, 100}}, "street", 8, false}};
  GeosContext geos;
  PatchParams params;
  params.short_edge = 30.0;
  params.detect_circles = false;
  PatchExtraction x = extract_patches(geos, ex, params);
  bool joined = false;
  for (const Patch& p : x.patches) {
    for (const PatchEdge& e : p.edges) joined = joined || (e.example_id == 2 && e.role == PatchEdgeRole::inner);
  }
  EXPECT_TRUE(joined);
}

TEST(ExtractPatches, RowOrderAndDirectionDoNotMatter) {
  GeosContext geos;
  std::vector<PatchInputEdge> ex = grid_with_roundabout(false);
  PatchExtraction a = extract_patches(geos, ex, PatchParams{});
  std::reverse(ex.begin(), ex.end());
  for (std::size_t i = 0; i < ex.size(); i += 3) std::reverse(ex[i].line.begin(), ex[i].line.end());
  PatchExtraction b = extract_patches(geos, ex, PatchParams{});
  ASSERT_EQ(a.patches.size(), b.patches.size());
  for (std::size_t i = 0; i < a.patches.size(); ++i) {
    ASSERT_EQ(a.patches[i].edges.size(), b.patches[i].edges.size());
    EXPECT_EQ(a.patches[i].tags, b.patches[i].tags);
    for (std::size_t k = 0; k < a.patches[i].edges.size(); ++k) {
      EXPECT_EQ(a.patches[i].edges[k].line.size(), b.patches[i].edges[k].line.size());
      EXPECT_EQ(a.patches[i].edges[k].line.front().x, b.patches[i].edges[k].line.front().x);
      EXPECT_EQ(a.patches[i].edges[k].line.back().y, b.patches[i].edges[k].line.back().y);
    }
  }
}

TEST(ExtractPatches, BadInputIsRejected) {
  GeosContext geos;
  EXPECT_THROW(extract_patches(geos, {}, PatchParams{}), Error);
  EXPECT_THROW(extract_patches(geos, {{{{1, 1}, {1, 1}}, "street", 1, false}}, PatchParams{}), Error);
  PatchParams p;
  p.short_edge = -1;
  EXPECT_THROW(extract_patches(geos, grid_with_roundabout(false), p), Error);
  p = PatchParams{};
  p.circle_compactness = 0;
  EXPECT_THROW(extract_patches(geos, grid_with_roundabout(false), p), Error);
}

namespace {
struct PatchFixture {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-500 -500, 1500 -500, 1500 1500, -500 1500, -500 -500))");
  GeomPtr lake = wkt(geos, "POLYGON((800 800, 1100 800, 1100 1100, 800 1100, 800 800))");
  GrowInput input() {
    GrowInput in;
    in.patches = extract_patches(geos, grid_with_roundabout(true), PatchParams{}).patches;
    in.region = region.get();
    in.obstacles = {lake.get()};
    in.seeds = {{500.0, 500.0}};
    return in;
  }
};

}  // namespace

TEST(GrowPatches, PlanarInsideTheRegionMostlyFromPatches) {
  PatchFixture f;
  GrowInput in = f.input();
  GrowParams p;
  p.use_patches = true;
  p.seed = 3;
  p.max_edges = 1500;
  // (the open fronts kept: the fixture's grid has no dead end of its own, and the streets pruned
  // after growth would leave fewer patch edges than stats.patch_edges counted)
  p.patch.prune_without_own_dead_ends = false;
  GrowResult r = grow_example(f.geos, in, p);
  ASSERT_GT(r.edges.size(), 200u);
  std::size_t from_patches = 0;
  for (const GrownEdge& e : r.edges) {
    from_patches += e.example >= 0;
    for (Point q : {e.a, e.b}) {
      EXPECT_TRUE(q.x >= -500 && q.x <= 1500 && q.y >= -500 && q.y <= 1500);
      EXPECT_FALSE(q.x > 800 && q.x < 1100 && q.y > 800 && q.y < 1100) << q.x << " " << q.y;
    }
  }
  EXPECT_GE(from_patches, r.stats.patch_edges);  // a split patch edge counts twice in the output
  EXPECT_GT(r.stats.patches_placed, 20u);
  // Patch size at fronts (DEBUG1): every draw is placed or refused for a reason, at most one
  // placement per front with a first draw (the fixture's equal streets may leave a tercile empty).
  std::size_t first = 0, placed = 0;
  for (int c = 0; c < 3; ++c) {
    std::size_t refused = 0;
    for (std::size_t n : r.stats.size_refusals[c]) refused += n;
    EXPECT_EQ(r.stats.size_tried[c], r.stats.size_placed[c] + refused) << c;
    EXPECT_EQ(r.stats.size_refusals[c][kRefNone], 0u) << c;
    first += r.stats.size_first[c];
    placed += r.stats.size_placed[c];
  }
  EXPECT_LE(placed, first);
  EXPECT_LE(placed, r.stats.patches_placed);
  EXPECT_GT(placed, 0u);
  EXPECT_LE(r.stats.size_cut[0], r.stats.size_cut[1]);
  EXPECT_GT(r.stats.size_cut[0], 0.0);
  EXPECT_GT(static_cast<double>(from_patches) / r.edges.size(), 0.5);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < r.edges.size(); ++j) bad += crosses_without_node(r.edges[i], r.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
}

TEST(GrowPatches, SameSeedSameOutput) {
  PatchFixture f;
  GrowInput in = f.input();
  GrowParams p;
  p.use_patches = true;
  p.max_edges = 600;
  p.seed = 5;
  GrowResult a = grow_example(f.geos, in, p);
  GrowResult b = grow_example(f.geos, in, p);
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].a.x, b.edges[i].a.x);
    EXPECT_EQ(a.edges[i].b.y, b.edges[i].b.y);
    EXPECT_EQ(a.edges[i].example_id, b.edges[i].example_id);
  }
  p.seed = 6;
  GrowResult c = grow_example(f.geos, in, p);
  bool differ = c.edges.size() != a.edges.size();
  for (std::size_t i = 0; !differ && i < a.edges.size(); ++i) differ = a.edges[i].example_id != c.edges[i].example_id;
  EXPECT_TRUE(differ);
}

TEST(GrowPatches, BadPatchesAreRejected) {
  PatchFixture f;
  GrowInput in = f.input();
  GrowParams p;
  p.use_patches = true;
  GrowInput empty = in;
  empty.patches.clear();
  EXPECT_THROW(grow_example(f.geos, empty, p), Error);
  GrowInput closed = in;
  for (Patch& patch : closed.patches) {
    for (PatchEdge& e : patch.edges) {
      if (e.role == PatchEdgeRole::connector) e.role = PatchEdgeRole::inner;
    }
  }
  try {
    grow_example(f.geos, closed, p);
    FAIL() << "no connector accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
    EXPECT_NE(std::string(e.what()).find("connector"), std::string::npos);
  }
  p.patch.scale = 0;
  EXPECT_THROW(grow_example(f.geos, in, p), Error);
}


TEST(ExtractPatches, LevelsSplitArterialAndLocalPatches) {
  GeosContext geos;
  PatchExtraction x = extract_patches(geos, avenue_grid(), PatchParams{});
  std::size_t arterial = 0, local = 0;
  for (const Patch& p : x.patches) {
    bool is_arterial = has(p.tags, "arterial");
    arterial += is_arterial;
    local += !is_arterial;
    for (const PatchEdge& e : p.edges) {
      if (!is_arterial) {
        // Local patches' streets end at junctions (an avenue crossing is the arterial level's,
        // still a connector); the grid has no dead end.
        EXPECT_NE(e.role, PatchEdgeRole::dead_end);
        continue;
      }
      EXPECT_EQ(e.road_class, "avenue");  // the arterial level holds main streets only
      // Its streets run on through the local junctions: avenue to avenue, 300 m.
      if (e.role == PatchEdgeRole::connector) {
        EXPECT_NEAR(length(e.line), 300.0, 1e-6);
      }
    }
  }
  EXPECT_EQ(arterial, 4u);  // the four avenue crossings
  EXPECT_EQ(x.arterial_patches, 4u);
  // Local patches: every junction where a street meets (the 7 x 7 nodes but the four corners and
  // the four avenue crossings).
  EXPECT_EQ(local, 49u - 4u - 4u);
  // Without levels: one patch per junction, none arterial.
  PatchParams flat;
  flat.levels = false;
  PatchExtraction y = extract_patches(geos, avenue_grid(), flat);
  EXPECT_EQ(y.patches.size(), 49u - 4u);
  for (const Patch& p : y.patches) EXPECT_FALSE(has(p.tags, "arterial"));
  EXPECT_EQ(y.arterial_patches, 0u);
}

TEST(ExtractPatches, CropMarginTurnsDeadEndsAtTheHullIntoCutConnectors) {
  GeosContext geos;
  std::vector<PatchInputEdge> ex = grid_with_roundabout(true);
  ex.push_back({{{400, 400}, {406, 408}}, "street", 999, false});  // a 10 m stub cut by the crop
  auto count = [](const PatchExtraction& x, const char* edge_tag, PatchEdgeRole role) {
    std::size_t n = 0;
    for (const Patch& p : x.patches) {
      for (const PatchEdge& e : p.edges) n += has(e.tags, edge_tag) && e.role == role;
    }
    return n;
  };
  PatchParams off;
  off.levels = false;
  PatchExtraction a = extract_patches(geos, ex, off);
  EXPECT_EQ(count(a, "dead-end", PatchEdgeRole::dead_end), 2u);  // the 50 m dead end and the stub
  EXPECT_EQ(count(a, "cut", PatchEdgeRole::connector), 0u);
  PatchParams on = off;
  on.crop_margin = 5.0;
  PatchExtraction b = extract_patches(geos, ex, on);
  EXPECT_EQ(count(b, "dead-end", PatchEdgeRole::dead_end), 0u);
  EXPECT_EQ(count(b, "cut", PatchEdgeRole::connector), 2u);  // both ends lie on the hull
  for (const Patch& p : b.patches) {
    EXPECT_FALSE(has(p.tags, "cul-de-sac"));
    for (const PatchEdge& e : p.edges) {
      if (!has(e.tags, "cut")) continue;
      EXPECT_TRUE(has(e.end_tags, "cut"));
      EXPECT_FALSE(has(e.end_tags, "dead-end"));
    }
  }
  on.crop_margin = -1.0;
  EXPECT_THROW(extract_patches(geos, ex, on), Error);
}

TEST(GrowPatches, ArterialsFirstThenLocalStreetsFromTheirSeeds) {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-600 -600, 1200 -600, 1200 1200, -600 1200, -600 -600))");
  GrowInput in;
  in.patches = extract_patches(geos, avenue_grid(), PatchParams{}).patches;
  in.region = region.get();
  in.seeds = {{300.0, 300.0}};
  GrowParams p;
  p.use_patches = true;
  p.seed = 2;
  p.max_edges = 3000;
  p.patch.demote_arterial_stubs = false;  // the classes as the phases gave them (the row order below)
  GrowResult r = grow_example(geos, in, p);
  ASSERT_GT(r.edges.size(), 100u);
  EXPECT_GT(r.stats.arterial_patches_placed, 3u);
  EXPECT_GT(r.stats.local_seeds, 10u);
  EXPECT_GT(r.stats.local_seeds_used, 0u);
  // Why arterial fronts stopped (DEBUG1): each visit has one outcome, each front every draw of
  // which was refused has at least one refused draw with a reason, and the placed patches' connectors
  // made the fronts.
  const GrowStats& s = r.stats;
  const std::size_t stopped = s.arterial_front_finished + s.arterial_front_no_direction + s.arterial_front_used_up +
                              s.arterial_front_reach + s.arterial_front_hausdorff + s.arterial_front_refused;
  EXPECT_GT(s.arterial_fronts, 0u);
  EXPECT_LE(stopped, s.arterial_fronts);
  // the seed's patch and the arterial refill's seed patches have no front
  EXPECT_GE(s.arterial_fronts - stopped + 1 + s.arterial_reseeds, s.arterial_patches_placed);
  std::size_t refused = 0;
  for (std::size_t k = 0; k < kPatchRefusals; ++k) refused += s.arterial_refusals[k];
  EXPECT_EQ(s.arterial_refusals[kRefNone], 0u);
  EXPECT_GE(refused, s.arterial_front_refused);
  EXPECT_GT(s.arterial_conn_front, 0u);
  EXPECT_LE(s.arterial_conn_front, s.arterial_fronts);
  // The output is in growth order: the arterial phase's avenues first, then the streets.
  std::size_t first_street = r.edges.size(), avenues = 0, avenues_before = 0;
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    if (r.edges[i].road_class == "street" && first_street == r.edges.size()) first_street = i;
    if (r.edges[i].road_class == "avenue") {
      ++avenues;
      avenues_before += first_street == r.edges.size();
    }
  }
  ASSERT_GT(avenues, 0u);
  EXPECT_GT(first_street, 20u);
  EXPECT_GE(static_cast<double>(avenues_before) / avenues, 0.9);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < r.edges.size(); ++j) bad += crosses_without_node(r.edges[i], r.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
  // Levels off: one phase, streets from the first patch on.
  p.patch.levels = false;
  GrowResult flat = grow_example(geos, in, p);
  EXPECT_EQ(flat.stats.arterial_patches_placed, 0u);
  EXPECT_EQ(flat.stats.local_seeds, 0u);
  EXPECT_EQ(flat.stats.arterial_fronts, 0u);
  EXPECT_EQ(flat.stats.arterial_conn_front, 0u);
  std::size_t flat_first_street = flat.edges.size();
  for (std::size_t i = 0; i < flat.edges.size() && flat_first_street == flat.edges.size(); ++i) {
    if (flat.edges[i].road_class == "street") flat_first_street = i;
  }
  EXPECT_LT(flat_first_street, 20u);
}

// arterial_refill: the arterial phase copies the example's arterials outwards from its seed patch
// and stops where they stop (here the second part of a region of two, 200 m apart, which no
// arterial reaches); arterial seed patches in the land farther from every arterial than the
// example's widest space between its own arterials grow arterials there too, before the local
// phase. Planar, inside the region, deterministic.
TEST(GrowPatches, ArterialRefillSeedsArterialsWhereThePhaseStopped) {
  GeosContext geos;
  GeomPtr two = wkt(geos,
                    "MULTIPOLYGON(((-1200 -1200, -100 -1200, -100 1200, -1200 1200, -1200 -1200)),"
                    "((100 -1200, 1200 -1200, 1200 1200, 100 1200, 100 -1200)))");
  GrowInput in;
  in.patches = extract_patches(geos, avenue_grid(), PatchParams{}).patches;
  in.region = two.get();
  in.seeds = {{-600.0, 0.0}};
  GrowParams p;
  p.use_patches = true;
  p.seed = 2;
  p.max_edges = 20000;
  p.patch.arterial_refill = 0.0;
  p.patch.demote_arterial_stubs = false;  // (it takes avenue stubs back after the refill's count)
  GrowResult off = grow_example(geos, in, p);
  p.patch.arterial_refill = 0.5;  // (its default)
  GrowResult on = grow_example(geos, in, p);
  auto avenues_east = [](const GrowResult& r) {
    double total = 0.0;
    for (const GrownEdge& e : r.edges) {
      if (e.road_class == "avenue" && e.a.x > 0.0) total += std::hypot(e.b.x - e.a.x, e.b.y - e.a.y);
    }
    return total;
  };
  auto avenues = [](const GrowResult& r) {
    double total = 0.0;
    for (const GrownEdge& e : r.edges) {
      if (e.road_class == "avenue") total += std::hypot(e.b.x - e.a.x, e.b.y - e.a.y);
    }
    return total;
  };
  EXPECT_EQ(off.stats.arterial_reseeds, 0u);
  EXPECT_EQ(avenues_east(off), 0.0);
  ASSERT_GT(on.stats.arterial_reseeds, 0u);
  EXPECT_GT(avenues_east(on), 1000.0);
  EXPECT_GT(avenues(on), avenues(off) + 1000.0);
  // (the joins after growth may add arterial pieces: arterial T's continued across)
  EXPECT_LE(on.stats.arterial_refill_after, avenues(on) + 1e-6);
  EXPECT_GT(on.stats.arterial_refill_after, on.stats.arterial_refill_before + 1000.0);
  // (the last land left is narrower than the gap)
  EXPECT_GT(on.stats.arterial_refill_after, 0.8 * on.stats.arterial_refill_target);
  // The example's widest space between avenues: from its corner (600, 600) to the avenues at 400 m.
  EXPECT_NEAR(on.stats.arterial_refill_gap, 200.0, 10.0);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < on.edges.size(); ++i) {
    EXPECT_FALSE(std::abs(on.edges[i].a.x) < 100.0 || std::abs(on.edges[i].b.x) < 100.0 ||
                 on.edges[i].a.x * on.edges[i].b.x < 0.0);
    for (std::size_t j = i + 1; j < on.edges.size(); ++j) bad += crosses_without_node(on.edges[i], on.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
  expect_same_edges(grow_example(geos, in, p), on);
}

namespace {
// An avenue from a to b (axis-parallel) in 100 m pieces (the example is noded at shared vertices)
// with a local stub of 40 m at each piece's end, alternately on either side, but at its ends: the
// local level a street grid example has beside its arterials, and short local streets that keep
// the mean street short.
void add_avenue(std::vector<PatchInputEdge>& out, std::int64_t& id, Point a, Point b) {
  const Point dir = unit(b - a), side{-dir.y, dir.x};
  const int pieces = static_cast<int>(std::lround(distance(a, b) / 100.0));
  for (int k = 0; k < pieces; ++k) {
    const Point from = a + (k * 100.0) * dir, to = k + 1 == pieces ? b : a + ((k + 1) * 100.0) * dir;
    out.push_back({{from, to}, "avenue", ++id, false});
    if (k + 1 < pieces) out.push_back({{to, to + (k % 2 ? 40.0 : -40.0) * side}, "street", ++id, false});
  }
}

// A 3 x 3 grid of avenue crossings 600 m apart (avenues at 0, 600, 1200 in x and y, each running
// on 300 m past the outer crossings to a dead end), with the local stubs above: its arterial
// connectors (600 m) are longer than 3 mean streets of all levels (the patch streets' mean is about
// 130 m: 100 m avenue pieces and 40 m stubs beside the arterial level's 600 m and 300 m).
std::vector<PatchInputEdge> long_avenue_grid() {
  std::vector<PatchInputEdge> out;
  std::int64_t id = 0;
  for (int i = 0; i < 3; ++i) {
    const double c = i * 600.0;
    for (int j = 0; j < 4; ++j) {  // each avenue in four streets between crossings and ends
      const double from = j == 0 ? -300.0 : (j - 1) * 600.0, to = j == 3 ? 1500.0 : j * 600.0;
      for (auto [a, b] : {std::pair{Point{from, c}, Point{to, c}}, std::pair{Point{c, from}, Point{c, to}}}) {
        add_avenue(out, id, a, b);
      }
    }
  }
  return out;
}

// Two avenue junctions J1 (-300, 0) and J2 (300, 0) joined by a dual carriageway whose two
// roadways part at 13 degrees at each junction (34 m apart in between); each junction has three
// more avenue arms (dead ends 400 m long) with local stubs. Every arterial patch with two
// connectors has two streets 13 degrees apart at its junction, below the default min_angle (20).
std::vector<PatchInputEdge> dual_carriageway() {
  std::vector<PatchInputEdge> out;
  std::int64_t id = 0;
  const double rise = 150.0 * std::tan(6.5 * kPi / 180.0);
  for (double s : {1.0, -1.0}) {
    out.push_back({{{-300, 0}, {-150, s * rise}, {150, s * rise}, {300, 0}}, "avenue", ++id, false});
  }
  for (double x : {-300.0, 300.0}) {
    const double out_x = x < 0 ? -700.0 : 700.0;
    for (Point end : {Point{out_x, 0}, Point{x, 400}, Point{x, -400}}) {
      add_avenue(out, id, {x, 0}, end);
    }
  }
  return out;
}
}  // namespace

// arterial_whole_streets: a front's street is compared whole with the arterial connectors. Cut to
// 3 mean streets of all levels (here about 400 m against 600 m connectors) the example's own
// neighbouring patch is out of reach and the arterial phase stops at the seed patch (seeds 1-8).
TEST(GrowPatches, ArterialWholeStreetsReachLongConnectors) {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-1000 -1000, 2200 -1000, 2200 2200, -1000 2200, -1000 -1000))");
  GrowInput in;
  in.patches = extract_patches(geos, long_avenue_grid(), PatchParams{}).patches;
  in.region = region.get();
  in.seeds = {{600.0, 600.0}};
  GrowParams p;
  p.use_patches = true;
  p.seed = 4;
  p.patch.arterial_refill = 0.0;  // the arterial phase alone
  p.patch.refill = 0.0;
  GrowResult on = grow_example(geos, in, p);
  p.patch.arterial_whole_streets = false;
  GrowResult off = grow_example(geos, in, p);
  EXPECT_EQ(off.stats.arterial_patches_placed, 1u);  // the seed's
  EXPECT_GT(off.stats.arterial_front_reach, 0u);
  EXPECT_GE(on.stats.arterial_patches_placed, 9u);  // the grid copied on over the region (16-24, seeds 1-8)
  EXPECT_EQ(on.stats.arterial_front_reach, 0u);
  auto avenues = [](const GrowResult& r) {
    double total = 0.0;
    for (const GrownEdge& e : r.edges) {
      if (e.road_class == "avenue") total += distance(e.a, e.b);
    }
    return total;
  };
  EXPECT_GT(avenues(on), 2.0 * avenues(off));
  std::size_t bad = 0;
  for (std::size_t i = 0; i < on.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < on.edges.size(); ++j) bad += crosses_without_node(on.edges[i], on.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
}

// arterial_own_angles: two streets leaving one patch vertex keep the example's angle in the
// arterial phase; min_angle (20 degrees) refused the dual carriageway parting at 13 degrees, so no
// arterial patch was placed at all.
TEST(GrowPatches, ArterialOwnAnglesPlaceADualCarriageway) {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-1500 -1500, 1500 -1500, 1500 1500, -1500 1500, -1500 -1500))");
  GrowInput in;
  in.patches = extract_patches(geos, dual_carriageway(), PatchParams{}).patches;
  in.region = region.get();
  in.seeds = {{0.0, 0.0}};
  GrowParams p;
  p.use_patches = true;
  p.seed = 1;
  p.patch.arterial_refill = 0.0;
  p.patch.refill = 0.0;
  GrowResult on = grow_example(geos, in, p);
  p.patch.arterial_own_angles = false;
  GrowResult off = grow_example(geos, in, p);
  EXPECT_EQ(off.stats.arterial_patches_placed, 0u);
  EXPECT_GE(on.stats.arterial_patches_placed, 2u);  // both junctions, the carriageway between them
  // The two roadways leave one grown node 13 degrees apart.
  std::map<std::int64_t, std::vector<double>> out_angles;
  for (const GrownEdge& e : on.edges) {
    if (e.road_class != "avenue") continue;
    out_angles[e.from_node].push_back(std::atan2(e.b.y - e.a.y, e.b.x - e.a.x));
    out_angles[e.to_node].push_back(std::atan2(e.a.y - e.b.y, e.a.x - e.b.x));
  }
  bool narrow = false;
  for (const auto& [node, angles] : out_angles) {
    for (std::size_t a = 0; a < angles.size(); ++a) {
      for (std::size_t b = a + 1; b < angles.size(); ++b) {
        double d = std::abs(std::remainder(angles[a] - angles[b], 2.0 * kPi)) * 180.0 / kPi;
        narrow = narrow || (d > 12.0 && d < 14.0);
      }
    }
  }
  EXPECT_TRUE(narrow);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < on.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < on.edges.size(); ++j) bad += crosses_without_node(on.edges[i], on.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
}

// The roundabout tests' library: the fixture's roundabout patch alone (a ring of radius 20 m,
// spokes out to the next junctions), grown in the fixture's region without the fallback.
namespace {
GrowInput roundabout_only(PatchFixture& f) {
  GrowInput in;
  for (const Patch& patch : extract_patches(f.geos, grid_with_roundabout(true), PatchParams{}).patches) {
    if (has(patch.tags, "roundabout")) in.patches.push_back(patch);
  }
  in.region = f.region.get();
  return in;
}
GrowParams roundabout_only_params() {
  GrowParams p;
  p.use_patches = true;
  p.seed = 1;
  p.max_edges = 200;
  p.fallback = false;
  return p;
}
}  // namespace

// PatchGrowParams::roundabout_spokes_dropped: the library's only patch is the fixture's roundabout
// (a ring of radius 20 m, spokes out to the next junctions); the seed ends a street that comes
// into a square of existing streets, 50 m from the seed on three sides, open on the fourth. The
// spokes to the closed sides reach past them, so the whole patch is refused; without them the
// ring fits, joined to the seed's street and by its spoke through the open side. (With it, the
// growth goes on past the open side and elsewhere in the region, with later roundabouts whole.)
TEST(GrowPatches, FirstRoundaboutLeavesOutTheSpokesThatComeTooNear) {
  PatchFixture f;
  GrowInput in = roundabout_only(f);
  ASSERT_EQ(in.patches.size(), 1u);
  const double h = 50.0;
  in.existing = {{{-h, h}, {-h, -h}, {h, -h}, {h, h}}, {{0.0, -h}, {0.0, 0.0}}};
  in.seeds = {{0.0, 0.0}};
  GrowParams p = roundabout_only_params();
  p.patch.roundabout_shift = false;  // (with it, the patch refused at the seed is placed ahead of it instead)
  auto inside = [&](Point q) { return std::abs(q.x) < h && std::abs(q.y) < h; };
  for (bool drop : {false, true}) {
    p.patch.roundabout_spokes_dropped = drop;
    GrowResult r = grow_example(f.geos, in, p);
    if (!drop) {
      EXPECT_EQ(r.stats.patches_placed, 0u);
      EXPECT_EQ(r.stats.roundabout_spokes_dropped, 0u);
      continue;
    }
    ASSERT_GE(r.stats.patches_placed, 1u);
    EXPECT_GE(r.stats.roundabout_spokes_dropped, 2u);
    // Inside the square: the ring, closed, joined to the seed's street at the seed, no street
    // hanging from it; one street leaves it, through the open side.
    std::map<std::int64_t, int> degree;
    bool at_seed = false;
    double ring = 0.0;
    int leaving = 0;
    for (const GrownEdge& e : r.edges) {
      if (inside(e.a) != inside(e.b)) {
        ++leaving;
        EXPECT_GT(std::max(e.a.y, e.b.y), h) << e.a.x << " " << e.a.y << " " << e.b.x << " " << e.b.y;
        EXPECT_LT(std::max(std::abs(e.a.x), std::abs(e.b.x)), h);
        continue;
      }
      if (!inside(e.a)) continue;
      ++degree[e.from_node];
      ++degree[e.to_node];
      ring += distance(e.a, e.b);
      at_seed = at_seed || distance(e.a, Point{0.0, 0.0}) < 1e-6 || distance(e.b, Point{0.0, 0.0}) < 1e-6;
    }
    EXPECT_EQ(leaving, 1);
    EXPECT_TRUE(at_seed);
    EXPECT_NEAR(ring, 2.0 * kPi * 20.0, 2.0);
    int branching = 0;
    for (const auto& [node, d] : degree) {
      EXPECT_GE(d, 2) << node;
      branching += d > 2;
    }
    EXPECT_LE(branching, 1);  // where the spoke through the open side leaves the ring, if inside
    EXPECT_EQ(streetgen::test::crossings_without_node(r), 0);
  }
}

// PatchGrowParams::roundabout_shift: the same roundabout patch, grown from a street ending between
// two existing streets 23 m to either side, which run on 30 m past the seed. At the seed its ring
// (20 m across each way) would come 3 m from them, under the clearance (5 m): refused. Tried 40 m
// ahead, it fits: the front's street goes straight on to it, and the whole ring is there, clear of
// the two streets.
TEST(GrowPatches, FirstRoundaboutIsTriedAheadOfItsFront) {
  PatchFixture f;
  GrowInput in = roundabout_only(f);
  ASSERT_EQ(in.patches.size(), 1u);
  const double side = 23.0;
  in.existing = {{{-side, -50.0}, {-side, 30.0}}, {{side, -50.0}, {side, 30.0}}, {{0.0, -50.0}, {0.0, 0.0}}};
  in.seeds = {{0.0, 0.0}};
  GrowParams p = roundabout_only_params();
  p.patch.clearance = 5.0;
  for (bool shift : {false, true}) {
    p.patch.roundabout_shift = shift;
    GrowResult r = grow_example(f.geos, in, p);
    if (!shift) {
      EXPECT_EQ(r.stats.roundabouts_placed, 0u);
      EXPECT_EQ(r.stats.roundabout_ahead, 0.0);
      continue;
    }
    ASSERT_GE(r.stats.roundabouts_placed, 1u);
    EXPECT_EQ(r.stats.roundabout_ahead, 40.0);
    const Point centre{0.0, 60.0};  // the ring's centre, 40 m ahead of the seed and its radius on
    double ring = 0.0;
    bool joined = false;
    for (const GrownEdge& e : r.edges) {
      joined = joined || (distance(e.a, Point{0.0, 0.0}) < 1e-6 && distance(e.b, Point{0.0, 40.0}) < 1e-6) ||
               (distance(e.b, Point{0.0, 0.0}) < 1e-6 && distance(e.a, Point{0.0, 40.0}) < 1e-6);
      if (std::abs(distance(e.a, centre) - 20.0) < 0.5 && std::abs(distance(e.b, centre) - 20.0) < 0.5) {
        ring += distance(e.a, e.b);
      }
      // Nothing new within the clearance of the two streets beside the seed (they are not crossed,
      // so the nearest points are segment ends).
      for (double x : {-side, side}) {
        const Point s0{x, -50.0}, s1{x, 30.0};
        if (distance(e.a, s0) < 1e-6 && distance(e.b, s1) < 1e-6) continue;  // the street itself
        if (distance(e.a, s1) < 1e-6 && distance(e.b, s0) < 1e-6) continue;
        const double gap = std::min({point_segment_distance(s1, e.a, e.b), point_segment_distance(e.a, s0, s1),
                                     point_segment_distance(e.b, s0, s1)});
        EXPECT_GE(gap, 5.0) << e.a.x << " " << e.a.y << " " << e.b.x << " " << e.b.y;
      }
    }
    EXPECT_TRUE(joined);
    EXPECT_NEAR(ring, 2.0 * kPi * 20.0, 2.0);
    EXPECT_EQ(streetgen::test::crossings_without_node(r), 0);
  }
}

// PatchGrowParams::roundabout_ring_kept: the same roundabout patch, grown from a street ending at
// the seed, beside a street already there that ends 10 m east of where the ring's east vertex
// falls (20 m east of the ring's centre, 20 m ahead of the seed), within snap (15 m). Merged into
// that node, the vertex bends two arcs of the ring out to it, and the patch is refused (no other
// front: nothing is placed; with that street far away it is placed either way). Kept, the ring is
// placed whole and round, clear of that street, and
// its east spoke, which would touch the street's end, is left out.
TEST(GrowPatches, FirstRoundaboutKeepsItsRingWhole) {
  PatchFixture f;
  GrowInput in = roundabout_only(f);
  ASSERT_EQ(in.patches.size(), 1u);
  const Point east_end{30.0, 20.0}, east_far{30.0, 100.0};
  in.existing = {{{0.0, -50.0}, {0.0, 0.0}}, {east_end, east_far}};
  in.seeds = {{0.0, 0.0}};
  GrowParams p = roundabout_only_params();
  p.patch.clearance = 5.0;
  p.snap = 15.0;
  const Point centre{0.0, 20.0};
  for (bool kept : {false, true}) {
    p.patch.roundabout_ring_kept = kept;
    GrowResult r = grow_example(f.geos, in, p);
    if (!kept) {
      EXPECT_EQ(r.stats.roundabouts_placed, 0u);
      continue;
    }
    ASSERT_GE(r.stats.roundabouts_placed, 1u);
    double ring = 0.0;
    for (const GrownEdge& e : r.edges) {
      if (std::abs(distance(e.a, centre) - 20.0) < 0.5 && std::abs(distance(e.b, centre) - 20.0) < 0.5) {
        ring += distance(e.a, e.b);
      }
      if (distance(e.a, east_end) < 1e-6 && distance(e.b, east_far) < 1e-6) continue;  // the street itself
      if (distance(e.b, east_end) < 1e-6 && distance(e.a, east_far) < 1e-6) continue;
      const double gap = std::min({point_segment_distance(east_end, e.a, e.b), point_segment_distance(e.a, east_end, east_far),
                                   point_segment_distance(e.b, east_end, east_far)});
      EXPECT_GE(gap, 5.0) << e.a.x << " " << e.a.y << " " << e.b.x << " " << e.b.y;
    }
    EXPECT_NEAR(ring, 2.0 * kPi * 20.0, 2.0);
    EXPECT_EQ(streetgen::test::crossings_without_node(r), 0);
  }
}
