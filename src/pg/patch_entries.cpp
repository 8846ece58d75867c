// Patch-based growth (growing networks II): extract_patches turns an example into patch rows with
// semantic tags; grow_patches grows a network from such rows. sql/82-patches.sql reads the
// queries and the params jsonb; src/core/growth/patches.cpp and grow_example.cpp hold the method.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/geometry_checks.hpp"
#include "core/growth/grow_example.hpp"
#include "core/growth/patches.hpp"
#include "core/interrupts.hpp"
#include "pg/array_args.hpp"
#include "pg/boundary.hpp"
#include "pg/grid_args.hpp"
#include "pg/grown_rows.hpp"
#include "pg/owned_result.hpp"

extern "C" {
#include "catalog/pg_type.h"
#include "utils/array.h"
#include "utils/builtins.h"
}

using namespace streetgen;

namespace {

struct PatchRow {
  std::int64_t patch_id;
  int edge_index;
  std::string role, road_class;
  std::vector<std::string> tags, edge_tags, start_tags, end_tags;
  std::int64_t example_id;
  core::Bytes geom;
};

Datum text_array(const std::vector<std::string>& values) {
  auto* elems = static_cast<Datum*>(palloc(sizeof(Datum) * (values.empty() ? 1 : values.size())));
  for (std::size_t i = 0; i < values.size(); ++i) elems[i] = CStringGetTextDatum(values[i].c_str());
  return PointerGetDatum(construct_array(elems, static_cast<int>(values.size()), TEXTOID, -1, false, TYPALIGN_INT));
}

enum ExtractArg {
  kXGeoms, kXClasses, kXIds, kXRoundabouts, kXShortEdge, kXClusterDistance, kXCircles, kXCircleMin, kXCircleMax,
  kXCompactness, kXCropMargin, kXLevels, kXArgs
};

enum GrowArg {
  kGPatchIds, kGRoles, kGClasses, kGGeoms, kGMaxUses, kGRegion, kGSeedsX, kGSeedsY, kGObstacles, kGSeed, kGMaxEdges,
  kGSnap, kGMinAngle, kGScale, kGMaxDistance, kGAngleWindow, kGTries, kGDefaultMaxUses, kGRotation, kGFallback, kGClearance,
  kGArterials, kGLevels, kGWater, kGDemGrid, kGDemValues, kGMaxSlope, kGBridgeDistance, kGBridgeTurn,
  // Operations: warping (guide), interpolation (a second library, t) and blending.
  kGGuide, kGGuideReach, kGPatchIdsB, kGRolesB, kGClassesB, kGGeomsB, kGMaxUsesB, kGArterialsB, kGT, kGBlendMode,
  kGBlendAngle, kGBlendX, kGBlendY, kGBlendSigma, kGPruneDangling, kGDirectionGrid, kGDirectionValues, kGConnectDangling,
  kGFallbackCurvature, kGArterialFallback, kGFallbackLocalSeeds,
  // Teng & Bidarra: the first library's patches tagged initial, breadth-first bridging, cell initialisation.
  kGInitials, kGBridgeFronts, kGCellInit, kGMaxTurn, kGCellSpacing,
  kGPromoteArterials, kGTerminalRoom, kGRoundabouts,
  kGArgs
};

// One patch library's rows, read in phase 1 (palloc'd plain data).
struct EdgeArg {
  std::int64_t patch_id;
  core::PatchEdgeRole role;
  const char* road_class;
  int max_uses;
  bool arterial;
  bool initial;     // the patch is tagged initial
  bool roundabout;  // the patch is tagged roundabout
  pg::ByteView geom;
};
struct LibraryArg {
  EdgeArg* edges = nullptr;
  int count = 0;
  const char* what = "";  // "" for the first library, "interpolate " for the second
};

LibraryArg read_library(FunctionCallInfo fcinfo, int a_ids, int a_roles, int a_classes, int a_geoms, int a_uses,
                        int a_arterials, const char* what, int a_initials = -1, int a_roundabouts = -1) {
  pg::ArrayArg pids = pg::array_arg(fcinfo, a_ids, INT8OID, "patch ids");
  pg::ArrayArg roles = pg::array_arg(fcinfo, a_roles, TEXTOID, "roles");
  pg::ArrayArg classes = pg::array_arg(fcinfo, a_classes, TEXTOID, "road classes");
  pg::ArrayArg geoms = pg::array_arg(fcinfo, a_geoms, BYTEAOID, "patch edges");
  pg::ArrayArg uses = pg::array_arg(fcinfo, a_uses, INT4OID, "max_uses");
  pg::ArrayArg arterials = pg::array_arg(fcinfo, a_arterials, BOOLOID, "arterials");
  pg::ArrayArg initials{};
  if (a_initials >= 0) initials = pg::array_arg(fcinfo, a_initials, BOOLOID, "initials");
  pg::ArrayArg roundabouts{};
  if (a_roundabouts >= 0) roundabouts = pg::array_arg(fcinfo, a_roundabouts, BOOLOID, "roundabouts");
  pg::require_same_length(geoms, "patch edges", pids, "patch ids");
  pg::require_same_length(geoms, "patch edges", roles, "roles");
  if (classes.count != 0) pg::require_same_length(geoms, "patch edges", classes, "road classes");
  if (uses.count != 0) pg::require_same_length(geoms, "patch edges", uses, "max_uses");
  if (arterials.count != 0) pg::require_same_length(geoms, "patch edges", arterials, "arterials");
  if (initials.count != 0) pg::require_same_length(geoms, "patch edges", initials, "initials");
  if (roundabouts.count != 0) pg::require_same_length(geoms, "patch edges", roundabouts, "roundabouts");
  LibraryArg lib;
  lib.what = what;
  lib.count = geoms.count;
  auto* edges = static_cast<EdgeArg*>(palloc0(sizeof(EdgeArg) * (geoms.count > 0 ? geoms.count : 1)));
  lib.edges = edges;
  for (int i = 0; i < geoms.count; ++i) {
    if (pids.nulls[i]) {
      ereport(ERROR, (errcode(ERRCODE_NULL_VALUE_NOT_ALLOWED), errmsg("patch_id must not be null"),
                      errdetail("%sPatch row %d has no patch_id.", what, i + 1)));
    }
    EdgeArg& e = edges[i];
    e.patch_id = DatumGetInt64(pids.values[i]);
    if (geoms.nulls[i]) {
      ereport(ERROR, (errcode(ERRCODE_NULL_VALUE_NOT_ALLOWED), errmsg("patch edge geometry must not be null"),
                      errdetail("%sPatch row %d (patch_id %lld) has no geom.", what, i + 1,
                                static_cast<long long>(e.patch_id))));
    }
    const char* role = roles.nulls[i] ? "" : TextDatumGetCString(roles.values[i]);
    if (strcmp(role, "inner") == 0) {
      e.role = core::PatchEdgeRole::inner;
    } else if (strcmp(role, "connector") == 0) {
      e.role = core::PatchEdgeRole::connector;
    } else if (strcmp(role, "dead_end") == 0) {
      e.role = core::PatchEdgeRole::dead_end;
    } else if (strcmp(role, "isolated") == 0) {
      e.role = core::PatchEdgeRole::isolated;
    } else {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE),
                      errmsg("patch edge role must be 'inner', 'connector', 'dead_end' or 'isolated'"),
                      errdetail("%sPatch row %d (patch_id %lld) has role %s.", what, i + 1,
                                static_cast<long long>(e.patch_id),
                                roles.nulls[i] ? "NULL" : quote_literal_cstr(role))));
    }
    e.road_class = classes.count != 0 && !classes.nulls[i] ? TextDatumGetCString(classes.values[i]) : "unclassified";
    e.max_uses = uses.count != 0 && !uses.nulls[i] ? DatumGetInt32(uses.values[i]) : 0;
    if (e.max_uses < 0) {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("max_uses must be >= 0"),
                      errdetail("%sPatch row %d (patch_id %lld) has max_uses %d.", what, i + 1,
                                static_cast<long long>(e.patch_id), e.max_uses)));
    }
    e.arterial = arterials.count != 0 && !arterials.nulls[i] && DatumGetBool(arterials.values[i]);
    e.initial = initials.count != 0 && !initials.nulls[i] && DatumGetBool(initials.values[i]);
    e.roundabout = roundabouts.count != 0 && !roundabouts.nulls[i] && DatumGetBool(roundabouts.values[i]);
    e.geom = pg::byte_view(geoms.values[i]);
  }
  return lib;
}

