#include "core/streets/polyline.hpp"

#include <algorithm>
#include <limits>

namespace streetgen::core {

double length(const Polyline& line) {
  double total = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) total += distance(line[i - 1], line[i]);
  return total;
}

Point point_at(const Polyline& line, double s) {
  if (line.empty()) return {};
  if (s <= 0.0) return line.front();
  double walked = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    double seg = distance(line[i - 1], line[i]);
    if (walked + seg >= s && seg > 0.0) {
      double t = (s - walked) / seg;
      return line[i - 1] + t * (line[i] - line[i - 1]);
    }
    walked += seg;
  }
  return line.back();
}

Point tangent_at(const Polyline& line, double s) {
  double walked = 0.0;
  Point last{1.0, 0.0};
  for (std::size_t i = 1; i < line.size(); ++i) {
    double seg = distance(line[i - 1], line[i]);
    if (seg <= 0.0) continue;
    last = unit(line[i] - line[i - 1]);
    if (walked + seg > s) return last;
    walked += seg;
  }
  return last;
}

Polyline substring(const Polyline& line, double a, double b) {
  double total = length(line);
  a = std::clamp(a, 0.0, total);
  b = std::clamp(b, a, total);
  Polyline out;
  out.push_back(point_at(line, a));
  double walked = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    walked += distance(line[i - 1], line[i]);
    if (walked > a && walked < b) out.push_back(line[i]);
  }
  out.push_back(point_at(line, b));
  return out;
}

Polyline reversed(Polyline line) {
  std::reverse(line.begin(), line.end());
  return line;
}

Projection project(const Polyline& line, Point p) {
  Projection best;
  best.distance = std::numeric_limits<double>::infinity();
  if (line.empty()) return best;
  if (line.size() == 1) return {0.0, distance(line[0], p), line[0]};
  double walked = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    Point a = line[i - 1];
    Point d = line[i] - a;
    double seg2 = dot(d, d);
    double t = seg2 > 0.0 ? std::clamp(dot(p - a, d) / seg2, 0.0, 1.0) : 0.0;
    Point q = a + t * d;
    double dist = distance(p, q);
    double seg = std::sqrt(seg2);
    if (dist < best.distance) best = {walked + t * seg, dist, q};
    walked += seg;
  }
  return best;
}

double point_segment_distance(Point p, Point a, Point b) {
  Point d = b - a;
  double len2 = dot(d, d);
  double t = len2 > 0.0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return distance(p, a + t * d);
}

namespace {

bool segments_cross(Point a0, Point a1, Point b0, Point b1) {
  double d1 = cross(a1 - a0, b0 - a0), d2 = cross(a1 - a0, b1 - a0);
  double d3 = cross(b1 - b0, a0 - b0), d4 = cross(b1 - b0, a1 - b0);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}
}  // namespace

double polyline_distance(const Polyline& a, const Polyline& b) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    for (std::size_t j = 0; j + 1 < b.size(); ++j) {
      if (segments_cross(a[i], a[i + 1], b[j], b[j + 1])) return 0.0;
      best = std::min({best, point_segment_distance(a[i], b[j], b[j + 1]), point_segment_distance(a[i + 1], b[j], b[j + 1]),
                       point_segment_distance(b[j], a[i], a[i + 1]), point_segment_distance(b[j + 1], a[i], a[i + 1])});
    }
  }
  return best;
}

Polyline without_repeated_points(const Polyline& line, double eps) {
  Polyline out;
  for (const Point& p : line) {
    if (out.empty() || distance(out.back(), p) > eps) out.push_back(p);
  }
  return out;
}

}  // namespace streetgen::core
