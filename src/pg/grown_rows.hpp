// What grow_example and grow_patches share at the boundary: the region and obstacles read into
// the grower's input (phase 2, C++ only), and the grown edges out as rows (id, from_node,
// to_node, road_class, origin, geom bytea) (phase 3). Include after core headers: it includes
// PostgreSQL.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/ewkb.hpp"
#include "core/geometry_checks.hpp"
#include "core/growth/grow_example.hpp"
#include "pg/array_args.hpp"
#include "pg/owned_result.hpp"

extern "C" {
#include "utils/builtins.h"
}

namespace streetgen::pg {

struct GrownRow {
  std::int64_t id, from_node, to_node;
  std::string road_class, origin;
  core::Bytes geom;
};

// Phase 1: the `blend` parameter of either grower; anything else is 22023.
inline core::BlendParams::Mode blend_mode_of(const char* mode) {
  if (strcmp(mode, "none") == 0) return core::BlendParams::Mode::none;
  if (strcmp(mode, "gradient") == 0) return core::BlendParams::Mode::gradient;
  if (strcmp(mode, "points") == 0) return core::BlendParams::Mode::points;
  ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("blend must be 'gradient' or 'points'"),
                  errdetail("It is '%s'.", mode)));
  return core::BlendParams::Mode::none;  // (not reached: ereport(ERROR) does not return)
}

// Phase 2: the region and the obstacles, parsed into `input` (which points into `keep`). Returns
// the region's SRID, the output's.
inline int read_region_and_obstacles(core::GeosContext& geos, ByteView region, const ByteView* obstacles,
                                     int obstacle_count, core::GrowInput& input, std::vector<core::SridGeometry>& keep) {
  keep.reserve(static_cast<std::size_t>(obstacle_count) + 1);
  keep.push_back(core::read_ewkb(geos, region.data, region.size, "region"));
  input.region = keep.back().geom.get();
  int srid = keep.back().srid;
  for (int i = 0; i < obstacle_count; ++i) {
    std::string name = "obstacle " + std::to_string(i + 1);
    keep.push_back(core::read_ewkb(geos, obstacles[i].data, obstacles[i].size, name.c_str()));
    core::require_finite_coordinates(geos, keep.back().geom.get(), name.c_str());
    input.obstacles.push_back(keep.back().geom.get());
  }
  return srid;
}

// Phase 2: one grown edge as a row, its geometry a two-point LineString.
inline GrownRow grown_row(const core::GrownEdge& e, std::string origin, int srid) {
  double xy[4] = {e.a.x, e.a.y, e.b.x, e.b.y};
  return {e.id, e.from_node, e.to_node, e.road_class, std::move(origin),
          core::write_ewkb_coordinates(core::WkbType::line_string, xy, 2, srid)};
}

// Phase 3: the rows into the call's materialized result set.
inline void emit_grown_rows(FunctionCallInfo fcinfo, const std::vector<GrownRow>& rows) {
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (const GrownRow& row : rows) {
    Datum v[6];
    bool null[6] = {false, false, false, false, false, false};
    v[0] = Int64GetDatum(row.id);
    v[1] = Int64GetDatum(row.from_node);
    v[2] = Int64GetDatum(row.to_node);
    v[3] = CStringGetTextDatum(row.road_class.c_str());
    v[4] = CStringGetTextDatum(row.origin.c_str());
    v[5] = PointerGetDatum(to_bytea(row.geom));
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, v, null);
  }
}

}  // namespace streetgen::pg
