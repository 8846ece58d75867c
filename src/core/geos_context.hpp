// A GEOS reentrant-API context whose error handler writes into a buffer instead of printing:
// after a GEOS call fails, fail() turns the buffered message into a core::Error. The boundary
// keeps one context per backend (GEOS contexts are cheap but not free, and a backend is
// single-threaded).
#pragma once
#include "core/no_postgres.hpp"

#include <geos_c.h>

#include <memory>
#include <string>

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

}  // namespace streetgen::core
