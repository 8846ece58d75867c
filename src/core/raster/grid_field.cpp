#include "core/raster/grid_field.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace streetgen::core {

namespace {

// p in continuous cell coordinates: the centre of cell (c, r) is (c, r).
bool to_cell(const GridField& g, Point p, double& u, double& v) {
  u = (p.x - g.origin_x) / g.scale_x - 0.5;
  v = (p.y - g.origin_y) / g.scale_y - 0.5;
  return u >= -0.5 && v >= -0.5 && u <= g.width - 0.5 && v <= g.height - 0.5;
}

int nearest_index(double u, int n) { return std::clamp(static_cast<int>(std::floor(u + 0.5)), 0, n - 1); }

// The four neighbours' (col, row, weight), edge cells repeated at the border.
template <typename F>
void for_neighbours(const GridField& g, double u, double v, F&& f) {
  const int c0 = static_cast<int>(std::floor(u)), r0 = static_cast<int>(std::floor(v));
  const double fu = u - c0, fv = v - r0;
  for (int dr = 0; dr < 2; ++dr) {
    for (int dc = 0; dc < 2; ++dc) {
      const double w = (dc ? fu : 1.0 - fu) * (dr ? fv : 1.0 - fv);
      if (w <= 0.0) continue;
      f(std::clamp(c0 + dc, 0, g.width - 1), std::clamp(r0 + dr, 0, g.height - 1), w);
    }
  }
}

}  // namespace

void GridField::check(const char* name) const {
  const std::string n = name;
  if (bands < 1 || width < 1 || height < 1) throw_invalid_argument(n + " raster is empty");
  if (values.size() != static_cast<std::size_t>(bands) * width * height) {
    throw_invalid_argument(n + " raster values do not match its size",
                           "There are " + std::to_string(values.size()) + " values for " + std::to_string(bands) +
                               " band(s) of " + std::to_string(width) + " x " + std::to_string(height) + " cells.");
  }
  if (!std::isfinite(origin_x) || !std::isfinite(origin_y) || !std::isfinite(scale_x) || !std::isfinite(scale_y) ||
      scale_x == 0.0 || scale_y == 0.0) {
    throw_invalid_argument(n + " raster has a degenerate georeference", "Its scale must be finite and non-zero.");
  }
}

double sample_nearest(const GridField& g, int band, Point p) {
  double u = 0.0, v = 0.0;
  if (g.empty() || !to_cell(g, p, u, v)) return NAN;
  return g.at(band, nearest_index(u, g.width), nearest_index(v, g.height));
}

double sample_bilinear(const GridField& g, int band, Point p) {
  double u = 0.0, v = 0.0;
  if (g.empty() || !to_cell(g, p, u, v)) return NAN;
  if (std::isnan(g.at(band, nearest_index(u, g.width), nearest_index(v, g.height)))) return NAN;
  double sum = 0.0, weight = 0.0;
  for_neighbours(g, u, v, [&](int c, int r, double w) {
    const double x = g.at(band, c, r);
    if (std::isnan(x)) return;
    sum += w * x;
    weight += w;
  });
  return weight > 0.0 ? sum / weight : NAN;
}

double sample_axial_bilinear(const GridField& g, int band, Point p, double to_radians) {
  double u = 0.0, v = 0.0;
  if (g.empty() || !to_cell(g, p, u, v)) return NAN;
  const double own = g.at(band, nearest_index(u, g.width), nearest_index(v, g.height));
  if (std::isnan(own)) return NAN;
  double cx = 0.0, cy = 0.0;
  for_neighbours(g, u, v, [&](int c, int r, double w) {
    const double a = g.at(band, c, r) * to_radians;
    if (std::isnan(a)) return;
    cx += w * std::cos(2.0 * a);
    cy += w * std::sin(2.0 * a);
  });
  if (std::hypot(cx, cy) < 1e-9) return own * to_radians;
  return 0.5 * std::atan2(cy, cx);
}

void check_weights(const GridField& g, const char* name) {
  g.check(name);
  for (double x : g.values) {
    if (std::isnan(x)) continue;
    if (!std::isfinite(x) || x < 0.0) {
      throw_invalid_argument(std::string(name) + " raster must hold finite weights >= 0",
                             "It holds " + std::to_string(x) + ".", "Nodata cells mean no control.");
    }
  }
}

void check_directions(const GridField& g, const char* name) {
  g.check(name);
  for (double x : g.values) {
    if (std::isinf(x)) throw_invalid_argument(std::string(name) + " raster must hold finite angles");
  }
}

bool overlaps(const GridField& g, double x0, double y0, double x1, double y1) {
  const double gx0 = std::min(g.origin_x, g.origin_x + g.scale_x * g.width);
  const double gx1 = std::max(g.origin_x, g.origin_x + g.scale_x * g.width);
  const double gy0 = std::min(g.origin_y, g.origin_y + g.scale_y * g.height);
  const double gy1 = std::max(g.origin_y, g.origin_y + g.scale_y * g.height);
  return gx0 < x1 && x0 < gx1 && gy0 < y1 && y0 < gy1;
}

}  // namespace streetgen::core
