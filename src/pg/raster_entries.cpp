// Road raster -> street graph: the raster crosses as its WKB (ST_AsBinary(raster), one bytea:
// the bytes are read in place, no per-pixel Datum), parameters as plain values
// (sql/90-raster.sql reads and checks the jsonb), edges out as rows for a model's axis table.
#include <cstdint>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/raster/raster_to_network.hpp"
#include "core/raster/wkb_raster.hpp"
#include "pg/array_args.hpp"
#include "pg/boundary.hpp"
#include "pg/owned_result.hpp"

extern "C" {
#include "utils/builtins.h"
}

using namespace streetgen;

namespace {

struct OutRow {
  std::int64_t id, from_node, to_node;
  core::Bytes geom;
};

constexpr int kArgs = 10;
constexpr int kColumns = 4;

}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_raster_to_network);
// (rast_wkb bytea, threshold float8, erode int4, dilate int4, min_block_area float8,
//  min_dead_end_length float8, smooth_iterations int4, simplify_tolerance float8, max_gap float8,
//  gap_angle float8)
//  -> SETOF (id int8, from_node int8, to_node int8, geom bytea)
Datum _streetgen_raster_to_network(PG_FUNCTION_ARGS) {
  // Phase 1.
  pg::require_argument_count(fcinfo, kArgs, "_streetgen_raster_to_network");
  static const char* const names[] = {"rast",           "threshold",           "erode",
                                      "dilate",         "min_block_area",      "min_dead_end_length",
                                      "smooth_iterations", "simplify_tolerance", "max_gap",
                                      "gap_angle"};
  for (int a = 0; a < kArgs; ++a) {
    if (PG_ARGISNULL(a)) pg::raise_null_argument(names[a]);
  }
  const pg::ByteView wkb = pg::byte_view(PG_GETARG_DATUM(0));
  const double threshold = PG_GETARG_FLOAT8(1);
  core::RasterNetworkParams params;
  params.erode = PG_GETARG_INT32(2);
  params.dilate = PG_GETARG_INT32(3);
  params.min_block_area = PG_GETARG_FLOAT8(4);
  params.min_dead_end_length = PG_GETARG_FLOAT8(5);
  params.smooth_iterations = PG_GETARG_INT32(6);
  params.simplify_tolerance = PG_GETARG_FLOAT8(7);
  params.max_gap = PG_GETARG_FLOAT8(8);
  params.gap_angle = PG_GETARG_FLOAT8(9);
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<std::vector<OutRow>>::create();

  // Phase 2.
  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    core::RoadRaster raster = core::read_wkb_raster(wkb.data, wkb.size, threshold);
    core::RasterNetwork net = core::raster_to_network(geos, raster, params);
    std::vector<OutRow> out;
    out.reserve(net.edges.size());
    for (const core::RasterEdge& e : net.edges) {
      out.push_back({e.id, e.from_node, e.to_node, core::write_ewkb_polyline(core::WkbType::line_string, e.line, raster.srid)});
    }
    rows.emplace(std::move(out));
  });
  pg::raise_if_failed(error);

  // Phase 3.
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (const OutRow& row : *rows) {
    Datum v[kColumns] = {Int64GetDatum(row.id), Int64GetDatum(row.from_node), Int64GetDatum(row.to_node),
                         PointerGetDatum(pg::to_bytea(row.geom))};
    bool null[kColumns] = {false, false, false, false};
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, v, null);
  }
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
