#include "core/growth/patches.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // Boost R-tree internals, as in grow_example.cpp
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include "core/error.hpp"
#include "core/interrupts.hpp"
#include "core/union_find.hpp"

namespace streetgen::core {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using PointValue = std::pair<BPoint, std::uint32_t>;

constexpr double kPi = 3.14159265358979323846;

using Key = std::pair<std::int64_t, std::int64_t>;
struct KeyHash {
  std::size_t operator()(const Key& k) const noexcept {
    return static_cast<std::size_t>(static_cast<std::uint64_t>(k.first) * 0x9E3779B97F4A7C15ULL ^
                                    static_cast<std::uint64_t>(k.second));
  }
};
Key key_of(Point p) { return {std::llround(p.x * 1000.0), std::llround(p.y * 1000.0)}; }

struct Street {
  std::uint32_t a, b;  // street-graph nodes
  Polyline line;       // from a to b
  std::string road_class;
  std::int64_t id;
  bool roundabout;
  double length;
};

// The example as a street graph: nodes of degree != 2 (and one node per isolated ring), streets
// between them.
struct StreetGraph {
  std::vector<Point> nodes;
  std::vector<Street> streets;
  std::vector<std::vector<std::uint32_t>> incident;  // streets at each node (a self-loop twice)
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
};

StreetGraph build_street_graph(const std::vector<PatchInputEdge>& example) {
  // Segment level: vertices closer than a millimetre are one, a segment mapped twice is one.
  struct Seg {
    std::uint32_t a, b;
    std::size_t edge;
  };
  std::vector<Point> pts;
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
  std::vector<Seg> segs;
  std::unordered_set<std::uint64_t> seen;
  InterruptPoller poller(1024);
  for (std::size_t i = 0; i < example.size(); ++i) {
    poller.tick();
    const Polyline& line = example[i].line;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      auto node = [&](Point p) {
        auto [it, added] = index.emplace(key_of(p), static_cast<std::uint32_t>(pts.size()));
        if (added) pts.push_back(p);
        return it->second;
      };
      std::uint32_t a = node(line[k]), b = node(line[k + 1]);
      if (a == b) continue;
      std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      if (!seen.insert(key).second) continue;
      segs.push_back({a, b, i});
    }
  }
  std::vector<std::vector<std::uint32_t>> at(pts.size());
  for (std::uint32_t s = 0; s < segs.size(); ++s) {
    at[segs[s].a].push_back(s);
    at[segs[s].b].push_back(s);
  }
  StreetGraph g;
  std::vector<std::uint32_t> street_node(pts.size(), UINT32_MAX);
  auto make_node = [&](std::uint32_t p) {
    if (street_node[p] == UINT32_MAX) {
      street_node[p] = static_cast<std::uint32_t>(g.nodes.size());
      g.index.emplace(key_of(pts[p]), street_node[p]);
      g.nodes.push_back(pts[p]);
    }
    return street_node[p];
  };
  std::vector<char> used(segs.size(), 0);
  auto walk = [&](std::uint32_t start, std::uint32_t first) {
    Street st{make_node(start), 0, {pts[start]}, example[segs[first].edge].road_class, example[segs[first].edge].id,
              false, 0.0};
    std::uint32_t cur = start, s = first;
    for (;;) {
      used[s] = 1;
      st.roundabout = st.roundabout || example[segs[s].edge].roundabout;
      std::uint32_t next = segs[s].a == cur ? segs[s].b : segs[s].a;
      st.line.push_back(pts[next]);
      st.length += distance(pts[cur], pts[next]);
      cur = next;
      if (at[cur].size() != 2 || street_node[cur] != UINT32_MAX) break;
      std::uint32_t t = at[cur][0] == s ? at[cur][1] : at[cur][0];
      if (used[t]) break;
      s = t;
    }
    st.b = make_node(cur);
    g.streets.push_back(std::move(st));
  };
  for (std::uint32_t p = 0; p < pts.size(); ++p) {
    if (at[p].size() == 2 || at[p].empty()) continue;
    make_node(p);
  }
  for (std::uint32_t p = 0; p < pts.size(); ++p) {
    poller.tick();
    if (street_node[p] == UINT32_MAX) continue;
    for (std::uint32_t s : at[p]) {
      if (!used[s]) walk(p, s);
    }
  }
  // Rings of degree-2 vertices only (an isolated loop): one node on each.
  for (std::uint32_t p = 0; p < pts.size(); ++p) {
    if (at[p].size() != 2 || used[at[p][0]]) continue;
    make_node(p);
    walk(p, at[p][0]);
  }
  g.incident.assign(g.nodes.size(), {});
  for (std::uint32_t s = 0; s < g.streets.size(); ++s) {
    g.incident[g.streets[s].a].push_back(s);
    g.incident[g.streets[s].b].push_back(s);
  }
  return g;
}

