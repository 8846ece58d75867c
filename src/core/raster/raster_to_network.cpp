#include "core/raster/raster_to_network.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/interrupts.hpp"
#include "core/union_find.hpp"

namespace streetgen::core {
namespace {

// ---- The skeleton's pixel graph ----------------------------------------------------------------

// Neighbours clockwise from north; odd k are diagonal.
constexpr int kDr[8] = {-1, -1, 0, 1, 1, 1, 0, -1};
constexpr int kDc[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// The 8-neighbour links of a skeleton pixel, except a diagonal link whose two pixels also touch
// through a shared 4-neighbour. Zhang-Suen leaves such staircase corners, and keeping the
// diagonal makes the paper's "0.5 square pixel" triangle blocks, which the paper then finds as
// faces and removes by their longest (sqrt 2) edge. Dropping exactly that edge here gives the
// same graph without building the triangles. Connectivity is unchanged: the two orthogonal links
// remain.
int links(const BinaryImage& img, int r, int c, int out[8]) {
  int n = 0;
  for (int k = 0; k < 8; ++k) {
    int rr = r + kDr[k], cc = c + kDc[k];
    if (!img.at(rr, cc)) continue;
    if ((k & 1) && (img.at(rr, c) || img.at(r, cc))) continue;
    out[n++] = rr * img.width + cc;
  }
  return n;
}

// ---- The chain graph ---------------------------------------------------------------------------

struct Chain {
  int a = 0, b = 0;
  Polyline line;  // starts at node a, ends at node b
  bool alive = true;
};

struct Graph {
  std::vector<Point> nodes;
  std::vector<Chain> chains;
  double pixel_size = 1.0;  // m, for the direction probe of the face walk
  Point origin;             // subtracted in area sums (projected coordinates are large)
};

void reverse_chain(Chain& c) {
  std::swap(c.a, c.b);
  std::reverse(c.line.begin(), c.line.end());
}

// node -> (chain, end) with end 0 = the chain's start.
std::vector<std::vector<std::pair<int, int>>> incidence(const Graph& g) {
  std::vector<std::vector<std::pair<int, int>>> inc(g.nodes.size());
  for (int i = 0; i < static_cast<int>(g.chains.size()); ++i) {
    const Chain& c = g.chains[i];
    if (!c.alive) continue;
    inc[c.a].push_back({i, 0});
    inc[c.b].push_back({i, 1});
  }
  return inc;
}

// Joins the two chains at every node of degree 2 (but not a lone self-loop), so chains run from
// junction or dead end to junction or dead end, as the paper's street chains do.
void merge_degree2(Graph& g) {
  bool changed = true;
  while (changed) {
    changed = false;
    poll_interrupts();
    auto inc = incidence(g);
    std::vector<char> touched(g.chains.size(), 0);
    for (std::size_t v = 0; v < g.nodes.size(); ++v) {
      if (inc[v].size() != 2) continue;
      int c1 = inc[v][0].first, c2 = inc[v][1].first;
      if (c1 == c2 || touched[c1] || touched[c2]) continue;
      Chain& first = g.chains[c1];
      Chain& second = g.chains[c2];
      if (first.b != static_cast<int>(v)) reverse_chain(first);
      if (second.a != static_cast<int>(v)) reverse_chain(second);
      first.line.insert(first.line.end(), second.line.begin() + 1, second.line.end());
      first.b = second.b;
      second.alive = false;
      second.line.clear();
      touched[c1] = touched[c2] = 1;
      changed = true;
    }
  }
}

// The point `distance` along the line (or its end): the direction probe of a half-edge.
Point probe(const Polyline& line, double distance) {
  double walked = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    walked += core::distance(line[i - 1], line[i]);
    if (walked >= distance) return line[i];
  }
  return line.back();
}

// Faces of the embedded graph by the half-edge walk (at each node, leave by the next edge
// clockwise from the one arrived on): bounded faces come out counter-clockwise with a positive
// area. Each face of positive area below min_area loses its longest chain; repeated until no
// such face is left (a removal can merge two small faces into a larger one).
std::size_t remove_small_faces(Graph& g, double min_area) {
  std::size_t removed_total = 0;
  if (min_area <= 0.0) return 0;
  for (;;) {
    poll_interrupts();
    const int nh = static_cast<int>(g.chains.size()) * 2;
    std::vector<std::vector<int>> around(g.nodes.size());
    std::vector<double> angle(nh, 0.0);
    auto head = [&](int h) { return h & 1 ? g.chains[h / 2].a : g.chains[h / 2].b; };
    for (int i = 0; i < static_cast<int>(g.chains.size()); ++i) {
      const Chain& c = g.chains[i];
      if (!c.alive) continue;
      double len = length(c.line);
      double d = std::min(len / 2, 2.0 * g.pixel_size);
      Point start = c.line.front(), end = c.line.back();
      Point p = probe(c.line, d);
      Polyline back(c.line.rbegin(), c.line.rend());
      Point q = probe(back, d);
      angle[2 * i] = std::atan2(p.y - start.y, p.x - start.x);
      angle[2 * i + 1] = std::atan2(q.y - end.y, q.x - end.x);
      around[c.a].push_back(2 * i);
      around[c.b].push_back(2 * i + 1);
    }
    std::vector<int> position(nh, 0);
    for (auto& list : around) {
      std::sort(list.begin(), list.end(),
                [&](int x, int y) { return angle[x] < angle[y] || (angle[x] == angle[y] && x < y); });
      for (int k = 0; k < static_cast<int>(list.size()); ++k) position[list[k]] = k;
    }
    std::vector<char> seen(nh, 0);
    std::vector<char> drop(g.chains.size(), 0);
    bool any = false;
    for (int start = 0; start < nh; ++start) {
      if (seen[start] || !g.chains[start / 2].alive) continue;
      double area2 = 0.0;
      int longest = -1;
      double longest_len = -1.0;
      int h = start;
      std::size_t guard = 0;
      while (!seen[h] && guard++ <= static_cast<std::size_t>(nh)) {
        seen[h] = 1;
        const Chain& c = g.chains[h / 2];
        const Polyline& line = c.line;
        const std::size_t n = line.size();
        for (std::size_t k = 1; k < n; ++k) {
          Point p0 = (h & 1 ? line[n - k] : line[k - 1]) - g.origin;
          Point p1 = (h & 1 ? line[n - 1 - k] : line[k]) - g.origin;
          area2 += cross(p0, p1);
        }
        double len = length(line);
        if (len > longest_len) {
          longest_len = len;
          longest = h / 2;
        }
        const std::vector<int>& list = around[head(h)];
        int twin = h ^ 1;
        h = list[(position[twin] + list.size() - 1) % list.size()];
      }
      double area = area2 / 2;
      if (area > 0.0 && area < min_area && longest >= 0) {
        drop[longest] = 1;
        any = true;
      }
    }
    if (!any) break;
    for (std::size_t i = 0; i < g.chains.size(); ++i) {
      if (drop[i]) {
        g.chains[i].alive = false;
        ++removed_total;
      }
    }
    merge_degree2(g);
  }
  return removed_total;
}

// Dead-end chains shorter than min_length go, repeatedly (a fork of two short spurs leaves a
// short dead end behind), with degree-2 nodes merged after each round.
std::size_t prune_dead_ends(Graph& g, double min_length) {
  std::size_t removed = 0;
  if (min_length <= 0.0) return 0;
  for (;;) {
    poll_interrupts();
    auto inc = incidence(g);
    std::size_t round = 0;
    for (Chain& c : g.chains) {
      if (!c.alive || c.a == c.b) continue;
      bool dead_end = inc[c.a].size() == 1 || inc[c.b].size() == 1;
      if (dead_end && length(c.line) < min_length) {
        c.alive = false;
        ++round;
      }
    }
    if (round == 0) break;
    removed += round;
    merge_degree2(g);
  }
  return removed;
}

// The paper's local averaging p_i = p_{i-1}/4 + p_i/2 + p_{i+1}/4 on the inner vertices.
void smooth(Polyline& line, int iterations) {
  if (line.size() < 3) return;
  Polyline next = line;
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      next[i] = 0.25 * line[i - 1] + 0.5 * line[i] + 0.25 * line[i + 1];
    }
    line.swap(next);
    next.front() = line.front();
    next.back() = line.back();
  }
}

