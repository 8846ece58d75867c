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

}  // namespace streetgen::core
