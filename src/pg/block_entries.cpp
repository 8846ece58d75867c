// The block overlay: faces and pieces in as EWKB arrays, one row per face out (its index in
// the array, from 1, and what is left of it, or NULL). sql/62-blocks.sql gathers the faces and
// the street surfaces and sidewalks around them.
#include <malloc.h>  // malloc_trim (glibc)

#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/streets/blocks.hpp"
#include "pg/array_args.hpp"
#include "pg/boundary.hpp"
#include "pg/owned_result.hpp"
#include "pg/srf.hpp"

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
// (faces bytea[], sidewalks bytea[], sections bytea[], junctions bytea[], grid_size float8)
//   -> SETOF (face_index integer, geom bytea); the pieces are sections, junctions, sidewalks in turn
Datum _streetgen_faces_minus(PG_FUNCTION_ARGS) {
  pg::require_argument_count(fcinfo, 5, "_streetgen_faces_minus");
  if (PG_ARGISNULL(4)) pg::raise_null_argument("grid_size");
  pg::ArrayArg faces = pg::array_arg(fcinfo, 0, BYTEAOID, "faces");
  pg::ArrayArg piece_arrays[3] = {pg::array_arg(fcinfo, 2, BYTEAOID, "sections"),
                                  pg::array_arg(fcinfo, 3, BYTEAOID, "junctions"),
                                  pg::array_arg(fcinfo, 1, BYTEAOID, "sidewalks")};
  double grid_size = PG_GETARG_FLOAT8(4);
  auto* face_views = static_cast<pg::ByteView*>(palloc0(sizeof(pg::ByteView) * (faces.count > 0 ? faces.count : 1)));
  for (int i = 0; i < faces.count; ++i) {
    if (!faces.nulls[i]) face_views[i] = pg::byte_view(faces.values[i]);
  }
  pg::ByteView* piece_views[3];
  int piece_counts[3];
  for (int k = 0; k < 3; ++k) piece_views[k] = pg::byte_views(piece_arrays[k], &piece_counts[k]);
  pg::init_materialized_srf(fcinfo, pg::kSrfMemoryKb);
  auto rows = pg::OwnedResult<CutRows>::create();
  // The statements before this one (the faces' polygonization, the pieces' arrays) leave much of
  // the heap free but mapped (Reisterstown: about 10 MB), and the overlay's own allocations fill
  // little of it: handed back to the system first, the blocks' peak does not stack on it. Not
  // for an edit's few faces (see kTrimMinFaces).
  const bool trimmed = faces.count >= pg::kTrimMinFaces;
  if (trimmed) malloc_trim(0);

  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    // (the pieces stay EWKB here: the overlay reads each when its faces come)
    std::vector<core::WkbView> pieces;
    pieces.reserve(static_cast<std::size_t>(piece_counts[0] + piece_counts[1] + piece_counts[2]));
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < piece_counts[k]; ++i) pieces.push_back({piece_views[k][i].data, piece_views[k][i].size});
    }
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
       "unions %.3f, differences %.3f, rounding %.3f, all %.3f; heap %s before",
       rows->stats.faces, rows->stats.candidate_pairs, rows->stats.winding_faces, rows->stats.clipped_pairs,
       rows->stats.grid_faces, rows->stats.pieces_held_at_most, rows->stats.pieces, rows->stats.winding_seconds, rows->stats.clip_seconds, rows->stats.union_seconds, rows->stats.difference_seconds, rows->stats.rounding_seconds,
       rows->stats.total_seconds, trimmed ? "trimmed" : "kept");
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (std::size_t i = 0; i < rows->geoms.size(); ++i) {
    core::Bytes& g = rows->geoms[i];
    Datum values[2] = {Int32GetDatum(static_cast<int32>(i + 1)), g.empty() ? Datum(0) : PointerGetDatum(pg::to_bytea(g))};
    bool nulls[2] = {false, g.empty()};
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, values, nulls);
    if (!g.empty()) pfree(DatumGetPointer(values[1]));
    core::Bytes().swap(g);  // (written: not held beside the rows)
  }
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