// Douglas-Peucker by GEOS (GEOSSimplify), which keeps both ends of a LineString. A closed chain
// that would collapse below a ring keeps its smoothed course.
void simplify(GeosContext& geos, Polyline& line, double tolerance) {
  if (tolerance <= 0.0 || line.size() < 3) return;
  GEOSContextHandle_t h = geos.handle();
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, static_cast<unsigned>(line.size()), 2);
  if (seq == nullptr) geos.fail("GEOSCoordSeq_create");
  for (std::size_t i = 0; i < line.size(); ++i) {
    GEOSCoordSeq_setXY_r(h, seq, static_cast<unsigned>(i), line[i].x, line[i].y);
  }
  GeomPtr geom = own(geos, GEOSGeom_createLineString_r(h, seq), "GEOSGeom_createLineString");
  GeomPtr simple = own(geos, GEOSSimplify_r(h, geom.get(), tolerance), "GEOSSimplify");
  const GEOSCoordSequence* out = GEOSGeom_getCoordSeq_r(h, simple.get());
  unsigned n = 0;
  if (out == nullptr || !GEOSCoordSeq_getSize_r(h, out, &n)) geos.fail("GEOSGeom_getCoordSeq");
  bool closed = distance(line.front(), line.back()) == 0.0;
  if (n < (closed ? 4u : 2u)) return;
  Polyline result(n);
  for (unsigned i = 0; i < n; ++i) GEOSCoordSeq_getXY_r(h, out, i, &result[i].x, &result[i].y);
  line.swap(result);
}

