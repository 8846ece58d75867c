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

}  // namespace streetgen::pg
