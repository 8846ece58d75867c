#include "core/streets/polygon_contact.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <cmath>

#include <algorithm>
#include <vector>

namespace streetgen::core {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = Kernel::Point_2;

std::vector<P2> open_ring(const Polyline& ring) {
  std::vector<P2> out;
  out.reserve(ring.size());
  for (Point p : ring) out.emplace_back(p.x, p.y);
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

// A closed box; exact comparisons of the input doubles, no arithmetic.
struct Box2 {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  bool meets(const Box2& o) const { return xmin <= o.xmax && o.xmin <= xmax && ymin <= o.ymax && o.ymin <= ymax; }
  bool holds(const P2& p) const { return xmin <= p.x() && p.x() <= xmax && ymin <= p.y() && p.y() <= ymax; }
};
Box2 box_of(const std::vector<P2>& ring) {
  Box2 b{ring[0].x(), ring[0].y(), ring[0].x(), ring[0].y()};
  for (const P2& p : ring) {
    b.xmin = std::min(b.xmin, p.x());
    b.ymin = std::min(b.ymin, p.y());
    b.xmax = std::max(b.xmax, p.x());
    b.ymax = std::max(b.ymax, p.y());
  }
  return b;
}
Box2 box_of(const P2& p, const P2& q) {
  return {std::min(p.x(), q.x()), std::min(p.y(), q.y()), std::max(p.x(), q.x()), std::max(p.y(), q.y())};
}

// A ring and the edges (by their first vertex) and vertices that meet a region: where two rings'
// interiors can meet at all, the common part of their boxes. A long street's roadway beside a
// corner's band has hundreds of edges, a few of them near the band.
struct RingNear {
  const std::vector<P2>& ring;
  std::vector<std::size_t> edges;     // edge i runs from ring[i] to ring[i + 1] (cyclically)
  std::vector<std::size_t> vertices;
  bool all_edges = false;             // every edge of the ring meets the region
  RingNear(const std::vector<P2>& r, const Box2& region) : ring(r) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (region.meets(box_of(r[i], r[(i + 1) % r.size()]))) edges.push_back(i);
      if (region.holds(r[i])) vertices.push_back(i);
    }
    all_edges = edges.size() == r.size();
  }
  const P2& from(std::size_t e) const { return ring[e]; }
  const P2& to(std::size_t e) const { return ring[(e + 1) % ring.size()]; }
};

// Whether the segments cross at a point inside both: each one's ends strictly on either side of
// the other's line. Two edges that share an end cannot (an orientation with that end is
// COLLINEAR): they are answered by comparing coordinates, which is where most calls are, since
// a junction and a section share their border points exactly. An orientation that comes out
// exactly zero is CGAL's slow path (its floating-point filter cannot certify a zero, so it
// computes exactly); the orientations are also taken one at a time, and the first that settles
// the answer ends it.
bool properly_cross(const P2& a1, const P2& a2, const P2& b1, const P2& b2) {
  if (a1 == b1 || a1 == b2 || a2 == b1 || a2 == b2) return false;
  auto o1 = CGAL::orientation(a1, a2, b1);
  if (o1 == CGAL::COLLINEAR) return false;
  auto o2 = CGAL::orientation(a1, a2, b2);
  if (o2 == CGAL::COLLINEAR || o1 == o2) return false;
  auto o3 = CGAL::orientation(b1, b2, a1);
  if (o3 == CGAL::COLLINEAR) return false;
  auto o4 = CGAL::orientation(b1, b2, a2);
  return o4 != CGAL::COLLINEAR && o3 != o4;
}

// Whether u and w are the two ends of an edge of ring b (of its edges near the region: an edge
// of b along an edge of a lies in both boxes).
bool is_edge_of(const P2& u, const P2& w, const RingNear& b) {
  for (std::size_t e : b.edges) {
    const P2& s = b.from(e);
    const P2& t = b.to(e);
    if ((s == u && t == w) || (s == w && t == u)) return true;
  }
  return false;
}

// Where p lies against ring b: outside its box at once, on its boundary when it is one of b's
// vertices near the region (the rings share their border points exactly, and CGAL's test of a
// point on an edge is its slow exact path), else by CGAL's exact test.
CGAL::Bounded_side side_of(const P2& p, const RingNear& b, const Box2& b_box) {
  if (!b_box.holds(p)) return CGAL::ON_UNBOUNDED_SIDE;
  for (std::size_t k : b.vertices) {
    if (b.ring[k] == p) return CGAL::ON_BOUNDARY;
  }
  return CGAL::bounded_side_2(b.ring.begin(), b.ring.end(), p, Kernel());
}