// World -> pixel space (col, row), the inverse of the raster's affine georeference.
Point to_pixel(const GeoTransform& t, Point p) {
  double det = t.scale_x * t.scale_y - t.skew_x * t.skew_y;
  double dx = p.x - t.ip_x, dy = p.y - t.ip_y;
  return {(t.scale_y * dx - t.skew_x * dy) / det, (-t.skew_y * dx + t.scale_x * dy) / det};
}

// Distance (m) from a point to the nearest background pixel of the cleaned mask: the local half
// width of the painted road. Searched in square rings up to 64 pixels; pixels outside the raster
// do not count (a road leaving the raster is not narrower there).
double clearance(const BinaryImage& mask, const GeoTransform& t, Point world) {
  Point px = to_pixel(t, world);
  int r0 = static_cast<int>(std::floor(px.y)), c0 = static_cast<int>(std::floor(px.x));
  double best = -1.0;
  auto visit = [&](int r, int c) {
    if (r < 0 || c < 0 || r >= mask.height || c >= mask.width || mask.at(r, c)) return;
    double d = std::hypot(c + 0.5 - px.x, r + 0.5 - px.y);
    if (best < 0 || d < best) best = d;
  };
  // Ring k holds the pixels at Chebyshev distance k, all at Euclidean distance >= k - 1 from px.
  for (int k = 0; k <= 64 && !(best >= 0 && best <= k - 1); ++k) {
    if (k == 0) {
      visit(r0, c0);
      continue;
    }
    for (int d = -k; d <= k; ++d) {
      visit(r0 - k, c0 + d);
      visit(r0 + k, c0 + d);
      if (d != -k && d != k) {
        visit(r0 + d, c0 - k);
        visit(r0 + d, c0 + k);
      }
    }
  }
  return best < 0 ? 64.0 * std::sqrt(t.pixel_area()) : best * std::sqrt(t.pixel_area());
}

// Thinning a wide crossing often leaves two junctions joined by a short link where the roads
// meet. A link between two junctions (degree >= 3) shorter than the painted half width at
// either end is contracted: the junctions become one, at the middle of the link.
std::size_t contract_junction_links(Graph& g, const BinaryImage& mask, const GeoTransform& t) {
  std::size_t contracted = 0;
  std::vector<double> reach_of(g.nodes.size(), -1.0);  // clearance per node, until the node moves
  auto reach = [&](int node) {
    if (reach_of[node] < 0) reach_of[node] = clearance(mask, t, g.nodes[node]);
    return reach_of[node];
  };
  for (;;) {
    poll_interrupts();
    auto inc = incidence(g);
    std::vector<char> touched(g.nodes.size(), 0);
    std::size_t round = 0;
    for (std::size_t i = 0; i < g.chains.size(); ++i) {
      Chain& c = g.chains[i];
      if (!c.alive || c.a == c.b || touched[c.a] || touched[c.b]) continue;
      if (inc[c.a].size() < 3 || inc[c.b].size() < 3) continue;
      if (length(c.line) >= std::max(reach(c.a), reach(c.b))) continue;
      const int keep = c.a, gone = c.b;
      Point mid = 0.5 * (g.nodes[keep] + g.nodes[gone]);
      c.alive = false;
      g.nodes[keep] = mid;
      reach_of[keep] = -1.0;
      for (int node : {keep, gone}) {
        for (auto [ci, end] : inc[node]) {
          Chain& other = g.chains[ci];
          if (!other.alive) continue;
          if (end == 0) {
            other.a = keep;
            other.line.front() = mid;
          } else {
            other.b = keep;
            other.line.back() = mid;
          }
        }
      }
      touched[keep] = touched[gone] = 1;
      ++round;
    }
    if (round == 0) break;
    contracted += round;
    merge_degree2(g);
  }
  return contracted;
}