// The turning of the unit directions along the line (radians in total).
double turning(const Polyline& line) {
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    Point u = unit(line[i] - line[i - 1]), v = unit(line[i + 1] - line[i]);
    sum += std::abs(std::atan2(cross(u, v), dot(u, v)));
  }
  return sum;
}
constexpr double kCurvedTurning = 20.0 * kPi / 180.0;  // a street that turns more than this in all is curved

void add_tag(std::vector<std::string>& tags, const char* tag) {
  if (std::find(tags.begin(), tags.end(), tag) == tags.end()) tags.emplace_back(tag);
}

}  // namespace

const char* role_name(PatchEdgeRole role) {
  switch (role) {
    case PatchEdgeRole::inner: return "inner";
    case PatchEdgeRole::connector: return "connector";
    case PatchEdgeRole::dead_end: return "dead_end";
    case PatchEdgeRole::isolated: return "isolated";
  }
  return "inner";
}

bool is_main_class(const std::string& c) {
  static const char* const kMain[] = {"avenue", "highway", "boulevard", "motorway", "motorway_link", "trunk",
                                      "trunk_link", "primary", "primary_link", "secondary", "secondary_link",
                                      "tertiary", "tertiary_link", "main", "arterial"};
  for (const char* m : kMain) {
    if (c == m) return true;
  }
  return false;
}

double curvature(const Polyline& line) {
  double len = length(line);
  if (!(len > 0.0)) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < line.size(); ++i) sum += norm(unit(line[i + 1] - line[i]) - unit(line[i] - line[i - 1]));
  return sum / len;
}

double arc_curvature(const Polyline& line) {
  const double len = length(line);
  if (!(len > 0.0) || line.size() < 3) return 0.0;
  // An arc turning by T has chord / length = sin(T/2) / (T/2), decreasing on [0, 2 pi]: bisection.
  const double ratio = std::clamp(distance(line.front(), line.back()) / len, 0.0, 1.0);
  double lo = 0.0, hi = kPi;  // half the turn
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::sin(mid) / mid > ratio ? lo : hi) = mid;
  }
  return 2.0 * lo / len;
}

StreetStatistics street_statistics(const std::vector<const Polyline*>& streets) {
  StreetStatistics s;
  if (streets.empty()) return s;
  double n = static_cast<double>(streets.size());
  for (const Polyline* l : streets) {
    s.length_mean += length(*l);
    s.curvature_mean += curvature(*l);
  }
  s.length_mean /= n;
  s.curvature_mean /= n;
  for (const Polyline* l : streets) {
    double dl = length(*l) - s.length_mean, dk = curvature(*l) - s.curvature_mean;
    s.length_sd += dl * dl;
    s.curvature_sd += dk * dk;
  }
  s.length_sd = std::sqrt(s.length_sd / n);
  s.curvature_sd = std::sqrt(s.curvature_sd / n);
  return s;
}

