// A GEOS reentrant-API context whose error handler writes into a buffer instead of printing:
// after a GEOS call fails, fail() turns the buffered message into a core::Error. The boundary
// keeps one context per backend (GEOS contexts are cheap but not free, and a backend is
// single-threaded).
#pragma once
#include "core/no_postgres.hpp"

#include <geos_c.h>

#include <memory>
#include <string>
#include <vector>

namespace streetgen::core {

class GeosContext {
 public:
  GeosContext();
  ~GeosContext();
  GeosContext(const GeosContext&) = delete;
  GeosContext& operator=(const GeosContext&) = delete;

  GEOSContextHandle_t handle() const noexcept { return handle_; }

  // Throws the buffered GEOS error of `operation` (ErrorKind::canceled if GEOS was interrupted,
  // geometry_engine otherwise) and clears the buffer.
  [[noreturn]] void fail(const char* operation);

  // Forgets a buffered error (before a call whose failure is expected and handled).
  void clear_error() noexcept { error_.clear(); }
  const std::string& last_error() const noexcept { return error_; }

 private:
  static void on_error(const char* message, void* self);
  GEOSContextHandle_t handle_;
  std::string error_;
};

struct GeomDeleter {
  GEOSContextHandle_t handle = nullptr;
  void operator()(GEOSGeometry* geom) const noexcept {
    if (geom != nullptr) GEOSGeom_destroy_r(handle, geom);
  }
};
using GeomPtr = std::unique_ptr<GEOSGeometry, GeomDeleter>;

// Takes ownership of a GEOS result; a null result means GEOS failed and throws via ctx.fail().
GeomPtr own(GeosContext& ctx, GEOSGeometry* geom, const char* operation);

// A new collection of `type` (GEOS_MULTIPOLYGON, GEOS_GEOMETRYCOLLECTION, ...) that takes the
// geometries of `parts` and leaves `parts` empty; on failure the parts are freed and it throws.
GeomPtr make_collection(GeosContext& ctx, int type, std::vector<GeomPtr>& parts);

// Appends clones of the non-empty polygons of `geom`, recursively through collections: what
// ST_CollectionExtract(geom, 3) keeps, one polygon per entry.
void append_polygons(GeosContext& ctx, const GEOSGeometry* geom, std::vector<GeomPtr>& out);

}  // namespace streetgen::core
