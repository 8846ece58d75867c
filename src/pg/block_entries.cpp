// The block overlay: faces and pieces in as EWKB arrays, one row per face out (its index in
// the array, from 1, and what is left of it, or NULL). sql/62-blocks.sql gathers the faces and
// the street surfaces and sidewalks around them.
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/streets/blocks.hpp"
#include "pg/array_args.hpp"
#include "pg/boundary.hpp"
#include "pg/owned_result.hpp"

extern "C" {
#include "catalog/pg_type.h"
#include "utils/array.h"
}

using namespace streetgen;

namespace {

struct CutRows {
  std::vector<core::Bytes> geoms;  // empty: NULL
  core::FaceCutStats stats;
};

}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_faces_minus);
// (faces bytea[], pieces bytea[], grid_size float8) -> SETOF (face_index integer, geom bytea)
Datum _streetgen_faces_minus(PG_FUNCTION_ARGS) {
  pg::require_argument_count(fcinfo, 3, "_streetgen_faces_minus");
  if (PG_ARGISNULL(2)) pg::raise_null_argument("grid_size");
  pg::ArrayArg faces = pg::array_arg(fcinfo, 0, BYTEAOID, "faces");
  pg::ArrayArg piece_array = pg::array_arg(fcinfo, 1, BYTEAOID, "pieces");
  double grid_size = PG_GETARG_FLOAT8(2);
  auto* face_views = static_cast<pg::ByteView*>(palloc0(sizeof(pg::ByteView) * (faces.count > 0 ? faces.count : 1)));
  for (int i = 0; i < faces.count; ++i) {
    if (!faces.nulls[i]) face_views[i] = pg::byte_view(faces.values[i]);
  }
  int piece_count = 0;
  pg::ByteView* piece_views = pg::byte_views(piece_array, &piece_count);
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<CutRows>::create();

  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    // (the pieces stay EWKB here: the overlay reads each when its faces come)
    std::vector<core::WkbView> pieces(static_cast<std::size_t>(piece_count));
    for (int i = 0; i < piece_count; ++i) pieces[static_cast<std::size_t>(i)] = {piece_views[i].data, piece_views[i].size};
    // A face is read when its turn comes and its cut written at once (a city's faces and cuts
    // held whole were a fifth of the blocks' memory).
    auto& out = rows.emplace();
    out.geoms.resize(static_cast<std::size_t>(faces.count));
    int srid = 0;
    auto face_at = [&](std::size_t f) {
      const pg::ByteView& v = face_views[f];
      if (v.data == nullptr) return core::GeomPtr(nullptr, core::GeomDeleter{geos.handle()});
      std::string name = "face " + std::to_string(f + 1);
      core::SridGeometry g = core::read_ewkb(geos, v.data, v.size, name.c_str());
      srid = g.srid;
      return std::move(g.geom);
    };
    auto emit = [&](std::size_t f, core::GeomPtr cut) {
      if (cut) out.geoms[f] = core::write_ewkb(geos, cut.get(), srid);
    };
    core::faces_minus_pieces(geos, static_cast<std::size_t>(faces.count), face_at, pieces, grid_size, emit, &out.stats);
  });
  pg::raise_if_failed(error);

  elog(DEBUG1,
       "streetgen: blocks of %zu faces, %zu (face, polygon) pairs by box, %zu faces by winding, %zu polygons clipped, "
       "%zu faces on the grid, at most %zu of the %zu pieces read at once; CPU seconds in winding %.3f, clips %.3f, "
       "unions %.3f, differences %.3f, rounding %.3f, all %.3f",
       rows->stats.faces, rows->stats.candidate_pairs, rows->stats.winding_faces, rows->stats.clipped_pairs,
       rows->stats.grid_faces, rows->stats.pieces_held_at_most, rows->stats.pieces, rows->stats.winding_seconds, rows->stats.clip_seconds, rows->stats.union_seconds, rows->stats.difference_seconds, rows->stats.rounding_seconds,
       rows->stats.total_seconds);
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (std::size_t i = 0; i < rows->geoms.size(); ++i) {
    const core::Bytes& g = rows->geoms[i];
    Datum values[2] = {Int32GetDatum(static_cast<int32>(i + 1)), g.empty() ? Datum(0) : PointerGetDatum(pg::to_bytea(g))};
    bool nulls[2] = {false, g.empty()};
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, values, nulls);
  }
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