namespace {

// One level's patches from its street graph (see extract_patches).
enum class Level { all, arterial, local };
template <typename Cropped>
std::vector<Patch> extract_level(GeosContext& geos, const StreetGraph& g, const PatchParams& params, double short_edge,
                                 double cluster_distance, Level level, Cropped cropped) {
  const std::size_t n = g.nodes.size();
  auto degree = [&](std::uint32_t v) { return g.incident[v].size(); };

  // A junction of this level: any junction, or (local level) one where a local street meets.
  auto eligible = [&](std::uint32_t v) {
    if (degree(v) < 3) return false;
    if (level != Level::local) return true;
    for (std::uint32_t s : g.incident[v]) {
      if (!is_main_class(g.streets[s].road_class)) return true;
    }
    return false;
  };
  // A dead end the crop of the example made (near its hull's edge): the street went on.
  std::vector<char> cut(n, 0);
  for (std::uint32_t v = 0; v < n; ++v) cut[v] = degree(v) == 1 && cropped(g.nodes[v]);

  // ---- detection: structures are sets of nodes, expanded first -------------------------------
  struct Structure {
    std::vector<std::uint32_t> nodes;
    bool roundabout;
  };
  std::vector<Structure> structures;
  std::vector<char> in_structure(n, 0);
  std::vector<char> ring_street(g.streets.size(), 0);
  {  // roundabouts the example flags: connected flagged streets
    UnionFind uf(n);
    std::vector<char> flagged(n, 0);
    for (std::uint32_t s = 0; s < g.streets.size(); ++s) {
      if (!g.streets[s].roundabout) continue;
      uf.unite(g.streets[s].a, g.streets[s].b);
      flagged[g.streets[s].a] = flagged[g.streets[s].b] = 1;
      ring_street[s] = 1;
    }
    std::vector<char> group_of_level(n, 0);
    for (std::uint32_t v = 0; v < n; ++v) {
      if (flagged[v] && eligible(v)) group_of_level[uf.find(v)] = 1;
    }
    std::unordered_map<std::size_t, std::size_t> which;
    for (std::uint32_t v = 0; v < n; ++v) {
      if (!flagged[v] || !group_of_level[uf.find(v)]) continue;
      auto [it, added] = which.emplace(uf.find(v), structures.size());
      if (added) structures.push_back({{}, true});
      structures[it->second].nodes.push_back(v);
      in_structure[v] = 1;
    }
  }
  if (params.detect_circles) {  // small compact faces: roundabouts and plazas without the flag
    GEOSContextHandle_t h = geos.handle();
    std::vector<GeomPtr> lines;
    lines.reserve(g.streets.size());
    for (const Street& s : g.streets) {
      GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, static_cast<unsigned>(s.line.size()), 2);
      if (seq == nullptr) geos.fail("coordinate sequence");
      for (std::size_t i = 0; i < s.line.size(); ++i) GEOSCoordSeq_setXY_r(h, seq, static_cast<unsigned>(i), s.line[i].x, s.line[i].y);
      lines.push_back(own(geos, GEOSGeom_createLineString_r(h, seq), "street line"));
    }
    std::vector<const GEOSGeometry*> raw(lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) raw[i] = lines[i].get();
    poll_interrupts();
    GeomPtr faces = own(geos, GEOSPolygonize_r(h, raw.data(), static_cast<unsigned>(raw.size())), "polygonize");
    const double rmin = 0.5 * params.circle_min_diameter, rmax = 0.5 * params.circle_max_diameter;
    int count = GEOSGetNumGeometries_r(h, faces.get());
    InterruptPoller poller(256);
    for (int i = 0; i < count; ++i) {
      poller.tick();
      const GEOSGeometry* face = GEOSGetGeometryN_r(h, faces.get(), i);
      double area = 0.0, perimeter = 0.0;
      if (GEOSArea_r(h, face, &area) == 0) geos.fail("area");
      if (area < kPi * rmin * rmin || area > kPi * rmax * rmax) continue;
      const GEOSGeometry* shell = GEOSGetExteriorRing_r(h, face);
      if (shell == nullptr || GEOSGeomGetLength_r(h, shell, &perimeter) == 0) geos.fail("perimeter");
      if (!(perimeter > 0.0) || 4.0 * kPi * area / (perimeter * perimeter) < params.circle_compactness) continue;
      const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(h, shell);
      unsigned size = 0;
      GEOSCoordSeq_getSize_r(h, seq, &size);
      Structure st{{}, true};
      bool taken = false;
      for (unsigned k = 0; k < size; ++k) {
        double x = 0, y = 0;
        GEOSCoordSeq_getXY_r(h, seq, k, &x, &y);
        auto it = g.index.find(key_of({x, y}));
        if (it == g.index.end()) continue;
        if (in_structure[it->second]) taken = true;
        if (std::find(st.nodes.begin(), st.nodes.end(), it->second) == st.nodes.end()) st.nodes.push_back(it->second);
      }
      std::size_t approaches = 0, of_level = 0;
      for (std::uint32_t v : st.nodes) {
        approaches += degree(v) >= 3;
        of_level += eligible(v);
      }
      if (taken || approaches < 2 || of_level == 0) continue;  // flagged already, a closed street with one way in, another level
      std::sort(st.nodes.begin(), st.nodes.end());
      for (std::uint32_t v : st.nodes) in_structure[v] = 1;
      // The ring's streets: both ends on the ring and the street on the face's boundary.
      for (std::uint32_t v : st.nodes) {
        for (std::uint32_t s : g.incident[v]) {
          const Street& sr = g.streets[s];
          if (std::find(st.nodes.begin(), st.nodes.end(), sr.a == v ? sr.b : sr.a) == st.nodes.end()) continue;
          Point mid = point_at(sr.line, 0.5 * sr.length);
          GeomPtr pt = own(geos, GEOSGeom_createPointFromXY_r(h, mid.x, mid.y), "midpoint");
          double d = 1.0;
          if (GEOSDistance_r(h, shell, pt.get(), &d) == 0) geos.fail("distance");
          if (d < 1e-3) ring_street[s] = 1;
        }
      }
      structures.push_back(std::move(st));
    }
  }
  {  // tightly clustered junctions (interchanges, ramps): >= 3 within cluster_distance of each other
    std::vector<PointValue> values;
    for (std::uint32_t v = 0; v < n; ++v) {
      if (eligible(v) && !in_structure[v]) values.emplace_back(BPoint(g.nodes[v].x, g.nodes[v].y), v);
    }
    bgi::rtree<PointValue, bgi::rstar<16>> tree(values.begin(), values.end());
    UnionFind uf(n);
    std::vector<PointValue> hits;
    for (const PointValue& pv : values) {
      hits.clear();
      Point p = g.nodes[pv.second];
      bg::model::box<BPoint> box(BPoint(p.x - cluster_distance, p.y - cluster_distance),
                                 BPoint(p.x + cluster_distance, p.y + cluster_distance));
      tree.query(bgi::intersects(box), std::back_inserter(hits));
      for (const PointValue& q : hits) {
        if (q.second != pv.second && distance(g.nodes[q.second], p) <= cluster_distance) uf.unite(pv.second, q.second);
      }
    }
    std::unordered_map<std::size_t, std::vector<std::uint32_t>> groups;
    std::vector<std::size_t> order;
    for (const PointValue& pv : values) {
      std::size_t r = uf.find(pv.second);
      auto [it, added] = groups.emplace(r, std::vector<std::uint32_t>{});
      if (added) order.push_back(r);
      it->second.push_back(pv.second);
    }
    for (std::size_t r : order) {
      std::vector<std::uint32_t>& nodes = groups[r];
      if (nodes.size() < 3) continue;
      std::sort(nodes.begin(), nodes.end());
      for (std::uint32_t v : nodes) in_structure[v] = 1;
      structures.push_back({std::move(nodes), false});
    }
  }

