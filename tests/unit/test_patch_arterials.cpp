// The arterial phase's statistical fallback (PatchGrowParams::arterial_fallback) and the local seeds
// cut along the arterial streets it makes (PatchGrowParams::fallback_local_seeds): Nishida et al.
// 2016, sections 4.3.3 and 4.4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/error.hpp"
#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"
#include "patch_fixtures.hpp"
#include "test_support.hpp"

using namespace streetgen::core;
using streetgen::test::avenue_grid;
using streetgen::test::crosses_without_node;
using streetgen::test::wkt;

namespace {

// An arterial library too small for the region: the avenue grid's four avenue crossings (600 m
// square example, avenues 300 m apart), each usable once, in a 3 km square, no arterial refill.
struct SmallArterialLibrary {
  GeosContext geos;
  GeomPtr region = wkt(geos, "POLYGON((-1500 -1500, 1500 -1500, 1500 1500, -1500 1500, -1500 -1500))");
  GrowInput in;
  GrowParams p;
  SmallArterialLibrary() {
    PatchExtraction x = extract_patches(geos, avenue_grid(), PatchParams{});
    for (std::size_t i = 0; i < x.arterial_patches; ++i) x.patches[i].max_uses = 1;
    in.patches = x.patches;
    in.region = region.get();
    in.seeds = {{0.0, 0.0}};
    p.use_patches = true;
    p.seed = 3;
    p.max_edges = 20000;
    p.patch.arterial_refill = 0.0;
  }
};

// The same library with the arterial refill (its default 0.5), seed 2: about 110 avenue ends where
// only local streets go on, for the passes after the growth (promote_arterials) to work on.
struct RefilledArterialLibrary : SmallArterialLibrary {
  RefilledArterialLibrary() {
    p.seed = 2;
    p.patch.arterial_refill = 0.5;
  }
};

// The avenue (main street) graph of a result: per node, its avenue edges; and the largest distance
// of an avenue node from the seed.
struct Avenues {
  std::map<std::int64_t, int> degree;
  std::map<std::int64_t, Point> at;
  double reach = 0.0;
  double length = 0.0;
  explicit Avenues(const GrowResult& r) {
    for (const GrownEdge& e : r.edges) {
      if (e.road_class != "avenue") continue;
      ++degree[e.from_node];
      ++degree[e.to_node];
      at[e.from_node] = e.a;
      at[e.to_node] = e.b;
      reach = std::max({reach, std::hypot(e.a.x, e.a.y), std::hypot(e.b.x, e.b.y)});
      length += distance(e.a, e.b);
    }
  }
  // Avenue dead ends farther than 200 m inside the region's edge: where an avenue stops in the open.
  int interior_dead_ends() const {
    int n = 0;
    for (const auto& [node, d] : degree) {
      const Point q = at.at(node);
      n += d == 1 && std::abs(q.x) < 1300 && std::abs(q.y) < 1300;
    }
    return n;
  }
};

// Nodes where exactly one avenue ends and other streets go on, inside the 3 km square's 50 m margin.
int avenue_ends(const GrowResult& r) {
  std::map<std::int64_t, std::pair<int, int>> degree;  // avenues, all
  std::map<std::int64_t, Point> at;
  for (const GrownEdge& e : r.edges) {
    at[e.from_node] = e.a;
    at[e.to_node] = e.b;
    for (std::int64_t n : {e.from_node, e.to_node}) {
      degree[n].first += e.road_class == "avenue";
      ++degree[n].second;
    }
  }
  int n = 0;
  for (const auto& [node, d] : degree) {
    n += d.first == 1 && d.second > 1 && std::max(std::abs(at[node].x), std::abs(at[node].y)) <= 1450.0;
  }
  return n;
}

}  // namespace

