#include "pg/boundary.hpp"  // (first: core headers before PostgreSQL)
#include "pg/srf.hpp"

namespace streetgen::pg {

void init_materialized_srf(FunctionCallInfo fcinfo, int memory_kb) {
  InitMaterializedSRF(fcinfo, 0);  // (checks that the caller takes a tuplestore, and the row type)
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  MemoryContext caller_context = MemoryContextSwitchTo(rsinfo->econtext->ecxt_per_query_memory);
  tuplestore_end(rsinfo->setResult);
  rsinfo->setResult = tuplestore_begin_heap((rsinfo->allowedModes & SFRM_Materialize_Random) != 0, false, memory_kb);
  MemoryContextSwitchTo(caller_context);
}

}  // namespace streetgen::pg