  // ---- expansion by short edges (Nishida's Algorithm 2) --------------------------------------
  std::vector<std::int64_t> owner(n, -1);
  struct Work {
    std::vector<std::uint32_t> nodes;
    bool roundabout = false, cluster = false;
  };
  std::vector<Work> work;
  auto expand = [&](std::vector<std::uint32_t> seeds, bool roundabout, bool cluster) {
    Work w;
    w.roundabout = roundabout;
    w.cluster = cluster;
    const auto id = static_cast<std::int64_t>(work.size());
    std::deque<std::uint32_t> q;
    for (std::uint32_t v : seeds) {
      if (owner[v] >= 0) continue;
      owner[v] = id;
      w.nodes.push_back(v);
      q.push_back(v);
    }
    if (w.nodes.empty()) return;
    while (!q.empty()) {
      std::uint32_t v = q.front();
      q.pop_front();
      for (std::uint32_t s : g.incident[v]) {
        const Street& st = g.streets[s];
        std::uint32_t u = st.a == v ? st.b : st.a;
        if (owner[u] >= 0 || st.length >= short_edge || cut[u]) continue;  // a cut street stays a connector
        owner[u] = id;
        w.nodes.push_back(u);
        q.push_back(u);
      }
    }
    work.push_back(std::move(w));
  };
  for (Structure& s : structures) expand(s.nodes, s.roundabout, !s.roundabout);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (owner[v] < 0 && eligible(v)) expand({v}, false, false);
  }

  // ---- edges, roles and tags -----------------------------------------------------------------
  std::vector<Patch> patches(work.size());
  std::vector<std::vector<std::uint32_t>> patch_streets(work.size());
  std::vector<std::vector<char>> patch_reversed(work.size());
  for (std::uint32_t s = 0; s < g.streets.size(); ++s) {
    const Street& st = g.streets[s];
    std::int64_t oa = owner[st.a], ob = owner[st.b];
    if (oa >= 0) {
      patch_streets[oa].push_back(s);
      patch_reversed[oa].push_back(0);
    }
    if (ob >= 0 && ob != oa) {
      patch_streets[ob].push_back(s);
      patch_reversed[ob].push_back(1);
    }
  }
  auto vertex_tags = [&](std::uint32_t v, bool outer) {
    std::vector<std::string> t;
    if (degree(v) >= 3) t.emplace_back("intersection");
    if (degree(v) == 1) t.emplace_back("dead-end");
    if (outer) t.emplace_back("connectable");
    return t;
  };
  for (std::size_t p = 0; p < work.size(); ++p) {
    poll_interrupts();
    Patch& patch = patches[p];
    patch.id = static_cast<std::int64_t>(p + 1);
    const auto pid = static_cast<std::int64_t>(p);
    UnionFind uf(n);
    bool loop = false, curved = false, any_main = false, any_local = false, straight_main = false;
    std::size_t connectors = 0, dead_ends = 0;
    for (std::size_t k = 0; k < patch_streets[p].size(); ++k) {
      const Street& st = g.streets[patch_streets[p][k]];
      std::uint32_t from = patch_reversed[p][k] ? st.b : st.a, to = patch_reversed[p][k] ? st.a : st.b;
      PatchEdge e;
      e.line = patch_reversed[p][k] ? reversed(st.line) : st.line;
      e.road_class = st.road_class;
      e.example_id = st.id;
      if (degree(from) == 1 && degree(to) != 1) {  // the dead end last
        std::swap(from, to);
        e.line = reversed(std::move(e.line));
      }
      bool outside = owner[to] != pid;
      if (degree(to) == 1 && !cut[to]) {
        e.role = PatchEdgeRole::dead_end;
        ++dead_ends;
      } else if (outside) {
        // The far end is another patch's junction, a junction of the other level (a local patch's
        // arterial street reaching an arterial junction), or a street the crop cut.
        e.role = owner[to] >= 0 || degree(to) >= 3 || cut[to] ? PatchEdgeRole::connector : PatchEdgeRole::dead_end;
        connectors += e.role == PatchEdgeRole::connector;
        dead_ends += e.role == PatchEdgeRole::dead_end;
      } else {
        e.role = PatchEdgeRole::inner;
        if (uf.find(from) == uf.find(to)) loop = true;
        uf.unite(from, to);
      }
      bool main = is_main_class(st.road_class);
      bool edge_curved = turning(e.line) > kCurvedTurning;
      any_main = any_main || main;
      any_local = any_local || !main;
      curved = curved || edge_curved;
      straight_main = straight_main || (main && !edge_curved);
      add_tag(e.tags, main ? "main" : "local");
      if (e.role == PatchEdgeRole::connector) add_tag(e.tags, "connector");
      if (e.role == PatchEdgeRole::dead_end) add_tag(e.tags, "dead-end");
      if (cut[to]) add_tag(e.tags, "cut");
      if (degree(from) >= 3 || degree(to) >= 3) add_tag(e.tags, "snappable");
      add_tag(e.tags, edge_curved ? "curved" : "straight");
      if (ring_street[patch_streets[p][k]]) add_tag(e.tags, "roundabout");
      e.start_tags = vertex_tags(from, false);
      e.end_tags = vertex_tags(to, e.role == PatchEdgeRole::connector);
      if (cut[to]) std::replace(e.end_tags.begin(), e.end_tags.end(), std::string("dead-end"), std::string("cut"));
      patch.edges.push_back(std::move(e));
    }
    // Connectors first (the first one's inner end anchors a patch placed at a seed), then in
    // street order.
    std::stable_sort(patch.edges.begin(), patch.edges.end(), [](const PatchEdge& a, const PatchEdge& b) {
      return (a.role == PatchEdgeRole::connector) > (b.role == PatchEdgeRole::connector);
    });
    if (work[p].roundabout) add_tag(patch.tags, "roundabout");
    if (work[p].cluster) add_tag(patch.tags, "cluster");
    if (loop) add_tag(patch.tags, "loop");
    if (dead_ends > 0) add_tag(patch.tags, "cul-de-sac");
    add_tag(patch.tags, curved ? "curved" : "straight");
    if (connectors == 1) add_tag(patch.tags, "terminal");
    if (straight_main && any_local && connectors > 0) add_tag(patch.tags, "initial");
    if (any_main) add_tag(patch.tags, "main");
    if (any_local) add_tag(patch.tags, "local");
    if (level == Level::arterial) add_tag(patch.tags, "arterial");
  }
  return patches;
}

}  // namespace

