// The C++/PostgreSQL boundary, used by every entry point in three phases:
//   1. C side in: read and check arguments (raise_null_argument), palloc, SPI.
//   2. guarded_call(): the C++ work. noexcept; records any exception into a CallError, which is
//      plain data, so nothing is skipped when PostgreSQL later longjmps over this frame.
//   3. C side out: raise_if_failed() after every C++ object of phase 2 is gone, then emit.
// This header includes no PostgreSQL header, so C++-heavy files can include it first.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "core/error.hpp"
#include "core/geos_context.hpp"

namespace streetgen::pg {

struct CallError {
  bool failed;
  core::ErrorKind kind;
  char message[512];
  char detail[1024];
  char hint[512];
};

template <std::size_t N>
void copy_cstring(char (&dst)[N], const char* src) noexcept {
  std::strncpy(dst, src != nullptr ? src : "", N - 1);
  dst[N - 1] = '\0';
}

inline void record_error(CallError& error, core::ErrorKind kind, const char* message, const char* detail = "",
                         const char* hint = "") noexcept {
  error.failed = true;
  error.kind = kind;
  copy_cstring(error.message, message);
  copy_cstring(error.detail, detail);
  copy_cstring(error.hint, hint);
}

// Runs `body` and turns every exception into a CallError. Never throws, never longjmps: `body`
// must not call ereport/elog/palloc/SPI.
template <class Body>
void guarded_call(CallError& error, Body&& body) noexcept {
  error.failed = false;
  try {
    body();
  } catch (const core::Error& e) {
    record_error(error, e.kind(), e.what(), e.detail().c_str(), e.hint().c_str());
  } catch (const std::bad_alloc&) {
    record_error(error, core::ErrorKind::out_of_memory, "out of memory in streetgen");
  } catch (const std::exception& e) {
    record_error(error, core::ErrorKind::internal, "unexpected C++ exception in streetgen", e.what());
  } catch (...) {
    record_error(error, core::ErrorKind::internal, "unexpected C++ exception of unknown type in streetgen");
  }
}

// Raises `error` with the SQLSTATE of its kind (boundary.cpp holds the one table). For
// canceled, PostgreSQL's own interrupt is processed first so the user sees the real cause
// (57014 cancel or statement timeout, or a terminate). Returns only if nothing failed.
void raise_if_failed(const CallError& error);

// Raises 22004 naming the parameter; the phase-1 check for non-strict functions.
[[noreturn]] void raise_null_argument(const char* parameter);

// The backend's GEOS context, created on first use. Call only inside guarded_call (it may throw
// std::bad_alloc). Clears a stale GEOS interrupt request left over from an earlier statement.
core::GeosContext& backend_geos();

// From _PG_init: the interrupt probe for core loops and the GEOS interrupt callback.
void install_interrupt_hooks();

}  // namespace streetgen::pg