// Thinning stops a dead end about half a road width before the painted road ends (and before a
// road leaves the raster). Each dead end is carried on along its last direction to where the
// cleaned mask ends, so dead-end lengths match the painted roads.
void extend_dead_ends(Graph& g, const BinaryImage& mask, const GeoTransform& t) {
  auto inc = incidence(g);
  const double pixel = std::sqrt(t.pixel_area());
  for (std::size_t v = 0; v < g.nodes.size(); ++v) {
    if (inc[v].size() != 1) continue;
    Chain& c = g.chains[inc[v][0].first];
    const bool at_end = inc[v][0].second == 1;
    Polyline back = at_end ? Polyline(c.line.rbegin(), c.line.rend()) : c.line;  // starts at the dead end
    Point tip = back.front();
    Point dir = unit(tip - probe(back, 3.0 * pixel));
    if (norm(dir) == 0.0) continue;
    Point last = tip;
    for (double s = 0.5 * pixel;; s += 0.5 * pixel) {
      Point q = tip + s * dir;
      Point px = to_pixel(t, q);
      int r = static_cast<int>(std::floor(px.y)), col = static_cast<int>(std::floor(px.x));
      if (r < 0 || col < 0 || r >= mask.height || col >= mask.width || !mask.at(r, col)) break;
      last = q;
    }
    if (distance(last, tip) == 0.0) continue;
    g.nodes[v] = last;
    if (at_end) {
      c.line.push_back(last);
    } else {
      c.line.insert(c.line.begin(), last);
    }
  }
}

// ---- Gap closing -------------------------------------------------------------------------------

struct TreeDeleter {
  GEOSContextHandle_t handle;
  void operator()(GEOSSTRtree* tree) const noexcept { GEOSSTRtree_destroy_r(handle, tree); }
};

// What a tree query collects; GEOS calls this from C, so it must not throw.
struct Found {
  std::vector<int> chains;
  bool out_of_memory = false;
};
void collect_chain(void* item, void* userdata) noexcept {
  auto* found = static_cast<Found*>(userdata);
  try {
    found->chains.push_back(static_cast<int>(reinterpret_cast<std::uintptr_t>(item)) - 1);
  } catch (...) {
    found->out_of_memory = true;
  }
}

GeomPtr make_line(GeosContext& geos, const Polyline& line) {
  GEOSContextHandle_t h = geos.handle();
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, static_cast<unsigned>(line.size()), 2);
  if (seq == nullptr) geos.fail("GEOSCoordSeq_create");
  for (std::size_t i = 0; i < line.size(); ++i) {
    GEOSCoordSeq_setXY_r(h, seq, static_cast<unsigned>(i), line[i].x, line[i].y);
  }
  return own(geos, GEOSGeom_createLineString_r(h, seq), "GEOSGeom_createLineString");
}

// The circular sector a dead end looks into: apex at the tip, radius `reach`, half-angle `half`
// (radians, <= pi/2, so the sector is convex and holds every straight join it allows); a
// segment when the half-angle is 0.
GeomPtr make_sector(GeosContext& geos, Point tip, Point dir, double reach, double half) {
  GEOSContextHandle_t h = geos.handle();
  if (half <= 0.0) return make_line(geos, {tip, tip + reach * dir});
  const int steps = std::max(2, static_cast<int>(std::ceil(half / (std::acos(-1.0) / 36))));  // 5 degrees
  const double base = std::atan2(dir.y, dir.x);
  Polyline ring{tip};
  for (int k = 0; k <= steps; ++k) {
    double a = base - half + 2.0 * half * k / steps;
    ring.push_back(tip + reach * Point{std::cos(a), std::sin(a)});
  }
  ring.push_back(tip);
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, static_cast<unsigned>(ring.size()), 2);
  if (seq == nullptr) geos.fail("GEOSCoordSeq_create");
  for (std::size_t i = 0; i < ring.size(); ++i) {
    GEOSCoordSeq_setXY_r(h, seq, static_cast<unsigned>(i), ring[i].x, ring[i].y);
  }
  GEOSGeometry* shell = GEOSGeom_createLinearRing_r(h, seq);
  if (shell == nullptr) geos.fail("GEOSGeom_createLinearRing");
  return own(geos, GEOSGeom_createPolygon_r(h, shell, nullptr, 0), "GEOSGeom_createPolygon");
}

