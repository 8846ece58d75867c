#include "pg/boundary.hpp"

#include <geos_c.h>

#include "core/interrupts.hpp"
#include "pg/postgres_headers.hpp"

namespace streetgen::pg {
namespace {

// The one table from core error kinds to SQLSTATEs (conventions: errors).
struct KindSqlstate {
  core::ErrorKind kind;
  int sqlstate;
};
const KindSqlstate kSqlstates[] = {
    {core::ErrorKind::invalid_argument, ERRCODE_INVALID_PARAMETER_VALUE},      // 22023
    {core::ErrorKind::null_argument, ERRCODE_NULL_VALUE_NOT_ALLOWED},          // 22004
    {core::ErrorKind::bad_data, ERRCODE_DATA_EXCEPTION},                       // 22000
    {core::ErrorKind::geometry_engine, ERRCODE_EXTERNAL_ROUTINE_EXCEPTION},    // 38000
    {core::ErrorKind::out_of_memory, ERRCODE_OUT_OF_MEMORY},                   // 53200
    {core::ErrorKind::canceled, ERRCODE_QUERY_CANCELED},                       // 57014
    {core::ErrorKind::internal, ERRCODE_INTERNAL_ERROR},                       // XX000
};

int sqlstate_of(core::ErrorKind kind) {
  for (const auto& entry : kSqlstates) {
    if (entry.kind == kind) return entry.sqlstate;
  }
  return ERRCODE_INTERNAL_ERROR;
}

core::GeosContext* g_geos = nullptr;  // one per backend, lives as long as the process
GEOSInterruptCallback* g_previous_geos_callback = nullptr;

// Only cancel (user request or statement_timeout, both arrive as SIGINT) and terminate stop a
// computation. InterruptPending alone is not enough: it is also set for benign work such as
// catch-up or barrier signals, which CHECK_FOR_INTERRUPTS serves without raising anything.
bool interrupt_pending() noexcept { return QueryCancelPending || ProcDiePending; }

// GEOS calls this from inside its own loops. PostGIS requests GEOS interrupts only from its
// SIGINT handler; checking here also honours terminate. The previously registered callback (if
// any) is chained, not replaced.
void geos_interrupt_callback() {
  if (interrupt_pending()) GEOS_interruptRequest();
  if (g_previous_geos_callback != nullptr) g_previous_geos_callback();
}

}  // namespace

void raise_if_failed(const CallError& error) {
  if (!error.failed) return;
  if (error.kind == core::ErrorKind::canceled) {
    CHECK_FOR_INTERRUPTS();  // raises the real cause: cancel, statement timeout, terminate
  }
  ereport(ERROR, (errcode(sqlstate_of(error.kind)), errmsg_internal("%s", error.message),
                  error.detail[0] != '\0' ? errdetail_internal("%s", error.detail) : 0,
                  error.hint[0] != '\0' ? errhint("%s", error.hint) : 0));
}

void raise_null_argument(const char* parameter) {
  ereport(ERROR, (errcode(ERRCODE_NULL_VALUE_NOT_ALLOWED), errmsg("%s must not be null", parameter)));
  pg_unreachable();
}

core::GeosContext& backend_geos() {
  if (g_geos == nullptr) g_geos = new core::GeosContext();
  // GEOS keeps an interrupt request until some GEOS loop consumes it; one left over from a
  // statement that ended elsewhere must not cancel this one.
  if (!interrupt_pending()) GEOS_interruptCancel();
  g_geos->clear_error();
  return *g_geos;
}

void install_interrupt_hooks() {
  core::set_interrupt_probe(&interrupt_pending);
  g_previous_geos_callback = GEOS_interruptRegisterCallback(&geos_interrupt_callback);
}

}  // namespace streetgen::pg
