// CGAL translation unit (CGAL headers compile slowly: keep them here).
#include "core/streets/arc_centre.hpp"

#include <CGAL/Exact_circular_kernel_2.h>
#include <CGAL/intersections.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

#include "core/interrupts.hpp"

namespace streetgen::core {
namespace {

using Kernel = CGAL::Exact_circular_kernel_2;
using KPoint = Kernel::Point_2;
using KLine = Kernel::Line_2;
using KCircle = Kernel::Circle_2;
using ArcPoint = Kernel::Circular_arc_point_2;

// A piece of the locus {p : distance(p, polyline) = d} on one side of the polyline: the offset
// of a segment, or the circle around an interior vertex (where the offset has a gap).
struct Piece {
  bool is_circle;
  KLine line;      // offset segment's supporting line
  KCircle circle;  // circle around a vertex
};

KPoint exact(Point p) { return KPoint(p.x, p.y); }

// side = +1: left of the polyline, -1: right.
std::vector<Piece> locus_pieces(const Polyline& line, double d, int side) {
  std::vector<Piece> pieces;
  for (std::size_t i = 1; i < line.size(); ++i) {
    Point dir = unit(line[i] - line[i - 1]);
    if (norm(dir) == 0.0) continue;
    Point shift = (side * d) * left_normal(dir);
    Point p0 = line[i - 1] + shift;
    Point p1 = line[i] + shift;
    pieces.push_back({false, KLine(exact(p0), exact(p1)), KCircle()});
    if (i + 1 < line.size()) {
      pieces.push_back({true, KLine(), KCircle(exact(line[i]), Kernel::FT(d) * Kernel::FT(d))});
    }
  }
  return pieces;
}

template <class Variant>
void collect_arc_points(const std::vector<Variant>& hits, std::vector<Point>& out) {
  using Hit = std::pair<ArcPoint, unsigned>;
  for (const auto& hit : hits) {
    if (const Hit* h = boost::get<Hit>(&hit)) {
      out.push_back({CGAL::to_double(h->first.x()), CGAL::to_double(h->first.y())});
    }
  }
}

void intersect(const Piece& p, const Piece& q, std::vector<Point>& out) {
  if (!p.is_circle && !q.is_circle) {
    auto result = CGAL::intersection(p.line, q.line);
    if (result) {
      if (const KPoint* pt = boost::get<KPoint>(&*result)) {
        out.push_back({CGAL::to_double(pt->x()), CGAL::to_double(pt->y())});
      }
    }
  } else if (p.is_circle && q.is_circle) {
    std::vector<CGAL::CK2_Intersection_traits<Kernel, KCircle, KCircle>::type> hits;
    CGAL::intersection(p.circle, q.circle, std::back_inserter(hits));
    collect_arc_points(hits, out);
  } else {
    const KCircle& c = p.is_circle ? p.circle : q.circle;
    const KLine& l = p.is_circle ? q.line : p.line;
    std::vector<CGAL::CK2_Intersection_traits<Kernel, KCircle, KLine>::type> hits;
    CGAL::intersection(c, l, std::back_inserter(hits));
    collect_arc_points(hits, out);
  }
}

// True if p is at distance d from `line` (within eps) and on the requested side of the nearest
// part of it.
bool on_locus(const Polyline& line, Point p, double d, int side, double eps) {
  Projection pr = project(line, p);
  if (std::abs(pr.distance - d) > eps) return false;
  Point t = tangent_at(line, pr.abscissa);
  // At a vertex the foot is shared by two segments; the side is that of the offset direction.
  return side * cross(t, p - pr.point) > -eps * d;
}

// The same pieces in plain doubles: the fast path. Its candidates are checked exactly like the
// exact ones (on_locus), so it can miss a centre in a near-degenerate case (tangency, nearly
// parallel offsets) but not return a wrong one; a miss is retried with the exact kernel.
struct FastPiece {
  bool is_circle;
  Point p0, dir;  // line: point and unit direction
  Point centre;   // circle
  double radius;
};

std::vector<FastPiece> fast_pieces(const Polyline& line, double d, int side) {
  std::vector<FastPiece> pieces;
  for (std::size_t i = 1; i < line.size(); ++i) {
    Point dir = unit(line[i] - line[i - 1]);
    if (norm(dir) == 0.0) continue;
    pieces.push_back({false, line[i - 1] + (side * d) * left_normal(dir), dir, {}, 0.0});
    if (i + 1 < line.size()) pieces.push_back({true, {}, {}, line[i], d});
  }
  return pieces;
}

// Where doubles are not to be trusted the fast pass says so (`doubtful`), and a miss is then
// retried exactly: nearly parallel offsets, near-tangent circles.
constexpr double kDoubtful = 1e-9;

void fast_intersect(const FastPiece& p, const FastPiece& q, std::vector<Point>& out, bool& doubtful) {
  if (!p.is_circle && !q.is_circle) {
    double det = cross(p.dir, q.dir);
    if (std::abs(det) < kDoubtful) {
      doubtful = true;
      return;
    }
    double t = cross(q.p0 - p.p0, q.dir) / det;
    out.push_back(p.p0 + t * p.dir);
    return;
  }
  if (p.is_circle && q.is_circle) {
    Point d = q.centre - p.centre;
    double dist = norm(d);
    double scale = std::max(1.0, p.radius + q.radius);
    if (std::abs(dist - (p.radius + q.radius)) < kDoubtful * scale || std::abs(dist - std::abs(p.radius - q.radius)) < kDoubtful * scale) {
      doubtful = true;
    }
    if (dist == 0.0 || dist > p.radius + q.radius || dist < std::abs(p.radius - q.radius)) return;
    double along = (dist * dist + p.radius * p.radius - q.radius * q.radius) / (2 * dist);
    double h2 = p.radius * p.radius - along * along;
    double h = h2 > 0.0 ? std::sqrt(h2) : 0.0;
    Point u = (1.0 / dist) * d;
    Point base = p.centre + along * u;
    out.push_back(base + h * left_normal(u));
    out.push_back(base - h * left_normal(u));
    return;
  }
  const FastPiece& c = p.is_circle ? p : q;
  const FastPiece& l = p.is_circle ? q : p;
  double along = dot(c.centre - l.p0, l.dir);
  Point foot = l.p0 + along * l.dir;
  double h2 = c.radius * c.radius - dot(c.centre - foot, c.centre - foot);
  if (std::abs(h2) < kDoubtful * std::max(1.0, c.radius * c.radius)) doubtful = true;
  if (h2 < 0.0) return;
  double h = std::sqrt(h2);
  out.push_back(foot + h * l.dir);
  out.push_back(foot - h * l.dir);
}

template <class PieceT, class Intersect>
std::optional<Point> nearest_valid(const Polyline& a, double da, const Polyline& b, double db,
                                   const std::vector<PieceT>& pa, const std::vector<PieceT>& pb, Intersect intersect,
                                   bool& doubtful) {
  Point node = a.front();
  double eps = 1e-7 * std::max({1.0, da, db});
  std::optional<Point> best;
  double best_distance = std::numeric_limits<double>::infinity();
  std::vector<Point> candidates;
  InterruptPoller poller(256);
  for (const PieceT& p : pa) {
    for (const PieceT& q : pb) {
      poller.tick();
      candidates.clear();
      intersect(p, q, candidates, doubtful);
      for (Point c : candidates) {
        if (!std::isfinite(c.x) || !std::isfinite(c.y)) continue;
        double dn = distance(c, node);
        if (dn >= best_distance) continue;
        if (on_locus(a, c, da, +1, eps) && on_locus(b, c, db, -1, eps)) {
          best = c;
          best_distance = dn;
        } else if (on_locus(a, c, da, +1, 1e3 * eps) && on_locus(b, c, db, -1, 1e3 * eps)) {
          doubtful = true;  // rejected by a hair: the exact pass decides
        }
      }
    }
  }
  return best;
}

}  // namespace

namespace {
std::optional<Point> fast_pass(const Polyline& a, double da, const Polyline& b, double db, bool& doubtful) {
  if (a.size() < 2 || b.size() < 2) return std::nullopt;
  return nearest_valid(a, da, b, db, fast_pieces(a, da, +1), fast_pieces(b, db, -1), fast_intersect, doubtful);
}
}  // namespace

std::optional<Point> arc_centre_fast(const Polyline& a, double da, const Polyline& b, double db) {
  bool doubtful = false;
  return fast_pass(a, da, b, db, doubtful);
}

std::optional<Point> arc_centre(const Polyline& a, double da, const Polyline& b, double db) {
  bool doubtful = false;
  if (std::optional<Point> fast = fast_pass(a, da, b, db, doubtful)) return fast;
  if (!doubtful) return std::nullopt;
  return arc_centre_exact(a, da, b, db);
}

std::optional<Point> arc_centre_exact(const Polyline& a, double da, const Polyline& b, double db) {
  if (a.size() < 2 || b.size() < 2) return std::nullopt;
  std::vector<Piece> pa = locus_pieces(a, da, +1);
  std::vector<Piece> pb = locus_pieces(b, db, -1);
  bool unused = false;
  return nearest_valid(a, da, b, db, pa, pb,
                       [](const Piece& p, const Piece& q, std::vector<Point>& out, bool&) { intersect(p, q, out); },
                       unused);
}

}  // namespace streetgen::core
