// Plain 2D geometry for road axes: points, polylines, abscissas (curvilinear distance from the
// polyline's start). Double precision; robust predicates and exact constructions live in the
// CGAL translation unit (arc_centre.cpp).
#pragma once
#include "core/no_postgres.hpp"

#include <cmath>
#include <vector>

namespace streetgen::core {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

inline Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
inline Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
inline Point operator*(double k, Point a) { return {k * a.x, k * a.y}; }
inline double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }
inline double cross(Point a, Point b) { return a.x * b.y - a.y * b.x; }
inline double norm(Point a) { return std::sqrt(a.x * a.x + a.y * a.y); }  // metres: no overflow to guard against
inline double distance(Point a, Point b) { return norm(a - b); }
inline Point left_normal(Point unit) { return {-unit.y, unit.x}; }
inline Point unit(Point a) {
  double n = norm(a);
  return n > 0.0 ? Point{a.x / n, a.y / n} : Point{0.0, 0.0};
}

using Polyline = std::vector<Point>;

double length(const Polyline& line);

// The point at abscissa s (clamped to [0, length]).
Point point_at(const Polyline& line, double s);

// Unit tangent at abscissa s (of the segment holding s; at a vertex, the segment after it).
Point tangent_at(const Polyline& line, double s);

// The part of `line` between abscissas a <= b (clamped); at least two points.
Polyline substring(const Polyline& line, double a, double b);

Polyline reversed(Polyline line);

struct Projection {
  double abscissa = 0.0;
  double distance = 0.0;
  Point point;
};
// The closest point of `line` to p.
Projection project(const Polyline& line, Point p);

// Distance from p to the segment ab (a point when a == b).
double point_segment_distance(Point p, Point a, Point b);

// Smallest distance between two polylines.
double polyline_distance(const Polyline& a, const Polyline& b);

// Removes consecutive duplicate vertices (closer than eps).
Polyline without_repeated_points(const Polyline& line, double eps);

}  // namespace streetgen::core
