// Phase-1 helper shared by the growth entries: a control raster (weights, direction, DEM) that
// SQL read with ST_DumpValues, checked and copied into plain palloc'd values, then into a core
// GridField in phase 2. Include after core headers: it includes PostgreSQL.
#pragma once

#include "core/raster/grid_field.hpp"
#include "pg/array_args.hpp"

namespace streetgen::pg {

// A raster read in SQL (ST_DumpValues): grid = [upper-left x, upper-left y, scale x, scale y,
// width, height, bands], values band-major then row-major, NULL for nodata (NaN here). Both
// arguments NULL: no raster.
struct GridArg {
  bool present = false;
  double grid[7] = {0, 0, 0, 0, 0, 0, 0};
  double* values = nullptr;
  int count = 0;
};

// Raises 22023 / 22004 / 42804 naming `name` for a malformed georeference or values.
GridArg grid_arg(FunctionCallInfo fcinfo, int grid_argno, int values_argno, const char* name);

// Phase 2 (no PostgreSQL call): the raster as a GridField; nothing when absent.
void to_field(const GridArg& a, core::GridField& f);

}  // namespace streetgen::pg
