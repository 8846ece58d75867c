// Geometry SRFs. Geometry arrives and leaves as EWKB bytea; the SQL wrappers convert.
#include <string>
#include <vector>

#include "core/ewkb.hpp"
#include "core/roadway_borders.hpp"
#include "pg/boundary.hpp"
#include "pg/owned_result.hpp"

using namespace streetgen;

namespace {
struct BorderRow {
  const char* side;
  core::Bytes ewkb;
};
}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_roadway_borders);
// (axis_ewkb bytea, roadway_width float8) -> SETOF (side text, border_ewkb bytea)
Datum _streetgen_roadway_borders(PG_FUNCTION_ARGS) {
  if (PG_ARGISNULL(0)) pg::raise_null_argument("axis");
  if (PG_ARGISNULL(1)) pg::raise_null_argument("roadway_width");
  bytea* axis = PG_GETARG_BYTEA_PP(0);
  double roadway_width = PG_GETARG_FLOAT8(1);
  const auto* axis_data = reinterpret_cast<const std::uint8_t*>(VARDATA_ANY(axis));
  std::size_t axis_size = VARSIZE_ANY_EXHDR(axis);
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<std::vector<BorderRow>>::create();

  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    core::SridGeometry input = core::read_ewkb(geos, axis_data, axis_size, "axis");
    std::vector<core::RoadwayBorder> borders = core::roadway_borders(geos, input.geom.get(), roadway_width);
    auto& out = rows.emplace();
    for (auto& border : borders) {
      out.push_back({core::side_name(border.side), core::write_ewkb(geos, border.line.get(), input.srid)});
    }
  });
  pg::raise_if_failed(error);

  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (const BorderRow& row : *rows) {
    Datum values[2] = {CStringGetTextDatum(row.side), PointerGetDatum(pg::to_bytea(row.ewkb))};
    bool nulls[2] = {false, false};
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, values, nulls);
  }
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
