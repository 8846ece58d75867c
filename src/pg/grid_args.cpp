#include "pg/grid_args.hpp"

#include <cmath>

extern "C" {
#include "catalog/pg_type.h"
#include "utils/array.h"
}

namespace streetgen::pg {

GridArg grid_arg(FunctionCallInfo fcinfo, int grid_argno, int values_argno, const char* name) {
  GridArg out;
  if (PG_ARGISNULL(grid_argno) && PG_ARGISNULL(values_argno)) return out;
  ArrayArg grid = array_arg(fcinfo, grid_argno, FLOAT8OID, name);
  if (grid.count != 7) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE),
                    errmsg("%s raster georeference must hold 7 numbers", name), errdetail("It holds %d.", grid.count)));
  }
  for (int i = 0; i < 7; ++i) {
    if (grid.nulls[i]) {
      ereport(ERROR, (errcode(ERRCODE_NULL_VALUE_NOT_ALLOWED), errmsg("%s raster georeference holds a null", name)));
    }
    out.grid[i] = DatumGetFloat8(grid.values[i]);
  }
  for (int i = 4; i < 7; ++i) {
    const double v = out.grid[i];
    if (!(v >= 0.0 && v <= 65535.0) || v != std::floor(v)) {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE),
                      errmsg("%s raster size must be whole numbers in [0, 65535]", name)));
    }
  }
  // The values as ST_DumpValues gives them: one band's height x width array, or several bands'
  // stacked (bands x height x width), passed as they are because flattening millions of cells in
  // SQL costs more than the growth; a flat array of the same length is read alike.
  ArrayArg values;
  if (!PG_ARGISNULL(values_argno)) {
    ArrayType* array = PG_GETARG_ARRAYTYPE_P(values_argno);
    if (ARR_ELEMTYPE(array) != FLOAT8OID) {
      ereport(ERROR, (errcode(ERRCODE_DATATYPE_MISMATCH), errmsg("%s raster values have the wrong element type", name)));
    }
    const int ndim = ARR_NDIM(array);
    const int* dims = ARR_DIMS(array);
    const int bands = static_cast<int>(out.grid[6]), height = static_cast<int>(out.grid[5]);
    const int width = static_cast<int>(out.grid[4]);
    const bool fits = ndim == 3   ? dims[0] == bands && dims[1] == height && dims[2] == width
                      : ndim == 2 ? bands == 1 && dims[0] == height && dims[1] == width
                                  : ndim <= 1;
    if (!fits) {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("%s raster values do not match its size", name),
                      errdetail("The values have %d dimension(s); the raster is %d band(s) of %d x %d cells.", ndim,
                                bands, width, height)));
    }
    deconstruct_array(array, FLOAT8OID, sizeof(float8), FLOAT8PASSBYVAL, TYPALIGN_DOUBLE, &values.values,
                      &values.nulls, &values.count);
  }
  out.present = true;
  out.count = values.count;
  out.values = static_cast<double*>(palloc(sizeof(double) * (values.count > 0 ? values.count : 1)));
  for (int i = 0; i < values.count; ++i) {
    out.values[i] = values.nulls[i] ? NAN : DatumGetFloat8(values.values[i]);
    // NaN stands for nodata in core: a NaN pixel that is not the band's nodata would silently
    // mean "no control", so it is refused here, where NULL and NaN still differ.
    if (!values.nulls[i] && std::isnan(out.values[i])) {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("%s raster holds NaN", name),
                      errdetail("Cell %d (band-major, row-major) is NaN and not the band's nodata value.", i + 1),
                      errhint("Make NaN cells nodata (ST_SetBandNoDataValue, ST_MapAlgebra) for no control there.")));
    }
  }
  if (values.values != nullptr) pfree(values.values);  // a raster can hold millions of cells
  if (values.nulls != nullptr) pfree(values.nulls);
  return out;
}

void to_field(const GridArg& a, core::GridField& f) {
  if (!a.present) return;
  f.origin_x = a.grid[0];
  f.origin_y = a.grid[1];
  f.scale_x = a.grid[2];
  f.scale_y = a.grid[3];
  f.width = static_cast<int>(a.grid[4]);
  f.height = static_cast<int>(a.grid[5]);
  f.bands = static_cast<int>(a.grid[6]);
  f.values.assign(a.values, a.values + a.count);
}


}  // namespace streetgen::pg
