#include "core/versions.hpp"
#include "pg/boundary.hpp"
#include "pg/postgres_headers.hpp"

using namespace streetgen;

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_version);
// (extension text, geos text, cgal text): what this backend has loaded.
Datum _streetgen_version(PG_FUNCTION_ARGS) {
  TupleDesc desc;
  if (get_call_result_type(fcinfo, nullptr, &desc) != TYPEFUNC_COMPOSITE) {
    ereport(ERROR, (errcode(ERRCODE_FEATURE_NOT_SUPPORTED), errmsg("_streetgen_version must return a record")));
  }
  desc = BlessTupleDesc(desc);

  pg::CallError error;
  char geos[128];
  char cgal[128];
  pg::guarded_call(error, [&] {
    pg::copy_cstring(geos, core::geos_runtime_version().c_str());
    pg::copy_cstring(cgal, core::cgal_version().c_str());
  });
  pg::raise_if_failed(error);

  Datum values[3] = {CStringGetTextDatum(STREETGEN_VERSION), CStringGetTextDatum(geos), CStringGetTextDatum(cgal)};
  bool nulls[3] = {false, false, false};
  PG_RETURN_DATUM(HeapTupleGetDatum(heap_form_tuple(desc, values, nulls)));
}

}  // extern "C"
