#include "core/geos_context.hpp"

#include <cstring>
#include <new>

#include "core/error.hpp"

namespace streetgen::core {

GeosContext::GeosContext() : handle_(GEOS_init_r()) {
  if (handle_ == nullptr) throw std::bad_alloc();
  GEOSContext_setErrorMessageHandler_r(handle_, &GeosContext::on_error, this);
  // Notices (e.g. "Self-intersection at ...") are informative only; validity is checked explicitly.
  GEOSContext_setNoticeMessageHandler_r(handle_, nullptr, nullptr);
}

GeosContext::~GeosContext() { GEOS_finish_r(handle_); }

void GeosContext::on_error(const char* message, void* self) {
  // GEOS calls this from inside its C API, which must not see an exception: only buffer.
  try {
    static_cast<GeosContext*>(self)->error_.assign(message != nullptr ? message : "unknown GEOS error");
  } catch (...) {
    static_cast<GeosContext*>(self)->error_.clear();
  }
}

void GeosContext::fail(const char* operation) {
  std::string message = error_.empty() ? std::string("no message") : error_;
  error_.clear();
  // GEOS reports an honoured interrupt request as an ordinary error with this exception name.
  if (message.rfind("InterruptedException", 0) == 0) {
    throw Error(ErrorKind::canceled, std::string("GEOS ") + operation + " interrupted");
  }
  throw Error(ErrorKind::geometry_engine, std::string("GEOS ") + operation + " failed", "GEOS said: " + message + ".");
}

GeomPtr own(GeosContext& ctx, GEOSGeometry* geom, const char* operation) {
  if (geom == nullptr) ctx.fail(operation);
  return GeomPtr(geom, GeomDeleter{ctx.handle()});
}

GeomPtr make_collection(GeosContext& ctx, int type, std::vector<GeomPtr>& parts) {
  std::vector<GEOSGeometry*> raw;
  raw.reserve(parts.size());
  for (GeomPtr& p : parts) raw.push_back(p.get());
  GEOSGeometry* c = GEOSGeom_createCollection_r(ctx.handle(), type, raw.data(), static_cast<unsigned>(raw.size()));
  if (c == nullptr) {
    parts.clear();  // GEOS did not take them: the pointers still own them
    ctx.fail("collection");
  }
  for (GeomPtr& p : parts) p.release();  // owned by the collection now
  parts.clear();
  return GeomPtr(c, GeomDeleter{ctx.handle()});
}

void append_polygons(GeosContext& ctx, const GEOSGeometry* geom, std::vector<GeomPtr>& out) {
  GEOSContextHandle_t h = ctx.handle();
  int type = GEOSGeomTypeId_r(h, geom);
  if (type == GEOS_POLYGON) {
    if (GEOSisEmpty_r(h, geom) == 0) out.push_back(own(ctx, GEOSGeom_clone_r(h, geom), "clone"));
  } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
    int n = GEOSGetNumGeometries_r(h, geom);
    for (int i = 0; i < n; ++i) append_polygons(ctx, GEOSGetGeometryN_r(h, geom, i), out);
  }
}

}  // namespace streetgen::core