// Without the fallback the arterial phase stops where the library's four patches end: their open
// avenue connectors are dead ends in the middle of the region and no avenue gets near its edge.
// With it, the avenues go on with the arterial level's statistics up to the example's main-street
// length per area, across the region, and the open ends the patches left are continued.
TEST(GrowPatchesArterialFallback, ArterialsReachAcrossTheRegion) {
  SmallArterialLibrary f;
  GrowResult off = grow_example(f.geos, f.in, f.p);
  f.p.patch.arterial_fallback = 1.0;
  GrowResult on = grow_example(f.geos, f.in, f.p);
  const Avenues a_off(off), a_on(on);
  EXPECT_EQ(off.stats.arterial_fallback, 0u);
  EXPECT_GT(on.stats.arterial_fallback, 10u);
  // Without it the avenues stop within the library's four crossings, their open ends dead ends in
  // the middle of the region; with it they reach the region's edge and none is left in the open.
  EXPECT_LT(a_off.reach, 800.0);
  EXPECT_GE(a_off.interior_dead_ends(), 5);
  EXPECT_GT(a_on.reach, 1400.0);
  EXPECT_EQ(a_on.interior_dead_ends(), 0);
  EXPECT_GT(a_on.length, 3.0 * a_off.length);
  EXPECT_LE(a_on.length, on.stats.arterial_fallback_budget);
  EXPECT_EQ(on.stats.arterial_patches_placed, off.stats.arterial_patches_placed);  // each patch once
  std::size_t bad = 0;
  for (std::size_t i = 0; i < on.edges.size(); ++i) {
    for (std::size_t j = i + 1; j < on.edges.size(); ++j) bad += crosses_without_node(on.edges[i], on.edges[j]);
  }
  EXPECT_EQ(bad, 0u);
  GrowResult again = grow_example(f.geos, f.in, f.p);
  ASSERT_EQ(again.edges.size(), on.edges.size());
  for (std::size_t i = 0; i < on.edges.size(); ++i) {
    EXPECT_EQ(again.edges[i].from_node, on.edges[i].from_node);
    EXPECT_DOUBLE_EQ(again.edges[i].b.x, on.edges[i].b.x);
  }
  // Off by default: the default growth is the one without it.
  SmallArterialLibrary d;
  GrowResult def = grow_example(d.geos, d.in, d.p);
  EXPECT_EQ(def.edges.size(), off.edges.size());
  EXPECT_EQ(def.stats.arterial_fallback, 0u);
}

// The fallback's arterial streets are cut into fragments of the local level's mean street length
// (the avenue grid's streets: 100 m) and the local phase starts at every cut.
TEST(GrowPatchesArterialFallback, LocalSeedsAlongFallbackArterials) {
  SmallArterialLibrary f;
  f.p.patch.arterial_fallback = 1.0;
  // (the doubled streets kept: left out, the two local phases leave out different streets, and the
  // joins after growth then continue different arterial T's, so the fallback avenues' length differs)
  f.p.patch.wide_redundant = false;
  f.p.patch.align_lines = false;  // (and the ends on lines off: with them too, 9863 m against 9889 m)
  // (and the nodes not settled after growth: the local streets differ, so the avenues' junctions
  // settle differently, by millimetres)
  f.p.patch.settle_onto_grid = false;
  GrowResult off = grow_example(f.geos, f.in, f.p);
  f.p.patch.fallback_local_seeds = true;
  GrowResult on = grow_example(f.geos, f.in, f.p);
  struct Along {
    double longest = 0.0, length = 0.0;
    int junctions = 0;  // nodes between two fallback avenue edges with a local street
  };
  auto along = [](const GrowResult& r) {
    Along a;
    std::map<std::int64_t, int> fallback_avenue, street;
    for (const GrownEdge& e : r.edges) {
      if (e.road_class == "avenue" && e.example < 0) {
        a.longest = std::max(a.longest, distance(e.a, e.b));
        a.length += distance(e.a, e.b);
        ++fallback_avenue[e.from_node];
        ++fallback_avenue[e.to_node];
      } else if (e.road_class == "street") {
        ++street[e.from_node];
        ++street[e.to_node];
      }
    }
    for (const auto& [node, d] : fallback_avenue) a.junctions += d == 2 && street.count(node) != 0;
    return a;
  };
  const Along a_off = along(off), a_on = along(on);
  EXPECT_EQ(off.stats.fallback_local_seeds, 0u);
  EXPECT_GT(on.stats.fallback_local_seeds, 10u);
  EXPECT_DOUBLE_EQ(a_on.length, a_off.length);  // the same arterial phase
  // Every fallback avenue is cut to about the local street length (a street of less than 1.5 of
  // them stays whole; the joins after growth may continue an arterial T by up to a mean street).
  EXPECT_GT(a_off.longest, 200.0);
  EXPECT_LE(a_on.longest, 160.0);
  // Local streets leave the fallback avenues about every local street length.
  EXPECT_GT(a_on.junctions, a_off.junctions + 10);
  const double spacing = a_on.length / a_on.junctions;
  EXPECT_GT(spacing, 80.0);
  EXPECT_LT(spacing, 130.0);
}

