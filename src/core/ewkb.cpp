#include "core/ewkb.hpp"

#include <memory>
#include <string>

#include "core/error.hpp"

namespace streetgen::core {
namespace {

struct ReaderDeleter {
  GEOSContextHandle_t handle;
  void operator()(GEOSWKBReader* r) const noexcept { GEOSWKBReader_destroy_r(handle, r); }
};
struct WriterDeleter {
  GEOSContextHandle_t handle;
  void operator()(GEOSWKBWriter* w) const noexcept { GEOSWKBWriter_destroy_r(handle, w); }
};
struct BufferDeleter {
  GEOSContextHandle_t handle;
  void operator()(unsigned char* b) const noexcept { GEOSFree_r(handle, b); }
};

}  // namespace

SridGeometry read_ewkb(GeosContext& ctx, const std::uint8_t* data, std::size_t size, const char* parameter) {
  std::unique_ptr<GEOSWKBReader, ReaderDeleter> reader(GEOSWKBReader_create_r(ctx.handle()),
                                                       ReaderDeleter{ctx.handle()});
  if (!reader) ctx.fail("WKB reader creation");
  GEOSGeometry* raw = GEOSWKBReader_read_r(ctx.handle(), reader.get(), data, size);
  if (raw == nullptr) {
    std::string why = ctx.last_error();
    ctx.clear_error();
    throw Error(ErrorKind::bad_data, std::string(parameter) + " is not valid EWKB", "GEOS said: " + why + ".");
  }
  SridGeometry out{GeomPtr(raw, GeomDeleter{ctx.handle()}), 0};
  out.srid = GEOSGetSRID_r(ctx.handle(), raw);
  return out;
}

Bytes write_ewkb(GeosContext& ctx, GEOSGeometry* geom, int srid) {
  std::unique_ptr<GEOSWKBWriter, WriterDeleter> writer(GEOSWKBWriter_create_r(ctx.handle()),
                                                       WriterDeleter{ctx.handle()});
  if (!writer) ctx.fail("WKB writer creation");
  GEOSWKBWriter_setOutputDimension_r(ctx.handle(), writer.get(), 2);
  GEOSWKBWriter_setByteOrder_r(ctx.handle(), writer.get(), GEOS_WKB_NDR);
  GEOSWKBWriter_setIncludeSRID_r(ctx.handle(), writer.get(), srid != 0 ? 1 : 0);
  GEOSSetSRID_r(ctx.handle(), geom, srid);
  std::size_t size = 0;
  std::unique_ptr<unsigned char, BufferDeleter> buffer(GEOSWKBWriter_write_r(ctx.handle(), writer.get(), geom, &size),
                                                       BufferDeleter{ctx.handle()});
  if (!buffer) ctx.fail("WKB writing");
  return Bytes(buffer.get(), buffer.get() + size);
}

Bytes write_ewkb_coordinates(WkbType type, const double* xy, std::size_t point_count, int srid) {
  Bytes out;
  out.reserve(1 + 4 + 4 + 4 + 2 * point_count * sizeof(double));  // (byte order, type, SRID, count, points)
  auto put = [&out](const void* data, std::size_t n) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out.insert(out.end(), bytes, bytes + n);
  };
  static_assert(sizeof(double) == 8, "IEEE doubles expected");
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "write_ewkb_coordinates writes the host's byte order and marks it little-endian"
#endif
  std::uint8_t order = 1;
  std::uint32_t code = static_cast<std::uint32_t>(type) | (srid != 0 ? 0x20000000u : 0u);
  put(&order, 1);
  put(&code, 4);
  if (srid != 0) {
    std::uint32_t s = static_cast<std::uint32_t>(srid);
    put(&s, 4);
  }
  if (type != WkbType::point) {
    std::uint32_t n = static_cast<std::uint32_t>(point_count);
    put(&n, 4);
  }
  put(xy, 2 * point_count * sizeof(double));
  return out;
}

Bytes write_ewkb_polyline(WkbType type, const Polyline& line, int srid) {
  std::vector<double> xy;
  xy.reserve(line.size() * 2);
  for (const Point& p : line) {
    xy.push_back(p.x);
    xy.push_back(p.y);
  }
  return write_ewkb_coordinates(type, xy.data(), line.size(), srid);
}

}  // namespace streetgen::core