// A join proposed from a dead end to the road ahead of it.
struct Join {
  int from = 0;          // the dead-end node
  int node = -1;         // the target node, or -1: a point inside chain `chain`
  int chain = -1;        // the target chain
  double abscissa = 0;   // of the target point along the target chain
  Point at;              // the target point
  double length = 0;
};

// A generator's roads break off: its skeleton has dead ends facing the road they should meet a
// few metres on. Each dead end is joined by a straight segment to the nearest point of another
// chain inside the sector ahead of it (radius max_gap, half-angle gap_angle; a point within two
// pixels of a chain's end node is that node), shortest joins first, unless the join would cross
// a chain or a join already made. Runs before pruning, so what is still dangling and short is
// pruned after. Dead ends shorter than the painted half width at their other end are not joined:
// those are thinning spurs at wide corners, pointing anywhere.
std::size_t close_gaps(GeosContext& geos, Graph& g, const BinaryImage& mask, const GeoTransform& t, double max_gap,
                       double gap_angle_deg) {
  if (max_gap <= 0.0) return 0;
  GEOSContextHandle_t h = geos.handle();
  const double pixel = g.pixel_size;
  const double half = gap_angle_deg * std::acos(-1.0) / 180.0;
  const double snap = 2.0 * pixel;
  auto inc = incidence(g);

  // Every live chain as a GEOS line, in an STRtree by chain index (items are index + 1: GEOS
  // may treat a null item as none).
  std::vector<GeomPtr> lines(g.chains.size());
  std::unique_ptr<GEOSSTRtree, TreeDeleter> tree(GEOSSTRtree_create_r(h, 10), TreeDeleter{h});
  if (!tree) geos.fail("GEOSSTRtree_create");
  for (std::size_t i = 0; i < g.chains.size(); ++i) {
    if (!g.chains[i].alive) continue;
    lines[i] = make_line(geos, g.chains[i].line);
    GEOSSTRtree_insert_r(h, tree.get(), lines[i].get(), reinterpret_cast<void*>(static_cast<std::uintptr_t>(i + 1)));
  }
  Found found;
  auto query = [&](const GEOSGeometry* geom) -> const std::vector<int>& {
    found.chains.clear();
    GEOSSTRtree_query_r(h, tree.get(), geom, &collect_chain, &found);
    if (found.out_of_memory) throw std::bad_alloc();
    std::sort(found.chains.begin(), found.chains.end());
    return found.chains;
  };

  std::vector<Join> proposals;
  for (std::size_t v = 0; v < g.nodes.size(); ++v) {
    if (inc[v].size() != 1) continue;
    poll_interrupts();
    const int c = inc[v][0].first;
    const Chain& chain = g.chains[c];
    const Polyline back = inc[v][0].second == 1 ? Polyline(chain.line.rbegin(), chain.line.rend()) : chain.line;
    const double len = length(back);
    const int other = inc[v][0].second == 1 ? chain.a : chain.b;
    if (len < clearance(mask, t, g.nodes[other])) continue;
    const Point tip = back.front();
    const Point dir = unit(tip - probe(back, std::min(len, std::max(3.0 * pixel, 2.0 * clearance(mask, t, tip)))));
    if (norm(dir) == 0.0) continue;
    GeomPtr sector = make_sector(geos, tip, dir, max_gap, half);
    GeomPtr tip_point = own(geos, GEOSGeom_createPointFromXY_r(h, tip.x, tip.y), "GEOSGeom_createPointFromXY");
    Join best;
    best.length = std::numeric_limits<double>::infinity();
    for (int k : query(sector.get())) {
      if (k == c) continue;
      GeomPtr seen = own(geos, GEOSIntersection_r(h, sector.get(), lines[k].get()), "GEOSIntersection");
      if (GEOSisEmpty_r(h, seen.get())) continue;
      double d = 0.0;
      if (!GEOSDistance_r(h, seen.get(), tip_point.get(), &d)) geos.fail("GEOSDistance");
      if (!(d < best.length) || d <= 0.0) continue;
      GEOSCoordSequence* nearest = GEOSNearestPoints_r(h, seen.get(), tip_point.get());
      if (nearest == nullptr) geos.fail("GEOSNearestPoints");
      Point p;
      GEOSCoordSeq_getXY_r(h, nearest, 0, &p.x, &p.y);
      GEOSCoordSeq_destroy_r(h, nearest);
      best.from = static_cast<int>(v);
      best.chain = k;
      best.at = p;
      best.length = d;
    }
    if (best.chain < 0 || best.length > max_gap) continue;
    const Chain& target = g.chains[best.chain];
    const double s = project(target.line, best.at).abscissa;
    const double target_len = length(target.line);
    if (s <= snap || target_len - s <= snap) {
      best.node = s <= snap ? target.a : target.b;
      best.at = g.nodes[best.node];
      best.length = distance(tip, best.at);
    } else {
      best.abscissa = s;
      best.at = point_at(target.line, s);
    }
    proposals.push_back(best);
  }
  std::sort(proposals.begin(), proposals.end(), [](const Join& x, const Join& y) {
    return x.length < y.length || (x.length == y.length && x.from < y.from);
  });

  // Shortest first; a dead end that an earlier join reached is no longer one.
  std::vector<int> degree(g.nodes.size());
  for (std::size_t v = 0; v < g.nodes.size(); ++v) degree[v] = static_cast<int>(inc[v].size());
  std::vector<Join> accepted;
  std::vector<GeomPtr> made;  // the accepted joins, shortened like the candidates
  for (const Join& j : proposals) {
    if (degree[j.from] != 1 || (j.node >= 0 && j.node == j.from)) continue;
    const Point tip = g.nodes[j.from];
    const Point u = unit(j.at - tip);
    const double eps = std::min(0.01 * pixel, 0.25 * j.length);  // the join may touch chains at its two ends
    GeomPtr segment = make_line(geos, {tip + eps * u, j.at - eps * u});
    bool crosses = false;
    for (int k : query(segment.get())) {
      char hit = GEOSIntersects_r(h, segment.get(), lines[k].get());
      if (hit == 2) geos.fail("GEOSIntersects");
      if (hit) {
        crosses = true;
        break;
      }
    }
    for (std::size_t m = 0; m < made.size() && !crosses; ++m) {
      char hit = GEOSIntersects_r(h, segment.get(), made[m].get());
      if (hit == 2) geos.fail("GEOSIntersects");
      crosses = hit != 0;
    }
    if (crosses) continue;
    ++degree[j.from];
    if (j.node >= 0) ++degree[j.node];
    accepted.push_back(j);
    made.push_back(std::move(segment));
  }

  // Targets inside a chain split it there (several joins may split one chain).
  std::vector<std::vector<std::size_t>> splits(g.chains.size());
  for (std::size_t i = 0; i < accepted.size(); ++i) {
    if (accepted[i].node < 0) splits[accepted[i].chain].push_back(i);
  }
  for (std::size_t k = 0; k < splits.size(); ++k) {
    if (splits[k].empty()) continue;
    std::vector<std::size_t>& list = splits[k];
    std::sort(list.begin(), list.end(), [&](std::size_t x, std::size_t y) {
      return accepted[x].abscissa < accepted[y].abscissa || (accepted[x].abscissa == accepted[y].abscissa && x < y);
    });
    const Polyline line = g.chains[k].line;
    const int end_node = g.chains[k].b;
    int from_node = g.chains[k].a;
    double from_s = 0.0;
    bool first = true;
    for (std::size_t i : list) {
      Join& j = accepted[i];
      if (!first && j.abscissa == from_s) {  // the same point as the previous split
        j.node = from_node;
        continue;
      }
      const int node = static_cast<int>(g.nodes.size());
      g.nodes.push_back(j.at);
      Polyline piece = substring(line, from_s, j.abscissa);
      piece.front() = g.nodes[from_node];
      piece.back() = j.at;
      if (first) {
        g.chains[k].b = node;
        g.chains[k].line = std::move(piece);
      } else {
        g.chains.push_back({from_node, node, std::move(piece)});
      }
      j.node = node;
      from_node = node;
      from_s = j.abscissa;
      first = false;
    }
    Polyline rest = substring(line, from_s, length(line));
    rest.front() = g.nodes[from_node];
    rest.back() = g.nodes[end_node];
    g.chains.push_back({from_node, end_node, std::move(rest)});
  }
  for (const Join& j : accepted) g.chains.push_back({j.from, j.node, {g.nodes[j.from], g.nodes[j.node]}});
  merge_degree2(g);
  return accepted.size();
}

