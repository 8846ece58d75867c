// PostGIS rasters in their documented binary form (ST_AsBinary(raster) / ST_RastFromWKB,
// raster/doc/RFC2-WellKnownBinaryFormat in PostGIS): the georeference, and the single band
// thresholded into a road mask. This is how a raster crosses the boundary: one bytea, parsed
// here with no PostgreSQL or PostGIS header, so the same code runs in the unit tests.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/raster/binary_image.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

// Pixel (col, row) has its upper-left corner at
//   x = ip_x + scale_x * col + skew_x * row,  y = ip_y + skew_y * col + scale_y * row.
struct GeoTransform {
  double scale_x = 1.0, scale_y = -1.0, ip_x = 0.0, ip_y = 0.0, skew_x = 0.0, skew_y = 0.0;
  Point at(double col, double row) const {
    return {ip_x + scale_x * col + skew_x * row, ip_y + skew_y * col + scale_y * row};
  }
  // The world area of one pixel (|determinant|).
  double pixel_area() const;
};

enum class PixelType : int { b1 = 0, ui8 = 4, f32 = 10, f64 = 11 };

struct RoadRaster {
  GeoTransform transform;
  int srid = 0;
  PixelType pixel_type = PixelType::ui8;
  BinaryImage mask;  // value > threshold and not nodata (NaN is background)
};

constexpr double kMaxRasterPixels = 1e8;

// Reads a one-band WKB raster (either byte order). Throws invalid_argument for another band
// count, an out-of-database band, a pixel type other than 1BB, 8BUI, 32BF or 64BF, an empty
// raster, one of more than kMaxRasterPixels pixels, or a non-finite threshold; bad_data for
// truncated or inconsistent bytes.
RoadRaster read_wkb_raster(const std::uint8_t* data, std::size_t size, double threshold);

// The opposite direction, for tests and the benchmark: a one-band 8BUI raster without nodata.
std::vector<std::uint8_t> write_wkb_raster(const BinaryImage& image, const GeoTransform& transform, int srid);

}  // namespace streetgen::core
