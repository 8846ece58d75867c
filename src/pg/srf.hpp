// Set-returning functions' output. Include after core headers: it includes PostgreSQL.
#pragma once

#include "pg/postgres_headers.hpp"

namespace streetgen::pg {

// InitMaterializedSRF(fcinfo, 0), with a tuplestore that keeps at most `memory_kb` of rows in
// memory and writes the rest to its temporary file (InitMaterializedSRF's keeps work_mem, 4 MB by
// default). For the SRFs that emit a whole city while their C++ result is still held: rows kept
// in memory add to that peak, and once the tuplestore has gone to its file, the memory its rows
// took stays with the query's context (freed chunks of an AllocSet are not returned) to the
// statement's end.
void init_materialized_srf(FunctionCallInfo fcinfo, int memory_kb);

// What those SRFs keep in memory (kB).
constexpr int kSrfMemoryKb = 256;

}  // namespace streetgen::pg
