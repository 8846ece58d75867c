// Phase-1 helpers: PostgreSQL arrays into plain C arrays (palloc'd, so nothing C++ is alive
// when they raise). Include after core headers: it includes PostgreSQL.
#pragma once

#include <cstddef>
#include <cstdint>

#include "pg/postgres_headers.hpp"

namespace streetgen::pg {

// A one-dimensional array argument, deconstructed. `values`/`nulls` live in the current memory
// context. A NULL array counts as empty.
struct ArrayArg {
  Datum* values = nullptr;
  bool* nulls = nullptr;
  int count = 0;
};

ArrayArg array_arg(FunctionCallInfo fcinfo, int argno, Oid element_type, const char* parameter);

// Raises 55000 (with a hint to update the extension) unless the call has `expected` arguments: a
// library newer than the installed SQL would read arguments that are not there.
void require_argument_count(FunctionCallInfo fcinfo, int expected, const char* function);

// Raises 22023 naming the parameters when the two arrays differ in length.
void require_same_length(const ArrayArg& a, const char* a_name, const ArrayArg& b, const char* b_name);

// A bytea value read in place (detoasted into the current memory context when it must be).
struct ByteView {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};
inline ByteView byte_view(Datum d) {
  bytea* b = DatumGetByteaPP(d);
  return {reinterpret_cast<const std::uint8_t*>(VARDATA_ANY(b)), VARSIZE_ANY_EXHDR(b)};
}

// Interleaved x, y from two float8 array arguments of one length (palloc'd, never NULL); a NULL
// coordinate raises 22004 naming `what`. *count is the number of pairs.
double* xy_pairs(const ArrayArg& xs, const ArrayArg& ys, const char* what, int* count);

// The non-NULL values of a bytea array argument, read in place (palloc'd, never NULL); *count
// is how many there are.
ByteView* byte_views(const ArrayArg& arg, int* count);

}  // namespace streetgen::pg
