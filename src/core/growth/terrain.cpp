#include "core/growth/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace streetgen::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap(double a) {  // to (-pi, pi]
  a = std::fmod(a, 2.0 * kPi);
  if (a <= -kPi) a += 2.0 * kPi;
  if (a > kPi) a -= 2.0 * kPi;
  return a;
}

Point direction(double angle) { return {std::cos(angle), std::sin(angle)}; }

// The intervals [t0, t1] (metres along u from p) of the line pieces in g, recursively.
void collect_intervals(GEOSContextHandle_t h, const GEOSGeometry* g, Point p, Point u,
                       std::vector<std::pair<double, double>>& out) {
  const int type = GEOSGeomTypeId_r(h, g);
  if (type == GEOS_LINESTRING || type == GEOS_LINEARRING) {
    const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(h, g);
    unsigned size = 0;
    if (seq == nullptr || GEOSCoordSeq_getSize_r(h, seq, &size) == 0 || size == 0) return;
    double lo = INFINITY, hi = -INFINITY;
    for (unsigned i = 0; i < size; ++i) {
      double x = 0.0, y = 0.0;
      GEOSCoordSeq_getXY_r(h, seq, i, &x, &y);
      const double t = dot(Point{x, y} - p, u);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    out.emplace_back(lo, hi);
    return;
  }
  if (type == GEOS_MULTILINESTRING || type == GEOS_GEOMETRYCOLLECTION) {
    const int n = GEOSGetNumGeometries_r(h, g);
    for (int i = 0; i < n; ++i) collect_intervals(h, GEOSGetGeometryN_r(h, g, i), p, u, out);
  }
  // Points: the ray grazes the water at a vertex; it does not enter it.
}

}  // namespace

double grade(const GridField& dem, Point a, Point b) {
  if (dem.empty()) return 0.0;
  const double len = distance(a, b);
  if (!(len > 0.0)) return 0.0;
  const double step = 0.5 * std::min(std::abs(dem.scale_x), std::abs(dem.scale_y));
  const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
  const double ds = len / n;
  double worst = 0.0;
  double prev = sample_bilinear(dem, 0, a);
  for (int i = 1; i <= n; ++i) {
    const double z = sample_bilinear(dem, 0, a + (static_cast<double>(i) / n) * (b - a));
    if (!std::isnan(z) && !std::isnan(prev)) worst = std::max(worst, std::abs(z - prev) / ds);
    prev = z;
  }
  return worst;
}

Point terrain_gradient(const GridField& dem, Point p) {
  auto derivative = [&](Point d, double h) {
    const double zp = sample_bilinear(dem, 0, p + d), zm = sample_bilinear(dem, 0, p - d);
    const double z0 = sample_bilinear(dem, 0, p);
    if (!std::isnan(zp) && !std::isnan(zm)) return (zp - zm) / (2.0 * h);
    if (!std::isnan(zp) && !std::isnan(z0)) return (zp - z0) / h;  // at the raster's edge or next to nodata
    if (!std::isnan(zm) && !std::isnan(z0)) return (z0 - zm) / h;
    return static_cast<double>(NAN);
  };
  if (dem.empty()) return {NAN, NAN};
  const double hx = std::abs(dem.scale_x), hy = std::abs(dem.scale_y);
  return {derivative({hx, 0.0}, hx), derivative({0.0, hy}, hy)};
}

double bend_to_contour(const GridField& dem, Point p, double angle, double length, double max_grade, double step,
                       const std::function<bool(double)>& allowed) {
  const Point g = terrain_gradient(dem, p);
  if (std::isnan(g.x) || std::isnan(g.y) || !(norm(g) > 0.0) || !(step > 0.0)) return NAN;
  double d = wrap(std::atan2(g.x, -g.y) - angle);  // (-gy, gx): along the contour
  if (std::abs(d) > 0.5 * kPi) d = wrap(d + kPi);   // the contour direction nearer to the street's
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(d) / step - 1e-9)));
  for (int k = 1; k <= n; ++k) {
    const double a = wrap(angle + d * k / n);
    if (allowed && !allowed(a)) continue;
    if (grade(dem, p, p + length * direction(a)) <= max_grade) return a;
  }
  return NAN;
}

WaterCrossing find_water_crossing(GeosContext& geos, const GEOSGeometry* water, Point p,
                                  const std::vector<double>& angles, double approach, double max_span, double landing,
                                  const std::function<bool(Point, Point)>& land) {
  WaterCrossing best;
  if (water == nullptr || !(max_span > 0.0) || !(landing > 0.0)) return best;
  GEOSContextHandle_t h = geos.handle();
  const double reach = approach + max_span + landing;
  const double setback = std::min(1.0, 0.5 * landing);  // bridge ends stand on land, this far from the water
  std::vector<std::pair<double, double>> pieces;
  for (double angle : angles) {
    const Point u = direction(angle);
    const Point q = p + reach * u;
    GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, 2, 2);
    if (seq == nullptr) geos.fail("coordinate sequence");
    GEOSCoordSeq_setXY_r(h, seq, 0, p.x, p.y);
    GEOSCoordSeq_setXY_r(h, seq, 1, q.x, q.y);
    GeomPtr ray = own(geos, GEOSGeom_createLineString_r(h, seq), "bridge ray");
    GeomPtr wet = own(geos, GEOSIntersection_r(h, ray.get(), water), "bridge ray and water");
    pieces.clear();
    collect_intervals(h, wet.get(), p, u, pieces);
    if (pieces.empty()) continue;
    std::sort(pieces.begin(), pieces.end());
    // Pieces that touch are one stretch of water (two water polygons side by side).
    std::size_t k = 1;
    double t0 = pieces[0].first, t1 = pieces[0].second;
    for (; k < pieces.size() && pieces[k].first <= t1 + 1e-6; ++k) t1 = std::max(t1, pieces[k].second);
    const double next = k < pieces.size() ? pieces[k].first : INFINITY;
    if (t0 > approach || t1 - t0 > max_span || t1 >= reach - 1e-9) continue;  // no water ahead, or the sea
    if (next - t1 < landing + setback) continue;                               // the far bank is too narrow
    if (!land(p + (t1 + setback) * u, p + (t1 + setback + landing) * u)) continue;
    if (!best.found || t1 - t0 < best.exit - best.entry - 1e-9) best = {true, angle, t0, t1, setback};
  }
  return best;
}

}  // namespace streetgen::core