void require_non_negative(double v, const char* name) {
  if (!(v >= 0.0) || !std::isfinite(v)) {
    throw_invalid_argument(std::string(name) + " must be a finite number >= 0", "It is " + std::to_string(v) + ".");
  }
}

void require_steps(int v, const char* name) {
  if (v < 0 || v > 100) {
    throw_invalid_argument(std::string(name) + " must be between 0 and 100", "It is " + std::to_string(v) + ".");
  }
}

}  // namespace

RasterNetwork skeleton_to_network(GeosContext& geos, const BinaryImage& skeleton, const BinaryImage& cleaned,
                                  const GeoTransform& transform, const RasterNetworkParams& params) {
  RasterNetwork result;
  const int w = skeleton.width, h = skeleton.height;
  const std::size_t size = static_cast<std::size_t>(w) * h;
  InterruptPoller poller(1 << 16);

  // The skeleton pixels in raster order; one image-sized array maps a pixel to its index in
  // that list, and everything else is per skeleton pixel (a few % of the image).
  std::vector<int> pixels;
  std::vector<int> index_of(size, -1);
  for (int i = 0; i < static_cast<int>(size); ++i) {
    if (skeleton.pixels[i]) {
      index_of[i] = static_cast<int>(pixels.size());
      pixels.push_back(i);
    }
  }
  const int n_pix = static_cast<int>(pixels.size());
  result.stats.skeleton_pixels = pixels.size();
  int nb[8];
  std::vector<std::uint8_t> degree(n_pix);
  for (int s = 0; s < n_pix; ++s) {
    degree[s] = static_cast<std::uint8_t>(links(skeleton, pixels[s] / w, pixels[s] % w, nb));
  }
  // Links between skeleton indices.
  auto linked = [&](int s, int out[8]) {
    int n = links(skeleton, pixels[s] / w, pixels[s] % w, out);
    for (int k = 0; k < n; ++k) out[k] = index_of[out[k]];
    return n;
  };

  // Junction pixels (degree >= 3) that touch form one node, placed at their centroid.
  UnionFind clusters(pixels.size());
  for (int s = 0; s < n_pix; ++s) {
    if (degree[s] < 3) continue;
    int n = linked(s, nb);
    for (int k = 0; k < n; ++k) {
      if (degree[nb[k]] >= 3) clusters.unite(static_cast<std::size_t>(s), static_cast<std::size_t>(nb[k]));
    }
  }
  Graph g;
  g.pixel_size = std::sqrt(transform.pixel_area());
  g.origin = transform.at(0, 0);
  std::vector<int> node_of(n_pix, -1);
  std::vector<Point> sum;  // pixel-space centroid sums per node
  std::vector<int> members;
  for (int s = 0; s < n_pix; ++s) {
    if (degree[s] == 2 || degree[s] == 0) continue;
    int root = degree[s] >= 3 ? static_cast<int>(clusters.find(static_cast<std::size_t>(s))) : s;
    if (node_of[root] < 0) {  // the root comes first in raster order: it is the smallest index
      node_of[root] = static_cast<int>(sum.size());
      sum.push_back({0, 0});
      members.push_back(0);
    }
    const int node = node_of[root];
    node_of[s] = node;
    sum[node] = sum[node] + Point{pixels[s] % w + 0.5, pixels[s] / w + 0.5};
    members[node] += 1;
  }
  for (std::size_t n = 0; n < sum.size(); ++n) {
    g.nodes.push_back(transform.at(sum[n].x / members[n], sum[n].y / members[n]));
  }
  auto centre = [&](int s) { return transform.at(pixels[s] % w + 0.5, pixels[s] / w + 0.5); };

  // Chains from each node pixel along degree-2 pixels to the next node pixel.
  std::vector<std::uint8_t> visited(n_pix, 0);
  for (int s = 0; s < n_pix; ++s) {
    poller.tick();
    if (node_of[s] < 0) continue;
    int first[8];
    int n = linked(s, first);
    for (int k = 0; k < n; ++k) {
      int q = first[k];
      if (node_of[q] >= 0) {
        // Two node pixels side by side: one chain unless they belong to the same junction.
        if (node_of[q] != node_of[s] && s < q) {
          g.chains.push_back({node_of[s], node_of[q], {g.nodes[node_of[s]], g.nodes[node_of[q]]}});
        }
        continue;
      }
      if (visited[q]) continue;
      Chain chain;
      chain.a = node_of[s];
      chain.line.push_back(g.nodes[chain.a]);
      int prev = s, cur = q;
      while (node_of[cur] < 0) {
        visited[cur] = 1;
        chain.line.push_back(centre(cur));
        int m = linked(cur, nb);
        if (m != 2) throw Error(ErrorKind::internal, "skeleton chain walk met a pixel of degree " + std::to_string(m));
        int next = nb[0] == prev ? nb[1] : nb[0];
        prev = cur;
        cur = next;
      }
      chain.b = node_of[cur];
      chain.line.push_back(g.nodes[chain.b]);
      g.chains.push_back(std::move(chain));
    }
  }
  // Rings without any junction or end: one node on their first pixel, one closed chain.
  for (int s = 0; s < n_pix; ++s) {
    if (degree[s] != 2 || visited[s]) continue;
    int node = static_cast<int>(g.nodes.size());
    g.nodes.push_back(centre(s));
    Chain chain;
    chain.a = chain.b = node;
    chain.line.push_back(centre(s));
    visited[s] = 1;
    linked(s, nb);
    int prev = s, cur = nb[0];
    while (cur != s) {
      visited[cur] = 1;
      chain.line.push_back(centre(cur));
      linked(cur, nb);
      int next = nb[0] == prev ? nb[1] : nb[0];
      prev = cur;
      cur = next;
    }
    chain.line.push_back(centre(s));
    g.chains.push_back(std::move(chain));
  }
  result.stats.raw_edges = g.chains.size();

  merge_degree2(g);
  result.stats.small_faces = remove_small_faces(g, params.min_block_area);
  result.stats.gaps_closed = close_gaps(geos, g, cleaned, transform, params.max_gap, params.gap_angle);
  result.stats.dead_ends_pruned = prune_dead_ends(g, params.min_dead_end_length);
  result.stats.junctions_merged = contract_junction_links(g, cleaned, transform);
  // Pruning and contraction can leave a small face that a spur used to split; one more pass.
  result.stats.small_faces += remove_small_faces(g, params.min_block_area);
  extend_dead_ends(g, cleaned, transform);

  std::vector<std::int64_t> out_id(g.nodes.size(), 0);
  std::int64_t next_node = 0, next_edge = 0;
  for (Chain& c : g.chains) {
    if (!c.alive) continue;
    poller.tick();
    smooth(c.line, params.smooth_iterations);
    simplify(geos, c.line, params.simplify_tolerance);
    if (length(c.line) == 0.0) continue;
    for (int node : {c.a, c.b}) {
      if (out_id[node] == 0) out_id[node] = ++next_node;
    }
    result.edges.push_back({++next_edge, out_id[c.a], out_id[c.b], std::move(c.line)});
  }
  result.node_count = static_cast<std::size_t>(next_node);
  return result;
}

