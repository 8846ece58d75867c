// A raster sampled over space, for growth controls (a weight raster for blending, a direction
// field): the values of a PostGIS raster read in SQL (ST_DumpValues) and passed in as plain
// arrays, with the georeference of its upper-left corner and cell size. No skew (SQL rejects a
// skewed raster). NaN is nodata: "no control here".
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <vector>

#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct GridField {
  double origin_x = 0.0;   // upper-left corner of cell (0, 0) (ST_UpperLeftX)
  double origin_y = 0.0;   // (ST_UpperLeftY)
  double scale_x = 1.0;    // cell width, signed (ST_ScaleX, > 0 for north-up rasters)
  double scale_y = -1.0;   // cell height, signed (ST_ScaleY, < 0 for north-up rasters)
  int width = 0;
  int height = 0;
  int bands = 0;
  // bands x height x width, band-major then row-major from row 0 (ST_DumpValues' order); NaN = nodata.
  std::vector<double> values;

  bool empty() const { return bands == 0; }
  double at(int band, int col, int row) const {
    return values[(static_cast<std::size_t>(band) * height + row) * width + col];
  }
  // Throws invalid_argument when the sizes disagree, the scale is 0 or not finite, or the
  // georeference is not finite. Values are not checked (see check_weights, check_directions).
  void check(const char* name) const;
};

// Bilinear interpolation between the centres of the four cells around p, nodata cells left out
// and the others' weights renormalised; NaN when p is outside the raster, its own cell is nodata
// (for every band read), or every neighbour is. Edge cells act out to the raster's edge.
double sample_bilinear(const GridField& g, int band, Point p);

// The value of the cell holding p; NaN outside the raster or on nodata.
double sample_nearest(const GridField& g, int band, Point p);

// Axial (undirected) bilinear interpolation of angles: the mean of the doubled-angle unit vectors,
// halved, so 1° and 179° average to 0° (or 180°), not 90°. The values are angles in units of
// to_radians radians (1: radians; pi/180: degrees); the result is in radians, in the values'
// orientation. NaN as sample_bilinear, and the nearest cell's angle when the neighbours cancel out.
double sample_axial_bilinear(const GridField& g, int band, Point p, double to_radians = 1.0);

// A weight raster: values >= 0 and finite (NaN is nodata). Throws invalid_argument otherwise.
void check_weights(const GridField& g, const char* name);
// A direction raster: finite values (NaN is nodata). Throws invalid_argument otherwise.
void check_directions(const GridField& g, const char* name);

// Whether the raster's extent overlaps the box [x0, x1] x [y0, y1].
bool overlaps(const GridField& g, double x0, double y0, double x1, double y1);

}  // namespace streetgen::core