// Arterials run on (PatchGrowParams::promote_arterials): with the arterial refill, the library's
// avenue patches (each once) and the refill's leave about 110 avenue ends where only local streets
// go on; those with local streets leading on straight (or by a jog) to another avenue within the
// example's widest space between avenues take the avenue class. Nothing else changes.
TEST(GrowPatchesArterialsRunOn, LocalStreetsContinueAnAvenueToTheNext) {
  RefilledArterialLibrary f;
  f.p.patch.promote_arterials = false;
  const GrowResult off = grow_example(f.geos, f.in, f.p);
  f.p.patch.promote_arterials = true;
  f.p.patch.demote_arterial_stubs = false;  // its own test below
  const GrowResult on = grow_example(f.geos, f.in, f.p);
  streetgen::test::expect_same_edges(on, off);
  EXPECT_EQ(off.stats.arterials_promoted, 0u);
  EXPECT_GT(on.stats.arterial_ends, 50u);
  EXPECT_GT(on.stats.arterials_promoted, 10u);
  // A class changes only from street to avenue, and the changed edges are the promoted length.
  std::map<std::int64_t, std::vector<std::size_t>> promoted_at;  // node -> promoted edges there
  double promoted = 0.0;
  for (std::size_t i = 0; i < on.edges.size() && i < off.edges.size(); ++i) {
    if (on.edges[i].road_class == off.edges[i].road_class) continue;
    EXPECT_EQ(off.edges[i].road_class, "street");
    EXPECT_EQ(on.edges[i].road_class, "avenue");
    promoted += distance(on.edges[i].a, on.edges[i].b);
    promoted_at[on.edges[i].from_node].push_back(i);
    promoted_at[on.edges[i].to_node].push_back(i);
  }
  EXPECT_NEAR(promoted, on.stats.promoted_length, 1e-6 * promoted);
  // Each run of promoted edges (split at off's avenue nodes) ends, at both ends, on an avenue the
  // growth made (off's avenues) or within the 50 m margin; along it no turn over 100 degrees; and
  // from an end where an avenue ended into streets (the route's start) it goes on straight or by a
  // jog: at most two turns over 30 degrees counting the one off the avenue, at most a local mean
  // street (the avenue grid's streets: 100 m) from the first to the second, then within 30 degrees
  // of the way the avenue ran.
  std::map<std::int64_t, int> avenues_off, degree_off;
  std::map<std::int64_t, Point> at, avenue_from;  // avenue_from: the far end of a node's one avenue
  for (const GrownEdge& e : off.edges) {
    at[e.from_node] = e.a;
    at[e.to_node] = e.b;
    ++degree_off[e.from_node];
    ++degree_off[e.to_node];
    if (e.road_class != "avenue") continue;
    ++avenues_off[e.from_node];
    ++avenues_off[e.to_node];
    avenue_from[e.from_node] = e.b;
    avenue_from[e.to_node] = e.a;
  }
  auto in_margin = [&](std::int64_t n) { return std::max(std::abs(at[n].x), std::abs(at[n].y)) > 1450.0; };
  auto run_end = [&](std::int64_t n) { return promoted_at[n].size() != 2 || avenues_off.count(n) != 0 || in_margin(n); };
  // Whether the run (its nodes in order) leaves the avenue ending at its first node straight on or by a jog.
  auto straight_or_jog = [&](const std::vector<std::int64_t>& nodes) {
    if (avenues_off[nodes[0]] != 1 || degree_off[nodes[0]] < 2) return false;
    const Point ahead = unit(at[nodes[0]] - avenue_from[nodes[0]]);
    Point heading = ahead;
    int sharp = 0;
    double sideways = 0.0;
    for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
      const Point d = unit(at[nodes[k + 1]] - at[nodes[k]]);
      if (dot(heading, d) < std::cos(30.0 * M_PI / 180.0) && ++sharp == 2 && dot(d, ahead) < std::cos(30.0 * M_PI / 180.0)) {
        return false;
      }
      if (sharp == 1) sideways += distance(at[nodes[k]], at[nodes[k + 1]]);
      heading = d;
    }
    return sharp <= 2 && sideways <= 110.0;
  };
  std::set<std::size_t> seen;
  int runs = 0;
  for (const auto& [start, edges] : promoted_at) {
    if (!run_end(start)) continue;
    for (std::size_t first : edges) {
      if (seen.count(first) != 0) continue;
      ++runs;
      std::vector<std::int64_t> nodes{start};
      std::size_t edge = first;
      while (true) {
        seen.insert(edge);
        const GrownEdge& e = on.edges[edge];
        const std::int64_t next = e.from_node == nodes.back() ? e.to_node : e.from_node;
        EXPECT_GE(dot(unit(at[next] - at[nodes.back()]), nodes.size() < 2 ? unit(at[next] - at[nodes.back()])
                                                                          : unit(at[nodes.back()] - at[nodes[nodes.size() - 2]])),
                  std::cos(100.0 * M_PI / 180.0));
        nodes.push_back(next);
        if (run_end(next)) break;
        const std::vector<std::size_t>& there = promoted_at[next];
        edge = there[0] == edge ? there[1] : there[0];
      }
      for (std::int64_t n : {nodes.front(), nodes.back()}) {
        EXPECT_TRUE(avenues_off.count(n) != 0 || in_margin(n)) << "run end " << n;
      }
      const std::vector<std::int64_t> back(nodes.rbegin(), nodes.rend());
      EXPECT_TRUE(straight_or_jog(nodes) || straight_or_jog(back)) << "run from node " << nodes.front();
    }
  }
  std::size_t changed = 0;
  for (const auto& [node, edges] : promoted_at) changed += edges.size();
  EXPECT_EQ(seen.size() * 2, changed);  // every promoted edge on a run
  EXPECT_GT(runs, 10);
  // Avenue ends where only streets go on, inside the margin: fewer.
  EXPECT_LT(avenue_ends(on), avenue_ends(off) - 10);
  // Deterministic.
  const GrowResult again = grow_example(f.geos, f.in, f.p);
  ASSERT_EQ(again.edges.size(), on.edges.size());
  for (std::size_t i = 0; i < on.edges.size(); ++i) EXPECT_EQ(again.edges[i].road_class, on.edges[i].road_class);
}

