#include "core/streets/polygon_contact.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <algorithm>
#include <vector>

namespace streetgen::core {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = Kernel::Point_2;

std::vector<P2> open_ring(const Polyline& ring) {
  std::vector<P2> out;
  for (Point p : ring) out.emplace_back(p.x, p.y);
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

bool properly_cross(const P2& a1, const P2& a2, const P2& b1, const P2& b2) {
  auto o1 = CGAL::orientation(a1, a2, b1), o2 = CGAL::orientation(a1, a2, b2);
  auto o3 = CGAL::orientation(b1, b2, a1), o4 = CGAL::orientation(b1, b2, a2);
  return o1 != CGAL::COLLINEAR && o2 != CGAL::COLLINEAR && o1 != o2 && o3 != CGAL::COLLINEAR &&
         o4 != CGAL::COLLINEAR && o3 != o4;
}

// Whether u and w are the two ends of an edge of ring b.
bool is_edge_of(const P2& u, const P2& w, const std::vector<P2>& b) {
  for (std::size_t j = 0; j < b.size(); ++j) {
    const P2& s = b[j];
    const P2& t = b[(j + 1) % b.size()];
    if ((s == u && t == w) || (s == w && t == u)) return true;
  }
  return false;
}

// Does a point of `a`'s boundary lie strictly inside `b`? Each edge of `a` is cut at the vertices
// of `b` on it; between two cuts the edge is all inside `b`, all outside, or all on its boundary
// (no edge crosses properly: checked before), so its middle tells, unless the piece is an edge of
// `b` itself: then it lies on b's boundary, and its middle, rounded to doubles, need not (a curb
// arc shared by a junction and its sidewalk, whose chords' middles fell inside either by 1e-16).
// `on_boundary_only` is left true when every vertex and middle of `a` lies on `b`'s boundary.
bool boundary_enters(const std::vector<P2>& a, const std::vector<P2>& b, bool& on_boundary_only) {
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P2& p = a[i];
    const P2& q = a[(i + 1) % n];
    auto side = CGAL::bounded_side_2(b.begin(), b.end(), p, Kernel());
    if (side == CGAL::ON_BOUNDED_SIDE) return true;
    if (side == CGAL::ON_UNBOUNDED_SIDE) on_boundary_only = false;
    std::vector<P2> cuts{p, q};
    for (const P2& v : b) {
      if (v != p && v != q && CGAL::orientation(p, q, v) == CGAL::COLLINEAR && CGAL::collinear_are_strictly_ordered_along_line(p, v, q)) {
        cuts.push_back(v);
      }
    }
    std::sort(cuts.begin(), cuts.end(), [&](const P2& u, const P2& w) { return CGAL::has_smaller_distance_to_point(p, u, w); });
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      if (is_edge_of(cuts[k], cuts[k + 1], b)) continue;
      P2 middle = CGAL::midpoint(cuts[k], cuts[k + 1]);
      auto mside = CGAL::bounded_side_2(b.begin(), b.end(), middle, Kernel());
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
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (properly_cross(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
    }
  }
  bool a_on_b = true, b_on_a = true;
  if (boundary_enters(a, b, a_on_b) || boundary_enters(b, a, b_on_a)) return true;
  // Every point of one boundary on the other's: the same polygon (their interiors meet), or a
  // case this reasoning does not cover; either way, not "certainly apart".
  return a_on_b || b_on_a;
}

}  // namespace streetgen::core