// Phase 2: rows of one patch_id make one patch, in the order given.
void build_patches(core::GeosContext& geos, const LibraryArg& lib, std::vector<core::Patch>& out) {
  core::InterruptPoller poller(1024);
  std::map<std::int64_t, std::size_t> index;  // patch_id -> position in out
  for (int i = 0; i < lib.count; ++i) {
    poller.tick();
    const EdgeArg& e = lib.edges[i];
    std::string name = std::string(lib.what) + "patch row " + std::to_string(i + 1) + " (patch_id " +
                       std::to_string(e.patch_id) + ")";
    core::SridGeometry g = core::read_ewkb(geos, e.geom.data, e.geom.size, name.c_str());
    std::vector<core::Polyline> lines;
    core::append_linestrings(geos, g.geom.get(), name, "patch edges must be LineStrings", "", lines);
    if (lines.size() != 1) core::throw_invalid_argument(name + " must be one LineString");
    auto [it, added] = index.emplace(e.patch_id, out.size());
    if (added) {
      out.push_back({});
      out.back().id = e.patch_id;
    }
    core::Patch& patch = out[it->second];
    patch.max_uses = std::max(patch.max_uses, e.max_uses);
    for (const char* tag : {e.arterial ? "arterial" : nullptr, e.initial ? "initial" : nullptr,
                            e.roundabout ? "roundabout" : nullptr}) {
      if (tag != nullptr && std::find(patch.tags.begin(), patch.tags.end(), tag) == patch.tags.end()) {
        patch.tags.emplace_back(tag);
      }
    }
    core::PatchEdge pe;
    pe.line = std::move(lines[0]);
    pe.role = e.role;
    pe.road_class = e.road_class;
    pe.example_id = e.patch_id;
    patch.edges.push_back(std::move(pe));
  }
}

}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_extract_patches);
// See enum ExtractArg; -> SETOF (patch_id, edge_index, role, road_class, tags, edge_tags, start_tags,
// end_tags, example_id, geom bytea).
Datum _streetgen_extract_patches(PG_FUNCTION_ARGS) {
  // Phase 1.
  pg::require_argument_count(fcinfo, kXArgs, "_streetgen_extract_patches");
  static const char* const names[kXArgs] = {"example", "example road classes", "example ids", "example roundabouts",
                                            "short_edge", "cluster_distance", "detect_circles",
                                            "circle_min_diameter", "circle_max_diameter", "circle_compactness",
                                            "crop_margin", "levels"};
  for (int a = kXShortEdge; a < kXArgs; ++a) {
    if (PG_ARGISNULL(a)) pg::raise_null_argument(names[a]);
  }
  pg::ArrayArg geoms = pg::array_arg(fcinfo, kXGeoms, BYTEAOID, "example");
  pg::ArrayArg classes = pg::array_arg(fcinfo, kXClasses, TEXTOID, "example road classes");
  pg::ArrayArg ids = pg::array_arg(fcinfo, kXIds, INT8OID, "example ids");
  pg::ArrayArg rounds = pg::array_arg(fcinfo, kXRoundabouts, BOOLOID, "example roundabouts");
  if (classes.count != 0) pg::require_same_length(geoms, "example", classes, "example road classes");
  if (ids.count != 0) pg::require_same_length(geoms, "example", ids, "example ids");
  if (rounds.count != 0) pg::require_same_length(geoms, "example", rounds, "example roundabouts");
  struct ExampleArg {
    pg::ByteView geom;
    const char* road_class;
    std::int64_t id;
    bool roundabout;
  };
  auto* example = static_cast<ExampleArg*>(palloc0(sizeof(ExampleArg) * (geoms.count > 0 ? geoms.count : 1)));
  int example_count = 0;
  for (int i = 0; i < geoms.count; ++i) {
    if (geoms.nulls[i]) continue;
    ExampleArg& e = example[example_count++];
    e.geom = pg::byte_view(geoms.values[i]);
    e.road_class = classes.count != 0 && !classes.nulls[i] ? TextDatumGetCString(classes.values[i]) : "unclassified";
    e.id = ids.count != 0 && !ids.nulls[i] ? DatumGetInt64(ids.values[i]) : i + 1;
    e.roundabout = rounds.count != 0 && !rounds.nulls[i] && DatumGetBool(rounds.values[i]);
  }
  core::PatchParams params;
  params.short_edge = PG_GETARG_FLOAT8(kXShortEdge);
  params.cluster_distance = PG_GETARG_FLOAT8(kXClusterDistance);
  params.detect_circles = PG_GETARG_BOOL(kXCircles);
  params.circle_min_diameter = PG_GETARG_FLOAT8(kXCircleMin);
  params.circle_max_diameter = PG_GETARG_FLOAT8(kXCircleMax);
  params.circle_compactness = PG_GETARG_FLOAT8(kXCompactness);
  params.crop_margin = PG_GETARG_FLOAT8(kXCropMargin);
  params.levels = PG_GETARG_BOOL(kXLevels);
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<std::vector<PatchRow>>::create();
  std::size_t patch_count = 0, streets = 0, junctions = 0, arterial = 0;
  double short_edge = 0.0;

  // Phase 2.
  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    std::vector<core::PatchInputEdge> input;
    int srid = 0;
    core::InterruptPoller poller(1024);
    for (int i = 0; i < example_count; ++i) {
      poller.tick();
      std::string name = "example edge " + std::to_string(i + 1);
      core::SridGeometry g = core::read_ewkb(geos, example[i].geom.data, example[i].geom.size, name.c_str());
      if (i == 0) srid = g.srid;
      std::vector<core::Polyline> lines;
      core::append_linestrings(geos, g.geom.get(), name, "example edges must be LineStrings or MultiLineStrings", "", lines);
      for (core::Polyline& line : lines) input.push_back({std::move(line), example[i].road_class, example[i].id, example[i].roundabout});
    }
    core::PatchExtraction x = core::extract_patches(geos, input, params);
    patch_count = x.patches.size();
    streets = x.streets;
    junctions = x.junctions;
    arterial = x.arterial_patches;
    short_edge = x.short_edge;
    std::vector<PatchRow> out;
    for (const core::Patch& p : x.patches) {
      int k = 0;
      for (const core::PatchEdge& e : p.edges) {
        out.push_back({p.id, ++k, core::role_name(e.role), e.road_class, p.tags, e.tags, e.start_tags, e.end_tags,
                       e.example_id, core::write_ewkb_polyline(core::WkbType::line_string, e.line, srid)});
      }
    }
    rows.emplace(std::move(out));
  });
  pg::raise_if_failed(error);

  // Phase 3.
  ereport(DEBUG1, (errmsg("extract_patches: %zu streets, %zu junctions, %zu patches (%zu arterial), short_edge %.1f m",
                          streets, junctions, patch_count, arterial, short_edge)));
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (const PatchRow& row : *rows) {
    Datum v[10];
    bool null[10] = {false, false, false, false, false, false, false, false, false, false};
    v[0] = Int64GetDatum(row.patch_id);
    v[1] = Int32GetDatum(row.edge_index);
    v[2] = CStringGetTextDatum(row.role.c_str());
    v[3] = CStringGetTextDatum(row.road_class.c_str());
    v[4] = text_array(row.tags);
    v[5] = text_array(row.edge_tags);
    v[6] = text_array(row.start_tags);
    v[7] = text_array(row.end_tags);
    v[8] = Int64GetDatum(row.example_id);
    v[9] = PointerGetDatum(pg::to_bytea(row.geom));
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, v, null);
  }
  rows.release();
  PG_RETURN_NULL();
}

