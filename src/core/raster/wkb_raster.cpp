#include "core/raster/wkb_raster.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include "core/error.hpp"

namespace streetgen::core {

double GeoTransform::pixel_area() const { return std::fabs(scale_x * scale_y - skew_x * skew_y); }

namespace {

[[noreturn]] void truncated(const char* what) {
  throw Error(ErrorKind::bad_data, "rast is not a valid WKB raster", std::string("It ends inside the ") + what + ".");
}

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  void need(std::size_t n, const char* what) const {
    if (size_ - pos_ < n) truncated(what);
  }
  template <class T>
  T read(const char* what) {
    need(sizeof(T), what);
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (swap_) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    T v;
    std::memcpy(&v, bytes, sizeof(T));
    return v;
  }
  void set_swap(bool swap) { swap_ = swap; }
  bool swap() const { return swap_; }
  const std::uint8_t* here() const { return data_ + pos_; }
  void skip(std::size_t n, const char* what) {
    need(n, what);
    pos_ += n;
  }
  std::size_t left() const { return size_ - pos_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  bool swap_ = false;
};

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

const char* pixel_type_name(int code) {
  static const char* const names[] = {"1BB",  "2BUI",  "4BUI", "8BSI", "8BUI", "16BSI",
                                      "16BUI", "32BSI", "32BUI", "?",   "32BF", "64BF"};
  return code >= 0 && code < 12 ? names[code] : "unknown";
}

template <class T>
void threshold_into(Reader& in, BinaryImage& mask, double threshold, bool has_nodata, double nodata) {
  const std::size_t n = mask.pixels.size();
  in.need(n * sizeof(T), "pixel data");
  const std::uint8_t* p = in.here();
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, p + i * sizeof(T), sizeof(T));
    if (in.swap() && sizeof(T) > 1) {
      std::uint8_t b[sizeof(T)];
      std::memcpy(b, &v, sizeof(T));
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
      std::memcpy(&v, b, sizeof(T));
    }
    const double d = static_cast<double>(v);
    // NaN compares false: background.
    mask.pixels[i] = d > threshold && !(has_nodata && d == nodata);
  }
  in.skip(n * sizeof(T), "pixel data");
}

}  // namespace

RoadRaster read_wkb_raster(const std::uint8_t* data, std::size_t size, double threshold) {
  if (!std::isfinite(threshold)) throw_invalid_argument("threshold must be a finite number");
  Reader in(data, size);
  std::uint8_t order = in.read<std::uint8_t>("header");
  if (order > 1) {
    throw Error(ErrorKind::bad_data, "rast is not a valid WKB raster", "Its byte order flag is not 0 or 1.");
  }
  in.set_swap((order == 1) != host_is_little_endian());
  std::uint16_t version = in.read<std::uint16_t>("header");
  if (version != 0) {
    throw Error(ErrorKind::bad_data, "rast is not a valid WKB raster",
                "Its format version is " + std::to_string(version) + ", not 0.");
  }
  std::uint16_t bands = in.read<std::uint16_t>("header");
  RoadRaster out;
  GeoTransform& t = out.transform;
  t.scale_x = in.read<double>("header");
  t.scale_y = in.read<double>("header");
  t.ip_x = in.read<double>("header");
  t.ip_y = in.read<double>("header");
  t.skew_x = in.read<double>("header");
  t.skew_y = in.read<double>("header");
  out.srid = in.read<std::int32_t>("header");
  int width = in.read<std::uint16_t>("header");
  int height = in.read<std::uint16_t>("header");
  if (width == 0 || height == 0) {
    throw_invalid_argument("rast is empty",
                           "It has " + std::to_string(width) + " x " + std::to_string(height) + " pixels.");
  }
  // About 10 bytes of working memory per pixel (mask, cleaned copy, padded buffers, skeleton
  // index): 100 million pixels is about 1 GB, a 30 km square at 3 m.
  if (static_cast<double>(width) * height > kMaxRasterPixels) {
    throw_invalid_argument("rast has too many pixels",
                           "It has " + std::to_string(width) + " x " + std::to_string(height) + " pixels, more than " +
                               std::to_string(static_cast<long long>(kMaxRasterPixels)) + ".",
                           "Trace it in tiles (ST_Tile) that overlap by a few road widths.");
  }
  if (bands != 1) {
    throw_invalid_argument("rast must have exactly one band", "It has " + std::to_string(bands) + ".",
                           "Pick the road band with ST_Band(rast, n).");
  }
  const double numbers[] = {t.scale_x, t.scale_y, t.ip_x, t.ip_y, t.skew_x, t.skew_y};
  for (double v : numbers) {
    if (!std::isfinite(v)) throw Error(ErrorKind::bad_data, "rast has a non-finite georeference");
  }
  if (t.pixel_area() == 0.0) throw_invalid_argument("rast has pixels of zero area", "Its scale or skew is degenerate.");
  std::uint8_t flags = in.read<std::uint8_t>("band header");
  int type = flags & 0x0F;
  if (flags & 0x80) {
    throw_invalid_argument("rast must be an in-database raster", "Its band is stored out of the database.");
  }
  if (type != 0 && type != 4 && type != 10 && type != 11) {
    throw_invalid_argument(std::string("rast must have pixel type 8BUI, 32BF, 64BF or 1BB"),
                           std::string("Its band has pixel type ") + pixel_type_name(type) + ".",
                           "Convert it with ST_Reclass or ST_MapAlgebra.");
  }
  out.pixel_type = static_cast<PixelType>(type);
  const bool has_nodata = (flags & 0x40) != 0;
  const bool all_nodata = (flags & 0x20) != 0;
  out.mask = BinaryImage(width, height);
  double nodata = 0.0;
  switch (out.pixel_type) {
    case PixelType::b1:
    case PixelType::ui8:
      nodata = in.read<std::uint8_t>("nodata value");
      threshold_into<std::uint8_t>(in, out.mask, threshold, has_nodata, nodata);
      break;
    case PixelType::f32:
      nodata = in.read<float>("nodata value");
      threshold_into<float>(in, out.mask, threshold, has_nodata, nodata);
      break;
    case PixelType::f64:
      nodata = in.read<double>("nodata value");
      threshold_into<double>(in, out.mask, threshold, has_nodata, nodata);
      break;
  }
  if (all_nodata) std::fill(out.mask.pixels.begin(), out.mask.pixels.end(), 0);
  if (in.left() != 0) {
    throw Error(ErrorKind::bad_data, "rast is not a valid WKB raster",
                std::to_string(in.left()) + " bytes follow the band.");
  }
  return out;
}

std::vector<std::uint8_t> write_wkb_raster(const BinaryImage& image, const GeoTransform& t, int srid) {
  std::vector<std::uint8_t> out;
  auto put = [&out](const auto& v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), b, b + sizeof(v));
  };
  put(static_cast<std::uint8_t>(host_is_little_endian() ? 1 : 0));
  put(static_cast<std::uint16_t>(0));
  put(static_cast<std::uint16_t>(1));
  for (double v : {t.scale_x, t.scale_y, t.ip_x, t.ip_y, t.skew_x, t.skew_y}) put(v);
  put(static_cast<std::int32_t>(srid));
  put(static_cast<std::uint16_t>(image.width));
  put(static_cast<std::uint16_t>(image.height));
  put(static_cast<std::uint8_t>(4));  // 8BUI, no nodata
  put(static_cast<std::uint8_t>(0));  // the (unused) nodata value
  out.insert(out.end(), image.pixels.begin(), image.pixels.end());
  return out;
}

}  // namespace streetgen::core