PatchExtraction extract_patches(GeosContext& geos, const std::vector<PatchInputEdge>& example, const PatchParams& params) {
  auto check = [](double v, const char* name, bool zero_ok) {
    if (!std::isfinite(v) || v < 0.0 || (!zero_ok && v == 0.0)) {
      throw_invalid_argument(std::string(name) + " must be a finite number " + (zero_ok ? ">= 0" : "> 0"),
                             "It is " + std::to_string(v) + ".");
    }
  };
  check(params.short_edge, "short_edge", true);
  check(params.cluster_distance, "cluster_distance", true);
  check(params.circle_min_diameter, "circle_min_diameter", true);
  check(params.circle_max_diameter, "circle_max_diameter", false);
  check(params.crop_margin, "crop_margin", true);
  if (params.circle_max_diameter < params.circle_min_diameter) {
    throw_invalid_argument("circle_max_diameter must be >= circle_min_diameter");
  }
  if (!(params.circle_compactness > 0.0 && params.circle_compactness <= 1.0)) {
    throw_invalid_argument("circle_compactness must be in (0, 1]", "It is " + std::to_string(params.circle_compactness) + ".");
  }
  for (const PatchInputEdge& e : example) {
    for (Point p : e.line) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
        throw_invalid_argument("example edge " + std::to_string(e.id) + " has a non-finite coordinate");
      }
    }
  }
  // The patches depend on the example's content only, not on its row order or digitising
  // direction: edges are put in a canonical order (and direction) first.
  std::vector<PatchInputEdge> sorted = example;
  auto less = [](Point a, Point b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
  for (PatchInputEdge& e : sorted) {
    if (e.line.size() >= 2 && less(e.line.back(), e.line.front())) e.line = reversed(std::move(e.line));
  }
  std::stable_sort(sorted.begin(), sorted.end(), [&](const PatchInputEdge& a, const PatchInputEdge& b) {
    if (a.line.empty() || b.line.empty()) return a.line.size() < b.line.size();
    if (less(a.line.front(), b.line.front())) return true;
    if (less(b.line.front(), a.line.front())) return false;
    if (less(a.line.back(), b.line.back())) return true;
    if (less(b.line.back(), a.line.back())) return false;
    if (a.line.size() != b.line.size()) return a.line.size() < b.line.size();
    if (a.road_class != b.road_class) return a.road_class < b.road_class;
    return a.id < b.id;
  });
  StreetGraph g = build_street_graph(sorted);
  if (g.streets.empty()) {
    throw_invalid_argument("example has no edges", "The example holds no line of two distinct points.",
                           "Pass a query (or model) whose rows hold the example's road edges.");
  }
  const std::size_t n = g.nodes.size();
  PatchExtraction out;
  out.streets = g.streets.size();
  for (std::uint32_t v = 0; v < n; ++v) out.junctions += g.incident[v].size() >= 3;
  double short_edge = params.short_edge;
  if (short_edge == 0.0) {
    std::vector<double> lengths;
    for (const Street& s : g.streets) lengths.push_back(s.length);
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    short_edge = 0.4 * lengths[lengths.size() / 2];
  }
  out.short_edge = short_edge;
  const double cluster_distance = params.cluster_distance > 0.0 ? params.cluster_distance : short_edge;
  // The crop's edge: the convex hull of the example (GEOS), a dead end within crop_margin of it
  // is a street the crop cut.
  const double crop_margin = params.crop_margin;
  GEOSContextHandle_t h = geos.handle();
  GeomPtr hull_edge{nullptr, GeomDeleter{geos.handle()}};
  if (crop_margin > 0.0) {
    std::vector<GEOSGeometry*> pts;
    for (Point p : g.nodes) pts.push_back(GEOSGeom_createPointFromXY_r(h, p.x, p.y));
    for (const Street& s : g.streets) {
      for (Point p : s.line) pts.push_back(GEOSGeom_createPointFromXY_r(h, p.x, p.y));
    }
    if (std::find(pts.begin(), pts.end(), nullptr) != pts.end()) {
      for (GEOSGeometry* pt : pts) {
        if (pt != nullptr) GEOSGeom_destroy_r(h, pt);
      }
      geos.fail("hull point");
    }
    GeomPtr cloud = own(geos, GEOSGeom_createCollection_r(h, GEOS_MULTIPOINT, pts.data(), static_cast<unsigned>(pts.size())), "hull points");
    GeomPtr hull = own(geos, GEOSConvexHull_r(h, cloud.get()), "convex hull");
    hull_edge = own(geos, GEOSBoundary_r(h, hull.get()), "hull boundary");
  }
  auto cropped = [&](Point p) {
    if (!hull_edge) return false;
    GeomPtr pt = own(geos, GEOSGeom_createPointFromXY_r(h, p.x, p.y), "dead end");
    double d = INFINITY;
    if (GEOSDistance_r(h, hull_edge.get(), pt.get(), &d) == 0) geos.fail("distance to the hull");
    return d <= crop_margin;
  };
  // Levels (Nishida et al. 2016, section 3): arterial patches from the graph of the main streets
  // only (its streets run on through the junctions where local streets meet them), local patches
  // from the whole graph around the junctions where a local street meets.
  bool any_main = false, any_local = false;
  for (const Street& s : g.streets) {
    (is_main_class(s.road_class) ? any_main : any_local) = true;
  }
  std::vector<Patch> patches;
  if (params.levels && any_main && any_local) {
    std::vector<PatchInputEdge> main_edges;
    for (const PatchInputEdge& e : sorted) {
      if (is_main_class(e.road_class)) main_edges.push_back(e);
    }
    StreetGraph ga = build_street_graph(main_edges);
    patches = extract_level(geos, ga, params, short_edge, cluster_distance, Level::arterial, cropped);
    std::vector<Patch> local = extract_level(geos, g, params, short_edge, cluster_distance, Level::local, cropped);
    for (Patch& p : local) patches.push_back(std::move(p));
  } else {
    patches = extract_level(geos, g, params, short_edge, cluster_distance, Level::all, cropped);
  }
  // A patch without an edge (a junction whose streets all went elsewhere cannot happen; kept
  // for safety) is dropped, and the ids stay dense.
  std::int64_t next = 0;
  for (Patch& patch : patches) {
    if (patch.edges.empty()) continue;
    patch.id = ++next;
    out.arterial_patches += std::find(patch.tags.begin(), patch.tags.end(), "arterial") != patch.tags.end();
    out.patches.push_back(std::move(patch));
  }
  // The streets of components without a junction (a lone street, a ring) are in no patch; each
  // is a patch of its own with role isolated, after the others: grow_patches never places one,
  // but counts its dead ends in the example's share (the metrics count them).
  UnionFind components(n);
  for (const Street& s : g.streets) components.unite(s.a, s.b);
  std::vector<char> has_junction(n, 0);
  for (std::uint32_t v = 0; v < n; ++v) has_junction[components.find(v)] |= g.incident[v].size() >= 3 ? 1 : 0;
  for (const Street& s : g.streets) {
    if (has_junction[components.find(s.a)] != 0 || s.line.size() < 2) continue;
    Patch patch;
    patch.id = ++next;
    const bool curved = turning(s.line) > kCurvedTurning;
    add_tag(patch.tags, "isolated");
    add_tag(patch.tags, is_main_class(s.road_class) ? "main" : "local");
    add_tag(patch.tags, curved ? "curved" : "straight");
    PatchEdge e;
    e.line = s.line;
    e.role = PatchEdgeRole::isolated;
    e.road_class = s.road_class;
    e.example_id = s.id;
    add_tag(e.tags, is_main_class(s.road_class) ? "main" : "local");
    add_tag(e.tags, "isolated");
    add_tag(e.tags, curved ? "curved" : "straight");
    if (g.incident[s.a].size() == 1) add_tag(e.start_tags, "dead-end");
    if (g.incident[s.b].size() == 1) add_tag(e.end_tags, "dead-end");
    patch.edges.push_back(std::move(e));
    out.patches.push_back(std::move(patch));
  }
  return out;
}

}  // namespace streetgen::core