// Stubs past a main junction (PatchGrowParams::demote_arterial_stubs): of the avenue ends that no
// route continued, those whose avenue reaches back to an avenue junction (three or more avenues)
// within a local mean street (the avenue grid's streets: 100 m, their mean under 110 m) are the
// patches' stubs past that junction; they take the street class. Each such stub is one avenue end
// fewer, and none is made.
TEST(GrowPatchesArterialsRunOn, StubsPastAnAvenueJunctionBecomeStreets) {
  RefilledArterialLibrary f;
  f.p.patch.demote_arterial_stubs = false;
  const GrowResult off = grow_example(f.geos, f.in, f.p);
  f.p.patch.demote_arterial_stubs = true;
  const GrowResult on = grow_example(f.geos, f.in, f.p);
  streetgen::test::expect_same_edges(on, off);
  EXPECT_EQ(off.stats.arterial_stubs_demoted, 0u);
  ASSERT_GT(on.stats.arterial_stubs_demoted, 3u);
  std::map<std::int64_t, int> avenues_off, avenues_on, degree;
  std::map<std::int64_t, std::vector<std::size_t>> demoted_at;  // node -> demoted edges there
  double demoted = 0.0;
  for (std::size_t i = 0; i < on.edges.size() && i < off.edges.size(); ++i) {
    const GrownEdge& e = on.edges[i];
    for (std::int64_t n : {e.from_node, e.to_node}) {
      ++degree[n];
      avenues_off[n] += off.edges[i].road_class == "avenue";
      avenues_on[n] += e.road_class == "avenue";
    }
    if (e.road_class == off.edges[i].road_class) continue;
    EXPECT_EQ(off.edges[i].road_class, "avenue");
    EXPECT_EQ(e.road_class, "street");
    demoted += distance(e.a, e.b);
    demoted_at[e.from_node].push_back(i);
    demoted_at[e.to_node].push_back(i);
  }
  EXPECT_NEAR(demoted, on.stats.demoted_length, 1e-6 * demoted);
  // Each stub, walked from its avenue end: through nodes of two avenues, shorter than 110 m, to a
  // node of three or more avenues that keeps two or more.
  std::size_t stubs = 0, walked = 0;
  for (const auto& [start, edges] : demoted_at) {
    if (avenues_off[start] != 1) continue;
    ++stubs;
    EXPECT_GT(degree[start], 1) << "stub end " << start;
    EXPECT_EQ(avenues_on[start], 0) << "stub end " << start;
    std::int64_t node = start;
    std::size_t edge = edges[0];
    double length = 0.0;
    for (;;) {
      ++walked;
      const GrownEdge& e = on.edges[edge];
      length += distance(e.a, e.b);
      node = e.from_node == node ? e.to_node : e.from_node;
      if (avenues_off[node] != 2) break;
      const std::vector<std::size_t>& there = demoted_at[node];
      ASSERT_EQ(there.size(), 2u) << "stub through node " << node;
      edge = there[0] == edge ? there[1] : there[0];
    }
    EXPECT_LT(length, 110.0) << "stub from node " << start;
    EXPECT_GE(avenues_off[node], 3) << "stub from node " << start;
    EXPECT_GE(avenues_on[node], 2) << "stub from node " << start;
  }
  EXPECT_EQ(stubs, on.stats.arterial_stubs_demoted);
  std::size_t changed = 0;
  for (const auto& [node, edges] : demoted_at) changed += edges.size();
  EXPECT_EQ(walked * 2, changed);  // every demoted edge on a stub
  EXPECT_EQ(avenue_ends(off) - avenue_ends(on), static_cast<int>(stubs));
}
