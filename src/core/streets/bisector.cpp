#include "core/streets/bisector.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
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
  // The same sites must give the same segments to the last bit, in every run: the split line is
  // noded with the overlap's boundary, and where it runs a hair from a vertex a last-bit change
  // decides how many faces the overlap splits into (on Paris two junctions' shapes changed from
  // run to run of one build). CGAL's dual() does not give that: its edge iterator reports an edge
  // from whichever of its two faces lies lower in memory, which sets the segment's direction and
  // so the clipped ends' rounding, and a face's circumcentre is constructed (inexactly) from its
  // vertices in the order the face happens to list them. So each circumcentre is built from its
  // face's vertices in xy order, each segment runs from its xy-smaller end, and the segments are
  // returned sorted.
  auto circumcentre = [](Delaunay::Face_handle f) {
    std::array<Kernel::Point_2, 3> p{f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()};
    std::sort(p.begin(), p.end());
    return point_of(CGAL::circumcenter(p[0], p[1], p[2]));
  };
  auto xy_less = [](Point p, Point q) { return p.x < q.x || (p.x == q.x && p.y < q.y); };
  const double inf = std::numeric_limits<double>::infinity();
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    Delaunay::Face_handle f = e->first;
    Delaunay::Vertex_handle u = f->vertex(Delaunay::cw(e->second));
    Delaunay::Vertex_handle v = f->vertex(Delaunay::ccw(e->second));
    if (u->info() == v->info()) continue;
    // The dual of a Delaunay edge: a segment between two circumcentres, a ray from one when the
    // edge is on the hull, or the two sites' bisector line when all sites lie on one line.
    if (dt.dimension() == 1) {
      Kernel::Point_2 p = u->point(), q = v->point();
      if (q < p) std::swap(p, q);
      Kernel::Line_2 line = CGAL::bisector(p, q);
      keep_clipped(point_of(line.point(0)), point_of(line.point(1)), -inf, inf, clip, out);
      continue;
    }
    Delaunay::Face_handle g = f->neighbor(e->second);
    if (!dt.is_infinite(f) && !dt.is_infinite(g)) {
      Point from = circumcentre(f), to = circumcentre(g);
      if (xy_less(to, from)) std::swap(from, to);
      keep_clipped(from, to, 0.0, 1.0, clip, out);
    } else {
      // On the hull: from the finite face's circumcentre, perpendicular to the edge, away from
      // the face (the edge taken counter-clockwise as the finite face sees it).
      Delaunay::Face_handle finite = dt.is_infinite(f) ? g : f;
      int k = dt.is_infinite(f) ? g->index(f) : e->second;
      Kernel::Point_2 p = finite->vertex(Delaunay::ccw(k))->point(), q = finite->vertex(Delaunay::cw(k))->point();
      Point source = circumcentre(finite);
      Point outward{q.y() - p.y(), p.x() - q.x()};  // the edge p -> q turned clockwise: out of a ccw face
      keep_clipped(source, {source.x + outward.x, source.y + outward.y}, 0.0, inf, clip, out);
    }
  }
  std::sort(out.begin(), out.end(), [&](const BisectorSegment& s, const BisectorSegment& t) {
    if (xy_less(s.from, t.from)) return true;
    if (xy_less(t.from, s.from)) return false;
    return xy_less(s.to, t.to);
  });
  return out;
}

}  // namespace streetgen::core