// Does a point of `a`'s boundary lie strictly inside `b`? Each edge of `a` is cut at the vertices
// of `b` on it; between two cuts the edge is all inside `b`, all outside, or all on its boundary
// (no edge crosses properly: checked before), so its middle tells, unless the piece is an edge of
// `b` itself: then it lies on b's boundary, and its middle, rounded to doubles, need not (a curb
// arc shared by a junction and its sidewalk, whose chords' middles fell inside either by 1e-16).
// `on_boundary_only` is left true when every vertex and middle of `a` lies on `b`'s boundary.
// Only a's edges near the region can hold a point inside b; an edge away from it is not on b's
// boundary either.
bool boundary_enters(const RingNear& a, const RingNear& b, const Box2& b_box, bool& on_boundary_only) {
  if (!a.all_edges) on_boundary_only = false;
  std::vector<P2> cuts;
  for (std::size_t e : a.edges) {
    const P2& p = a.from(e);
    const P2& q = a.to(e);
    auto side = side_of(p, b, b_box);
    if (side == CGAL::ON_BOUNDED_SIDE) return true;
    if (side == CGAL::ON_UNBOUNDED_SIDE) on_boundary_only = false;
    cuts.assign({p, q});
    const Box2 edge_box = box_of(p, q);
    for (std::size_t k : b.vertices) {
      const P2& v = b.ring[k];
      if (edge_box.holds(v) && v != p && v != q && CGAL::orientation(p, q, v) == CGAL::COLLINEAR &&
          CGAL::collinear_are_strictly_ordered_along_line(p, v, q)) {
        cuts.push_back(v);
      }
    }
    if (cuts.size() > 2) {
      std::sort(cuts.begin(), cuts.end(), [&](const P2& u, const P2& w) { return CGAL::has_smaller_distance_to_point(p, u, w); });
    }
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      if (is_edge_of(cuts[k], cuts[k + 1], b)) continue;
      P2 middle = CGAL::midpoint(cuts[k], cuts[k + 1]);
      auto mside = side_of(middle, b, b_box);
      if (mside == CGAL::ON_BOUNDED_SIDE) return true;
      if (mside == CGAL::ON_UNBOUNDED_SIDE) on_boundary_only = false;
    }
  }
  return false;
}

}  // namespace

bool interiors_may_meet(const Polyline& ring_a, const Polyline& ring_b) {
  std::vector<P2> a = open_ring(ring_a), b = open_ring(ring_b);
  if (a.size() < 3 || b.size() < 3) return true;  // (not a polygon: let the overlay decide)
  const Box2 a_box = box_of(a), b_box = box_of(b);
  if (!a_box.meets(b_box)) return false;
  // Whatever the two share lies in both boxes.
  const Box2 region{std::max(a_box.xmin, b_box.xmin), std::max(a_box.ymin, b_box.ymin), std::min(a_box.xmax, b_box.xmax),
                    std::min(a_box.ymax, b_box.ymax)};
  const RingNear a_near(a, region), b_near(b, region);
  for (std::size_t i : a_near.edges) {
    const Box2 edge_box = box_of(a_near.from(i), a_near.to(i));
    for (std::size_t j : b_near.edges) {
      if (edge_box.meets(box_of(b_near.from(j), b_near.to(j))) &&
          properly_cross(a_near.from(i), a_near.to(i), b_near.from(j), b_near.to(j))) {
        return true;
      }
    }
  }
  bool a_on_b = true, b_on_a = true;
  if (boundary_enters(a_near, b_near, b_box, a_on_b) || boundary_enters(b_near, a_near, a_box, b_on_a)) return true;
  // Every point of one boundary on the other's: the same polygon (their interiors meet), or a
  // case this reasoning does not cover; either way, not "certainly apart".
  return a_on_b || b_on_a;
}

std::optional<double> touching_overlap_bound(const Polyline& fixed, const Polyline& moved, double snap) {
  std::vector<P2> f = open_ring(fixed), m = open_ring(moved);
  if (f.size() < 3 || m.size() < 3) return std::nullopt;
  const Box2 f_box = box_of(f);
  const Box2 near_f{f_box.xmin - snap, f_box.ymin - snap, f_box.xmax + snap, f_box.ymax + snap};
  std::vector<std::size_t> target_of(m.size(), f.size());  // f.size(): stays
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (!near_f.holds(m[i])) continue;
    double best = snap;
    for (std::size_t k = 0; k < f.size(); ++k) {
      double d = std::hypot(f[k].x() - m[i].x(), f[k].y() - m[i].y());
      if (d <= best) {
        best = d;
        target_of[i] = k;
      }
    }
    if (target_of[i] != f.size() && f[target_of[i]] == m[i]) target_of[i] = f.size();  // (already there)
  }
  // One after the other, each move changes the ring by at most the triangles its vertex sweeps
  // with its two neighbours (as moved so far).
  double swept = 0.0;
  bool any = false;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (target_of[i] == f.size()) continue;
    const P2 to = f[target_of[i]];
    const P2& prev = m[(i + m.size() - 1) % m.size()];
    const P2& next = m[(i + 1) % m.size()];
    auto triangle = [](const P2& a, const P2& b, const P2& c) {
      return 0.5 * std::abs((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
    };
    swept += triangle(prev, m[i], to) + triangle(m[i], to, next);
    m[i] = to;
    any = true;
  }
  if (any) {
    // Two vertices onto one point, or a fold: the moved ring says nothing about the real one.
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m[i] == m[(i + 1) % m.size()]) return std::nullopt;
    }
    if (!CGAL::is_simple_2(m.begin(), m.end(), Kernel())) return std::nullopt;
  }
  Polyline moved_ring;
  moved_ring.reserve(m.size());
  for (const P2& p : m) moved_ring.push_back({p.x(), p.y()});
  if (interiors_may_meet(fixed, moved_ring)) return std::nullopt;
  // (the triangles' areas in doubles: a relative error of a few ulps, doubled to be safe)
  return 2.0 * swept;
}

}  // namespace streetgen::core
