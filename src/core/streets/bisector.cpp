#include "core/streets/bisector.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace streetgen::core {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<bool, Kernel>;  // info: a site of `a`
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;

// The part of p(t) = from + t (to - from), t in [t0, t1], inside the box (Liang-Barsky), kept
// when it has a length. Plain doubles: CGAL's intersection of a zero-length segment with a box
// divides 0 by 0 (two Delaunay faces on one circle share their circumcentre), and a NaN reaching
// its exact predicates raises SIGFPE in GMP.
void keep_clipped(Point from, Point to, double t0, double t1, const Box& box, std::vector<BisectorSegment>& out) {
  const double dx = to.x - from.x, dy = to.y - from.y;
  if (!std::isfinite(dx) || !std::isfinite(dy) || (dx == 0.0 && dy == 0.0)) return;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {from.x - box.xmin, box.xmax - from.x, from.y - box.ymin, box.ymax - from.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return;  // parallel to this side and outside it
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  if (!(t0 < t1)) return;
  out.push_back({{from.x + t0 * dx, from.y + t0 * dy}, {from.x + t1 * dx, from.y + t1 * dy}});
}

Point point_of(const Kernel::Point_2& p) { return {p.x(), p.y()}; }

}  // namespace

std::vector<BisectorSegment> bisector_segments(const std::vector<Point>& a, const std::vector<Point>& b, const Box& clip) {
  std::vector<BisectorSegment> out;
  if (a.empty() || b.empty()) return out;
  std::vector<std::pair<Kernel::Point_2, bool>> sites;
  sites.reserve(a.size() + b.size());
  auto finite = [](Point p) { return std::isfinite(p.x) && std::isfinite(p.y); };
  for (Point p : a) {
    if (finite(p)) sites.emplace_back(Kernel::Point_2(p.x, p.y), true);
  }
  for (Point p : b) {
    if (finite(p)) sites.emplace_back(Kernel::Point_2(p.x, p.y), false);
  }
  // One site per point, `a`'s where both have it (true sorts after false: keep the last).
  std::sort(sites.begin(), sites.end());
  std::vector<std::pair<Kernel::Point_2, bool>> unique_sites;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (i + 1 < sites.size() && sites[i + 1].first == sites[i].first) continue;
    unique_sites.push_back(sites[i]);
  }
  Delaunay dt;
  dt.insert(unique_sites.begin(), unique_sites.end());
  if (dt.dimension() < 1) return out;  // (one point, in both sets: nothing is nearer to `b`)
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    Delaunay::Vertex_handle u = e->first->vertex(Delaunay::cw(e->second));
    Delaunay::Vertex_handle v = e->first->vertex(Delaunay::ccw(e->second));
    if (u->info() == v->info()) continue;
    // The dual of a Delaunay edge: a segment between two circumcentres, a ray from one when the
    // edge is on the hull, or the two sites' bisector line when all sites lie on one line.
    CGAL::Object dual = dt.dual(e);
    const double inf = std::numeric_limits<double>::infinity();
    if (const auto* s = CGAL::object_cast<Kernel::Segment_2>(&dual)) {
      keep_clipped(point_of(s->source()), point_of(s->target()), 0.0, 1.0, clip, out);
    } else if (const auto* r = CGAL::object_cast<Kernel::Ray_2>(&dual)) {
      keep_clipped(point_of(r->source()), point_of(r->point(1)), 0.0, inf, clip, out);
    } else if (const auto* l = CGAL::object_cast<Kernel::Line_2>(&dual)) {
      keep_clipped(point_of(l->point(0)), point_of(l->point(1)), -inf, inf, clip, out);
    }
  }
  return out;
}

}  // namespace streetgen::core
