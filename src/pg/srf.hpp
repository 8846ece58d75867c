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

// The size of a run from which those SRFs hand the heap's free pages back to the system
// (malloc_trim), so that the peak of what comes next does not stack on them: a whole city's, not
// an edit's local recompute, where the trim frees little and still makes a madvise call per free
// run of pages of the whole heap. An edit's recompute takes tens of axes (Paris 11e, one axis
// moved: 121) and tens of block faces (37); whole cities have about 0.4 faces an axis (Paris 11e
// 544 axes and 233 faces, Reisterstown 4,560 and 1,640).
constexpr int kTrimMinAxes = 500;
constexpr int kTrimMinFaces = 200;

}  // namespace streetgen::pg