PG_FUNCTION_INFO_V1(_streetgen_grow_patches);
// See enum GrowArg; -> SETOF (id, from_node, to_node, road_class, origin, geom bytea).
Datum _streetgen_grow_patches(PG_FUNCTION_ARGS) {
  // Phase 1.
  pg::require_argument_count(fcinfo, kGArgs, "_streetgen_grow_patches");
  static const char* const names[kGArgs] = {
      "patch ids", "roles", "road classes", "patch edges", "max_uses", "region", "seeds x", "seeds y", "obstacles",
      "seed", "max_edges", "snap", "min_angle", "scale", "max_distance", "angle_window", "tries", "max_uses",
      "rotation", "fallback", "clearance", "arterials", "levels", "water", "dem grid", "dem", "max_slope",
      "bridge_distance", "bridge_turn", "guide", "guide_reach", "interpolate patch ids", "interpolate roles",
      "interpolate road classes", "interpolate patch edges", "interpolate max_uses", "interpolate arterials", "t",
      "blend", "blend_angle", "blend_points x", "blend_points y", "blend_sigma", "prune_dangling", "direction grid",
      "direction", "connect_dangling", "fallback_curvature", "arterial_fallback", "fallback_local_seeds", "initials",
      "bridge_fronts", "cell_init", "max_turn", "cell_spacing", "promote_arterials", "terminal_room", "roundabouts"};
  for (int a = kGRegion; a < kGArgs; ++a) {
    if (a != kGSeedsX && a != kGSeedsY && a != kGObstacles && a != kGArterials && a != kGWater && a != kGDemGrid &&
        a != kGDemValues && a != kGGuide && !(a >= kGPatchIdsB && a <= kGArterialsB) && a != kGBlendX &&
        a != kGBlendY && a != kGDirectionGrid && a != kGDirectionValues && a != kGInitials && a != kGRoundabouts &&
        PG_ARGISNULL(a)) {
      pg::raise_null_argument(names[a]);
    }
  }
  LibraryArg lib = read_library(fcinfo, kGPatchIds, kGRoles, kGClasses, kGGeoms, kGMaxUses, kGArterials, "", kGInitials,
                                kGRoundabouts);
  LibraryArg lib_b = read_library(fcinfo, kGPatchIdsB, kGRolesB, kGClassesB, kGGeomsB, kGMaxUsesB, kGArterialsB,
                                  "interpolate ");
  pg::ArrayArg blend_xs = pg::array_arg(fcinfo, kGBlendX, FLOAT8OID, "blend_points x");
  pg::ArrayArg blend_ys = pg::array_arg(fcinfo, kGBlendY, FLOAT8OID, "blend_points y");
  pg::require_same_length(blend_xs, "blend_points x", blend_ys, "blend_points y");
  int blend_count = 0;
  double* blend_xy = pg::xy_pairs(blend_xs, blend_ys, "a blend point coordinate", &blend_count);
  bool has_guide = !PG_ARGISNULL(kGGuide);
  pg::ByteView guide = has_guide ? pg::byte_view(PG_GETARG_DATUM(kGGuide)) : pg::ByteView{nullptr, 0};
  pg::ArrayArg xs = pg::array_arg(fcinfo, kGSeedsX, FLOAT8OID, "seeds x");
  pg::ArrayArg ys = pg::array_arg(fcinfo, kGSeedsY, FLOAT8OID, "seeds y");
  pg::require_same_length(xs, "seeds x", ys, "seeds y");
  pg::ArrayArg obstacle_arg = pg::array_arg(fcinfo, kGObstacles, BYTEAOID, "obstacles");
  pg::ArrayArg water_arg = pg::array_arg(fcinfo, kGWater, BYTEAOID, "water");
  pg::GridArg dem = pg::grid_arg(fcinfo, kGDemGrid, kGDemValues, "dem");
  pg::GridArg direction = pg::grid_arg(fcinfo, kGDirectionGrid, kGDirectionValues, "direction");
  int seed_count = 0;
  double* seed_xy = pg::xy_pairs(xs, ys, "a seed coordinate", &seed_count);
  int obstacle_count = 0;
  pg::ByteView* obstacles = pg::byte_views(obstacle_arg, &obstacle_count);
  int water_count = 0;
  pg::ByteView* water = pg::byte_views(water_arg, &water_count);
  pg::ByteView region = pg::byte_view(PG_GETARG_DATUM(kGRegion));
  core::GrowParams params;
  params.use_patches = true;
  params.seed = static_cast<std::uint64_t>(PG_GETARG_INT64(kGSeed));
  int max_edges = PG_GETARG_INT32(kGMaxEdges);
  if (max_edges <= 0) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("max_edges must be > 0"),
                    errdetail("It is %d.", max_edges)));
  }
  params.max_edges = static_cast<std::size_t>(max_edges);
  params.snap = PG_GETARG_FLOAT8(kGSnap);
  params.min_angle = PG_GETARG_FLOAT8(kGMinAngle);
  params.patch.scale = PG_GETARG_FLOAT8(kGScale);
  params.patch.max_distance = PG_GETARG_FLOAT8(kGMaxDistance);
  params.patch.angle_window = PG_GETARG_FLOAT8(kGAngleWindow);
  params.patch.tries = PG_GETARG_INT32(kGTries);
  params.patch.max_uses = PG_GETARG_INT32(kGDefaultMaxUses);
  params.patch.rotation = PG_GETARG_FLOAT8(kGRotation);
  params.fallback = PG_GETARG_BOOL(kGFallback);
  params.patch.clearance = PG_GETARG_FLOAT8(kGClearance);
  params.patch.levels = PG_GETARG_BOOL(kGLevels);
  params.max_slope = PG_GETARG_FLOAT8(kGMaxSlope);
  params.bridge_distance = PG_GETARG_FLOAT8(kGBridgeDistance);
  params.bridge_turn = PG_GETARG_FLOAT8(kGBridgeTurn);
  params.rotation = true;  // the fallback's streets turn from the front's street, as Nishida's (about 90°)
  params.guide_reach = PG_GETARG_FLOAT8(kGGuideReach);
  params.patch.t = PG_GETARG_FLOAT8(kGT);
  const char* blend_mode = TextDatumGetCString(PG_GETARG_DATUM(kGBlendMode));
  params.blend.mode = pg::blend_mode_of(blend_mode);
  params.blend.angle = PG_GETARG_FLOAT8(kGBlendAngle);
  params.blend.sigma = PG_GETARG_FLOAT8(kGBlendSigma);
  params.patch.prune_dangling = PG_GETARG_BOOL(kGPruneDangling);
  params.patch.connect_dangling = PG_GETARG_BOOL(kGConnectDangling);
  params.patch.fallback_curvature = PG_GETARG_BOOL(kGFallbackCurvature);
  params.patch.continue_across = params.patch.connect_dangling;  // one SQL switch for both joins (README)
  params.patch.arterial_fallback = PG_GETARG_FLOAT8(kGArterialFallback);
  params.patch.fallback_local_seeds = PG_GETARG_BOOL(kGFallbackLocalSeeds);
  params.patch.bridge_fronts = PG_GETARG_BOOL(kGBridgeFronts);
  params.patch.max_turn = PG_GETARG_FLOAT8(kGMaxTurn);
  params.patch.cell_spacing = PG_GETARG_FLOAT8(kGCellSpacing);
  params.patch.promote_arterials = PG_GETARG_BOOL(kGPromoteArterials);
  params.patch.terminal_room = PG_GETARG_FLOAT8(kGTerminalRoom);
  {
    const char* cell_init = TextDatumGetCString(PG_GETARG_DATUM(kGCellInit));
    if (strcmp(cell_init, "seeds") == 0) {
      params.patch.cell_init = core::PatchGrowParams::CellInit::seeds;
    } else if (strcmp(cell_init, "initial") == 0) {
      params.patch.cell_init = core::PatchGrowParams::CellInit::initial;
    } else {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("cell_init must be 'seeds' or 'initial'"),
                      errdetail("It is %s.", quote_literal_cstr(cell_init))));
    }
  }
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<std::vector<pg::GrownRow>>::create();
  core::GrowStats stats;
  std::size_t from_patches = 0, total = 0, bridges = 0;
  double length_patches = 0.0, length_total = 0.0;

  // Phase 2.
  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    core::GrowInput input;
    core::InterruptPoller poller(1024);
    build_patches(geos, lib, input.patches);
    build_patches(geos, lib_b, input.patches_b);
    for (int i = 0; i < blend_count; ++i) params.blend.points.push_back({blend_xy[2 * i], blend_xy[2 * i + 1]});
    std::vector<core::SridGeometry> guide_geom;
    if (has_guide) {
      guide_geom.push_back(core::read_ewkb(geos, guide.data, guide.size, "guide"));
      core::append_linestrings(geos, guide_geom.back().geom.get(), "guide",
                               "guide must be a LineString or MultiLineString", "", input.guide);
    }
    std::vector<core::SridGeometry> region_and_obstacles;
    int srid = pg::read_region_and_obstacles(geos, region, obstacles, obstacle_count, input, region_and_obstacles);
    std::vector<core::SridGeometry> water_parts;
    water_parts.reserve(static_cast<std::size_t>(water_count));
    for (int i = 0; i < water_count; ++i) {
      std::string name = "water part " + std::to_string(i + 1);
      water_parts.push_back(core::read_ewkb(geos, water[i].data, water[i].size, name.c_str()));
      core::require_finite_coordinates(geos, water_parts.back().geom.get(), name.c_str());
      input.water.push_back(water_parts.back().geom.get());
    }
    pg::to_field(dem, input.dem);
    pg::to_field(direction, input.direction);
    for (int i = 0; i < seed_count; ++i) input.seeds.push_back({seed_xy[2 * i], seed_xy[2 * i + 1]});
    core::GrowResult result = core::grow_example(geos, input, params);
    stats = result.stats;
    std::vector<pg::GrownRow> out;
    out.reserve(result.edges.size());
    for (const core::GrownEdge& e : result.edges) {
      double len = core::distance(e.a, e.b);
      ++total;
      length_total += len;
      if (e.example >= 0) {
        ++from_patches;
        length_patches += len;
      }
      if (e.bridge) ++bridges;
      std::string origin = e.bridge           ? std::string("bridge")
                           : e.example < 0 ? std::string("grow_parametric")
                           : e.example == 1 ? "grow_patches:" + std::to_string(e.example_id) + ":b"
                                           : "grow_patches:" + std::to_string(e.example_id);
      out.push_back(pg::grown_row(e, std::move(origin), srid));
    }
    rows.emplace(std::move(out));
  });
  pg::raise_if_failed(error);

  // Phase 3.
  ereport(DEBUG1, (errmsg("grow_patches: %zu steps, %zu patches placed, %zu statistical fallback, %zu candidates, "
                          "%zu illegal, %zu terminal refused for the room ahead, %zu self-crossing patches dropped, %zu restarts; levels: %zu arterial patches "
                          "placed, %zu local seeds (%zu with their example patch), %zu local streets ended on arterials; "
                          "terrain: %zu bridges (%zu bridge attempts failed), %zu bent along the contour, %zu too steep; "
                          "operations: %zu warped steps, %zu patches from the interpolate library, %zu dangling "
                          "streets connected, %zu T-junctions continued across (%zu of them after the cuts, %zu facing joins found by the wider cone or reach, %zu across %zu streets, %zu nodes slid onto the grid for joins; %zu local T's to the node or street ahead; joins "
                          "refused: %zu over the example's street length, %zu over its junctions), %zu corners avoided (%zu cut back), %zu crop dead ends "
                          "cut back, %zu dangling segments "
                          "pruned, %zu dead ends kept, %zu islands joined to the rest (%zu of them beyond a mean "
                          "street; %zu left apart, %zu scraps removed), %zu segments under 0.5 m dropped; "
                          "example-based share %.1f %% of the edges, %.1f %% of the length",
                          stats.steps, stats.patches_placed, stats.fallback, stats.patch_candidates, stats.patch_illegal,
                          stats.terminal_refused, stats.patches_dropped, stats.restarts, stats.arterial_patches_placed, stats.local_seeds,
                          stats.local_seeds_used, stats.ended_on_arterial, bridges, stats.bridges_failed, stats.bent,
                          stats.too_steep, stats.guided, stats.patches_b_placed, stats.dangling_connected,
                          stats.continued_across, stats.faced_after_cuts, stats.wide_facing_joins, stats.facing_through_joins, stats.facing_through_crossed, stats.slid_onto_grid, stats.local_tees_continued, stats.local_tees_long, stats.local_tees_dense, stats.corners_avoided, stats.corners_cut, stats.crop_ends_cut, stats.dangling_pruned,
                          stats.dead_ends_kept, stats.islands_joined, stats.islands_joined_far, stats.islands_left,
                          stats.islands_dropped,
                          stats.short_segments_dropped,
                          total > 0 ? 100.0 * from_patches / total : 0.0,
                          length_total > 0 ? 100.0 * length_patches / length_total : 0.0)));
  if (stats.arterial_fronts > 0) {
    // Why the arterial phase stops: each front visit by outcome, then the illegal draws by reason.
    char reasons[512];
    std::size_t used = 0;
    reasons[0] = '\0';
    for (int r = core::kRefRedundant; r < core::kPatchRefusals && used < sizeof(reasons); ++r) {
      int n = snprintf(reasons + used, sizeof(reasons) - used, "%s%s %zu", r == core::kRefRedundant ? "" : ", ",
                       core::kPatchRefusalNames[r], stats.arterial_refusals[r]);
      if (n < 0) break;
      used += static_cast<std::size_t>(n);
    }
    ereport(DEBUG1, (errmsg("grow_patches: arterial fronts %zu: %zu already finished, %zu without a connector in "
                            "their direction, %zu with only used-up patches, %zu none within max_distance by reach, "
                            "%zu none by Hausdorff distance, %zu every draw refused; refused draws: %s; connectors of the "
                            "arterial patches: %zu new fronts, %zu clipped, %zu merged into a node, %zu dropped; %zu "
                            "dead-end edges",
                            stats.arterial_fronts, stats.arterial_front_finished, stats.arterial_front_no_direction,
                            stats.arterial_front_used_up, stats.arterial_front_reach, stats.arterial_front_hausdorff,
                            stats.arterial_front_refused, reasons, stats.arterial_conn_front, stats.arterial_conn_clipped,
                            stats.arterial_conn_merged, stats.arterial_conn_dropped, stats.arterial_dead_ends)));
  }
  if (stats.arterial_fallback_budget > 0.0 || stats.fallback_local_seeds > 0) {
    ereport(DEBUG1, (errmsg("grow_patches: arterial fallback: %zu statistical steps at arterial fronts (main streets up "
                            "to %.0f m; %zu dead ends queued again, %zu of them crop ends, %zu passes); %zu local seeds "
                            "cut along fallback arterials, %zu of them grew the local fallback",
                            stats.arterial_fallback, stats.arterial_fallback_budget, stats.arterial_fallback_fronts,
                            stats.arterial_fallback_crop_ends, stats.arterial_fallback_passes,
                            stats.fallback_local_seeds, stats.fallback_local_seeds_grown)));
  }
  if (stats.arterial_refill_target > 0.0) {
    ereport(DEBUG1, (errmsg("grow_patches: arterial refill: main streets %.0f m aimed at, gap %.0f m, %.0f m when the "
                            "arterial phase first stopped, %.0f m at its end, %zu arterial seeds",
                            stats.arterial_refill_target, stats.arterial_refill_gap, stats.arterial_refill_before,
                            stats.arterial_refill_after, stats.arterial_reseeds)));
  }
  if (stats.arterial_ends > 0) {
    ereport(DEBUG1, (errmsg("grow_patches: arterials run on: %zu arterial streets ended into local streets inside the "
                            "margin, %zu continued (%.0f m of local streets promoted), %zu left for the main-street "
                            "budget, %zu stubs past a main junction back to the local class (%.0f m)",
                            stats.arterial_ends, stats.arterials_promoted, stats.promoted_length,
                            stats.arterials_over_budget, stats.arterial_stubs_demoted, stats.demoted_length)));
  }
  ereport(DEBUG1, (errmsg("grow_patches: refill: target %.0f m, gap %.0f m, %.0f m grown when the queue first emptied, "
                          "%zu reseeds (%zu inside the void)",
                          stats.refill_target, stats.refill_gap, stats.refill_before, stats.reseeds,
                          stats.refill_islands)));
  if (stats.cap_length > 0.0) {
    ereport(DEBUG1, (errmsg("grow_patches: length cap: %.0f m, reached at step %zu (0: never), %zu open connectors cut "
                            "back there",
                            stats.cap_length, stats.cap_step, stats.cap_fronts_cut)));
  }
  if (stats.cap_first_length > 0.0) {
    ereport(DEBUG1, (errmsg("grow_patches: the first growth ended at %.0f m after its joins, over its cap of %.0f m, "
                            "and was grown again under a cap lowered by that overshoot (%s); %s",
                            stats.cap_first_length, stats.cap_first_cap,
                            stats.cap_resumed ? "resumed from its checkpoint" : "from the start",
                            stats.cap_regrown_kept ? "the second growth, nearer the cap, is kept (its cap above)"
                                                   : "the second ended farther from the cap: the first is kept")));
  }
  {
    // Patch size at fronts: legality against size (terciles of the local patches' connector length).
    char buf[1024];
    std::size_t used = 0;
    buf[0] = '\0';
    for (int c = 0; c < 3 && used < sizeof(buf); ++c) {
      std::size_t refused = 0;
      for (int r = 0; r < core::kPatchRefusals; ++r) refused += stats.size_refusals[c][r];
      int n = snprintf(buf + used, sizeof(buf) - used, "%sclass %d: first %zu, tried %zu, refused %zu, placed %zu (",
                       c == 0 ? "" : "; ", c, stats.size_first[c], stats.size_tried[c], refused, stats.size_placed[c]);
      if (n < 0) break;
      used += static_cast<std::size_t>(n);
      for (int r = 0; r < core::kPatchRefusals && used < sizeof(buf); ++r) {
        n = snprintf(buf + used, sizeof(buf) - used, "%s%zu", r == 0 ? "" : " ", stats.size_refusals[c][r]);
        if (n < 0) break;
        used += static_cast<std::size_t>(n);
      }
      if (used < sizeof(buf)) used += static_cast<std::size_t>(snprintf(buf + used, sizeof(buf) - used, ")"));
    }
    ereport(DEBUG1, (errmsg("grow_patches: patch size at fronts (local terciles %.0f, %.0f m): %s; stratified redraws %zu",
                            stats.size_cut[0], stats.size_cut[1], buf, stats.size_redraws)));
  }
  ereport(DEBUG1, (errmsg("grow_patches: seams: %.0f m of patch streets glued; streets whose chord a merge "
                          "turned (under 2, 2-5, 5-10, 10-20, 20+ degrees): %zu, %zu, %zu, %zu, %zu streets, %.0f, "
                          "%.0f, %.0f, %.0f, %.0f m; fronts with a draw refused for its seam %zu, tried again without "
                          "the rule %zu; dead ends slid %zu",
                          stats.patch_length, stats.seam_count[0], stats.seam_count[1], stats.seam_count[2],
                          stats.seam_count[3], stats.seam_count[4], stats.seam_length[0], stats.seam_length[1],
                          stats.seam_length[2], stats.seam_length[3], stats.seam_length[4], stats.seam_refused,
                          stats.seam_relaxed, stats.seam_slid)));
  ereport(DEBUG1, (errmsg("grow_patches: grid: %zu statistical streets turned onto the ordered example's grid (%zu "
                          "of them leaving a street more than 15 degrees off it), %zu free-end snaps refused off "
                          "their street's line, %zu dead ends cut back instead of joined at a corner, %zu dead "
                          "ends' joins refused off the grid, %zu nodes settled onto the grid (or onto local "
                          "grids); %zu short dead ends cut back instead of joined (a weakly ordered example)",
                          stats.fallback_grid_turned, stats.fallback_askew_turned, stats.fallback_snaps_off_line,
                          stats.dangling_corners_cut, stats.joins_off_grid, stats.settled_onto_grid,
                          stats.short_ends_cut)));
  ereport(DEBUG1, (errmsg("grow_patches: corners: %zu gone on straight (the other street dropped; %zu of them "
                          "junctions an earlier drop left corners), %zu gone on to a T (%zu of them for the "
                          "junctions), %zu changes refused (a weakly ordered example's junctions per area)",
                          stats.corners_straightened, stats.corners_in_turn, stats.corners_completed,
                          stats.corner_tees, stats.corners_over_density)));
  ereport(DEBUG1, (errmsg("grow_patches: front crossings: %zu draws refused (a front made a crossing its patch's "
                          "junction is not, the output's crossing share at the example's %.3f); the joins across "
                          "aimed at a share of %.3f",
                          stats.front_crossings_refused, stats.example_crossing_share, stats.crossing_target)));
  ereport(DEBUG1, (errmsg("grow_patches: stems: %zu fronts drew a patch going on across a T's lone street, %zu "
                          "T's the placed patches were drawn to go on across; %zu patch streets left out as doubling "
                          "a street within 1.25 x snap; %zu fronts drew a patch with a connector end on the line of a "
                          "street across it, %zu such ends placed",
                          stats.stem_fronts, stats.stems_continued, stats.wide_redundant_dropped, stats.line_fronts,
                          stats.line_ends_placed)));
  ereport(DEBUG1, (errmsg("grow_patches: roundabouts: %zu placed; the first %.0f m ahead of its "
                          "front (0: at it), without %zu of its streets (spokes too near the network, inner streets "
                          "left hanging)",
                          stats.roundabouts_placed, stats.roundabout_ahead, stats.roundabout_spokes_dropped)));
  ereport(DEBUG1, (errmsg("grow_patches: spread order: %zu fronts drew without the patches already used, ten times "
                          "flatter (the output more ordered than its example)",
                          stats.spread_fronts)));
  ereport(DEBUG1, (errmsg("grow_patches: front dead ends: %zu draws refused (a patch's own dead ends, the output's "
                          "share of them at the example's %.3f), %zu fronts tried again without the rule; when the "
                          "growth stopped %zu own dead ends, %zu junctions",
                          stats.front_dead_ends_refused, stats.example_dead_end_share, stats.front_dead_ends_relaxed,
                          stats.own_dead_ends_grown, stats.junctions_grown)));
  ereport(DEBUG1, (errmsg("grow_patches: dangling joins: %zu refused (a junction over the example's per area), %zu "
                          "refused (a block under the example's 20th percentile)",
                          stats.dangling_dense, stats.dangling_small_blocks)));
  ereport(DEBUG1, (errmsg("grow_patches: teng-bidarra: %zu fronts bridged (%zu placements tried, %zu junction pairs "
                          "in the library; turned under 5, 5-20, 20+ degrees: %zu, %zu, %zu; %zu of their junctions "
                          "crossings in their patch); %zu initial patches "
                          "placed at %zu seed points (spacing %.0f m; turned under 5, 5-20, 20+ degrees: %zu, %zu, "
                          "%zu)",
                          stats.fronts_bridged, stats.bridge_tries, stats.bridge_pairs, stats.bridge_turns[0],
                          stats.bridge_turns[1], stats.bridge_turns[2], stats.bridge_crossing_ends, stats.initial_placed,
                          stats.initial_seed_points, stats.initial_spacing, stats.initial_turns[0],
                          stats.initial_turns[1], stats.initial_turns[2])));
  pg::emit_grown_rows(fcinfo, *rows);
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
