#include "pg/boundary.hpp"  // (first: core headers before PostgreSQL)
#include "pg/array_args.hpp"

extern "C" {
#include "catalog/pg_type.h"
#include "utils/array.h"
#include "utils/lsyscache.h"
}

namespace streetgen::pg {

void require_argument_count(FunctionCallInfo fcinfo, int expected, const char* function) {
  if (PG_NARGS() != expected) {
    ereport(ERROR, (errcode(ERRCODE_OBJECT_NOT_IN_PREREQUISITE_STATE),
                    errmsg("%s expects %d arguments, got %d", function, expected, PG_NARGS()),
                    errhint("Run ALTER EXTENSION streetgen UPDATE, or re-create the extension.")));
  }
}

ArrayArg array_arg(FunctionCallInfo fcinfo, int argno, Oid element_type, const char* parameter) {
  ArrayArg out;
  if (PG_ARGISNULL(argno)) return out;
  ArrayType* array = PG_GETARG_ARRAYTYPE_P(argno);
  if (ARR_NDIM(array) > 1) {
    ereport(ERROR, (errcode(ERRCODE_ARRAY_SUBSCRIPT_ERROR), errmsg("%s must be a one-dimensional array", parameter)));
  }
  if (ARR_ELEMTYPE(array) != element_type) {
    ereport(ERROR, (errcode(ERRCODE_DATATYPE_MISMATCH), errmsg("%s has the wrong element type", parameter)));
  }
  int16 typlen;
  bool typbyval;
  char typalign;
  get_typlenbyvalalign(element_type, &typlen, &typbyval, &typalign);
  deconstruct_array(array, element_type, typlen, typbyval, typalign, &out.values, &out.nulls, &out.count);
  return out;
}

void require_same_length(const ArrayArg& a, const char* a_name, const ArrayArg& b, const char* b_name) {
  if (a.count != b.count) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE),
                    errmsg("%s and %s must have the same length", a_name, b_name),
                    errdetail("%s has %d elements, %s has %d.", a_name, a.count, b_name, b.count)));
  }
}

double* xy_pairs(const ArrayArg& xs, const ArrayArg& ys, const char* what, int* count) {
  auto* xy = static_cast<double*>(palloc0(sizeof(double) * 2 * (xs.count > 0 ? xs.count : 1)));
  for (int i = 0; i < xs.count; ++i) {
    if (xs.nulls[i] || ys.nulls[i]) raise_null_argument(what);
    xy[2 * i] = DatumGetFloat8(xs.values[i]);
    xy[2 * i + 1] = DatumGetFloat8(ys.values[i]);
  }
  *count = xs.count;
  return xy;
}

ByteView* byte_views(const ArrayArg& arg, int* count) {
  auto* views = static_cast<ByteView*>(palloc0(sizeof(ByteView) * (arg.count > 0 ? arg.count : 1)));
  *count = 0;
  for (int i = 0; i < arg.count; ++i) {
    if (!arg.nulls[i]) views[(*count)++] = byte_view(arg.values[i]);
  }
  return views;
}

}  // namespace streetgen::pg