RasterNetwork raster_to_network(GeosContext& geos, const RoadRaster& raster, const RasterNetworkParams& params) {
  require_steps(params.erode, "erode");
  require_steps(params.dilate, "dilate");
  require_steps(params.smooth_iterations, "smooth_iterations");
  require_non_negative(params.min_block_area, "min_block_area");
  require_non_negative(params.min_dead_end_length, "min_dead_end_length");
  require_non_negative(params.simplify_tolerance, "simplify_tolerance");
  require_non_negative(params.max_gap, "max_gap");
  if (!(params.gap_angle >= 0.0 && params.gap_angle <= 90.0)) {
    throw_invalid_argument("gap_angle must be between 0 and 90 (degrees)",
                           "It is " + std::to_string(params.gap_angle) + ".");
  }
  const BinaryImage& mask = raster.mask;
  std::size_t road = mask.count();
  if (road == mask.pixels.size()) {
    throw Error(ErrorKind::bad_data, "rast has no background pixel",
                "All " + std::to_string(road) + " pixels are above the threshold, so there are no streets to trace.",
                "Road pixels are those with a value > threshold (default 0.5); for a generator's output in [-1, 1] "
                "use \"threshold\": 0.");
  }
  BinaryImage image = mask;
  erode(image, params.erode);
  dilate(image, params.dilate);
  const BinaryImage cleaned = image;
  zhang_suen_thin(image);
  RasterNetwork result = skeleton_to_network(geos, image, cleaned, raster.transform, params);
  result.stats.road_pixels = road;
  result.stats.cleaned_pixels = cleaned.count();
  return result;
}

}  // namespace streetgen::core
