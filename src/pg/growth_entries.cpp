// Example-based growth: example edges in as parallel arrays (EWKB, road class, id), the region and
// obstacles as EWKB, seeds as coordinates, parameters as plain values (sql/80-growth.sql reads and
// checks the jsonb); grown edges out as rows ready for a model's axis table.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/geometry_checks.hpp"
#include "core/growth/grow_example.hpp"
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

// The C function's arguments, in order (sql/80-growth.sql).
enum Arg {
  kExampleGeoms, kExampleClasses, kExampleIds, kExampleSources, kRegion, kSeedsX, kSeedsY, kObstacles, kEpsilon,
  kRadius, kRotation, kSeed, kMaxEdges, kMatchLevels, kSnap, kMinAngle, kCandidates, kExisting, kParametric,
  kFallback, kKeepFrame, kCoherence, kCropMargin, kFill, kLength, kLengthDeviation, kMinLength, kMinDegree, kMaxDegree, kAngleDeviation, kRoadClass, kGuide,
  kGuideReach, kBlendMode, kBlendAngle, kBlendX, kBlendY, kBlendSigma, kWeightsGrid, kWeightsValues, kDirectionGrid,
  kDirectionValues, kArgs
};

}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_grow_example);
// See enum Arg; -> SETOF (id, from_node, to_node, road_class, origin, geom bytea).
Datum _streetgen_grow_example(PG_FUNCTION_ARGS) {
  // Phase 1.
  pg::require_argument_count(fcinfo, kArgs, "_streetgen_grow_example");
  static const char* const names[kArgs] = {
      "example", "example road classes", "example ids", "example sources", "region", "seeds x", "seeds y",
      "obstacles", "epsilon", "r", "rotation", "seed", "max_edges", "match_levels", "snap", "min_angle",
      "candidates", "existing", "parametric", "fallback", "keep_frame", "coherence", "crop_margin", "fill", "length", "length_deviation", "min_length",
      "min_degree", "max_degree", "angle_deviation", "road_class", "guide", "guide_reach", "blend",
      "blend_angle", "blend_points x", "blend_points y", "blend_sigma", "weights grid", "weights", "direction grid",
      "direction"};
  for (int a = kRegion; a < kArgs; ++a) {
    if (a != kSeedsX && a != kSeedsY && a != kObstacles && a != kExisting && a != kGuide && a != kBlendX &&
        a != kBlendY && a < kWeightsGrid && PG_ARGISNULL(a)) {
      pg::raise_null_argument(names[a]);
    }
  }
  pg::ArrayArg existing_arg = pg::array_arg(fcinfo, kExisting, BYTEAOID, "existing");
  auto* existing = static_cast<pg::ByteView*>(palloc0(sizeof(pg::ByteView) * (existing_arg.count > 0 ? existing_arg.count : 1)));
  int existing_count = 0;
  for (int i = 0; i < existing_arg.count; ++i) {
    if (!existing_arg.nulls[i]) existing[existing_count++] = pg::byte_view(existing_arg.values[i]);
  }
  pg::ArrayArg geoms = pg::array_arg(fcinfo, kExampleGeoms, BYTEAOID, "example");
  pg::ArrayArg classes = pg::array_arg(fcinfo, kExampleClasses, TEXTOID, "example road classes");
  pg::ArrayArg ids = pg::array_arg(fcinfo, kExampleIds, INT8OID, "example ids");
  pg::ArrayArg sources = pg::array_arg(fcinfo, kExampleSources, INT4OID, "example sources");
  pg::ArrayArg xs = pg::array_arg(fcinfo, kSeedsX, FLOAT8OID, "seeds x");
  pg::ArrayArg ys = pg::array_arg(fcinfo, kSeedsY, FLOAT8OID, "seeds y");
  pg::ArrayArg obstacle_arg = pg::array_arg(fcinfo, kObstacles, BYTEAOID, "obstacles");
  pg::ArrayArg blend_xs = pg::array_arg(fcinfo, kBlendX, FLOAT8OID, "blend_points x");
  pg::ArrayArg blend_ys = pg::array_arg(fcinfo, kBlendY, FLOAT8OID, "blend_points y");
  if (classes.count != 0) pg::require_same_length(geoms, "example", classes, "example road classes");
  if (ids.count != 0) pg::require_same_length(geoms, "example", ids, "example ids");
  if (sources.count != 0) pg::require_same_length(geoms, "example", sources, "example sources");
  pg::require_same_length(xs, "seeds x", ys, "seeds y");
  pg::require_same_length(blend_xs, "blend_points x", blend_ys, "blend_points y");

  struct ExampleArg {
    pg::ByteView geom;
    const char* road_class;
    std::int64_t id;
    int source;
  };
  auto* example = static_cast<ExampleArg*>(palloc0(sizeof(ExampleArg) * (geoms.count > 0 ? geoms.count : 1)));
  int example_count = 0;
  int example_sets = 1;
  for (int i = 0; i < geoms.count; ++i) {
    if (geoms.nulls[i]) continue;  // like an aggregate, NULL edges are skipped
    ExampleArg& e = example[example_count++];
    e.geom = pg::byte_view(geoms.values[i]);
    e.road_class = classes.count != 0 && !classes.nulls[i] ? TextDatumGetCString(classes.values[i]) : "unclassified";
    e.id = ids.count != 0 && !ids.nulls[i] ? DatumGetInt64(ids.values[i]) : i + 1;
    e.source = sources.count != 0 && !sources.nulls[i] ? DatumGetInt32(sources.values[i]) : 0;
    if (e.source < 0) {
      ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("example sources must be >= 0")));
    }
    if (e.source + 1 > example_sets) example_sets = e.source + 1;
  }
  int seed_count = 0;
  double* seed_xy = pg::xy_pairs(xs, ys, "a seed coordinate", &seed_count);
  int blend_count = 0;
  double* blend_xy = pg::xy_pairs(blend_xs, blend_ys, "a blend point coordinate", &blend_count);
  int obstacle_count = 0;
  pg::ByteView* obstacles = pg::byte_views(obstacle_arg, &obstacle_count);
  pg::ByteView region = pg::byte_view(PG_GETARG_DATUM(kRegion));
  pg::GridArg weights = pg::grid_arg(fcinfo, kWeightsGrid, kWeightsValues, "weights");
  pg::GridArg direction = pg::grid_arg(fcinfo, kDirectionGrid, kDirectionValues, "direction");
  bool has_guide = !PG_ARGISNULL(kGuide);
  pg::ByteView guide = has_guide ? pg::byte_view(PG_GETARG_DATUM(kGuide)) : pg::ByteView{nullptr, 0};
  core::GrowParams params;
  params.epsilon = PG_GETARG_FLOAT8(kEpsilon);
  params.radius = PG_GETARG_FLOAT8(kRadius);
  params.rotation = PG_GETARG_BOOL(kRotation);
  params.seed = static_cast<std::uint64_t>(PG_GETARG_INT64(kSeed));
  int max_edges = PG_GETARG_INT32(kMaxEdges);
  params.match_levels = PG_GETARG_BOOL(kMatchLevels);
  params.snap = PG_GETARG_FLOAT8(kSnap);
  params.min_angle = PG_GETARG_FLOAT8(kMinAngle);
  int candidates = PG_GETARG_INT32(kCandidates);
  params.parametric = PG_GETARG_BOOL(kParametric);
  params.fallback = PG_GETARG_BOOL(kFallback);
  params.keep_frame = PG_GETARG_BOOL(kKeepFrame);
  params.coherence = PG_GETARG_FLOAT8(kCoherence);
  params.crop_margin = PG_GETARG_FLOAT8(kCropMargin);
  params.fill = PG_GETARG_BOOL(kFill);
  params.shape.length = PG_GETARG_FLOAT8(kLength);
  params.shape.length_deviation = PG_GETARG_FLOAT8(kLengthDeviation);
  params.shape.min_length = PG_GETARG_FLOAT8(kMinLength);
  params.shape.min_degree = PG_GETARG_INT32(kMinDegree);
  params.shape.max_degree = PG_GETARG_INT32(kMaxDegree);
  params.shape.angle_deviation = PG_GETARG_FLOAT8(kAngleDeviation);
  const char* road_class = TextDatumGetCString(PG_GETARG_DATUM(kRoadClass));
  params.guide_reach = PG_GETARG_FLOAT8(kGuideReach);
  const char* blend_mode = TextDatumGetCString(PG_GETARG_DATUM(kBlendMode));
  params.blend.mode = pg::blend_mode_of(blend_mode);
  params.blend.angle = PG_GETARG_FLOAT8(kBlendAngle);
  params.blend.sigma = PG_GETARG_FLOAT8(kBlendSigma);
  if (max_edges <= 0) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("max_edges must be > 0"),
                    errdetail("It is %d.", max_edges)));
  }
  if (candidates <= 0) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("candidates must be > 0"),
                    errdetail("It is %d.", candidates)));
  }
  params.max_edges = static_cast<std::size_t>(max_edges);
  params.candidates = static_cast<std::size_t>(candidates);
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<std::vector<pg::GrownRow>>::create();
  core::GrowStats stats;  // plain data: reported at DEBUG1 in phase 3

  // Phase 2.
  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    core::GrowInput input;
    input.example.reserve(example_count);
    core::InterruptPoller poller(1024);
    for (int i = 0; i < example_count; ++i) {
      poller.tick();
      std::string name = "example edge " + std::to_string(i + 1);
      core::SridGeometry g = core::read_ewkb(geos, example[i].geom.data, example[i].geom.size, name.c_str());
      std::vector<core::Polyline> lines;
      core::append_linestrings(geos, g.geom.get(), name, "example edges must be LineStrings or MultiLineStrings", "", lines);
      for (core::Polyline& line : lines) {
        input.example.push_back({std::move(line), example[i].road_class, example[i].id, example[i].source});
      }
    }
    std::vector<core::SridGeometry> region_and_obstacles;
    int srid = pg::read_region_and_obstacles(geos, region, obstacles, obstacle_count, input, region_and_obstacles);
    for (int i = 0; i < existing_count; ++i) {
      poller.tick();
      std::string name = "existing edge " + std::to_string(i + 1);
      core::SridGeometry g = core::read_ewkb(geos, existing[i].data, existing[i].size, name.c_str());
      core::append_linestrings(geos, g.geom.get(), name, "example edges must be LineStrings or MultiLineStrings", "", input.existing);
    }
    for (int i = 0; i < seed_count; ++i) input.seeds.push_back({seed_xy[2 * i], seed_xy[2 * i + 1]});
    for (int i = 0; i < blend_count; ++i) params.blend.points.push_back({blend_xy[2 * i], blend_xy[2 * i + 1]});
    params.shape.road_class = road_class;
    if (has_guide) {
      core::SridGeometry g = core::read_ewkb(geos, guide.data, guide.size, "guide");
      core::append_linestrings(geos, g.geom.get(), "guide", "guide must be a LineString or MultiLineString", "",
                               input.guide);
    }
    pg::to_field(weights, input.weights);
    pg::to_field(direction, input.direction);
    core::GrowResult result = core::grow_example(geos, input, params);
    stats = result.stats;
    std::vector<pg::GrownRow> out;
    out.reserve(result.edges.size());
    for (const core::GrownEdge& e : result.edges) {
      // Which example an edge came from: grow_example:<id>, with several grow_example:<k>:<id>;
      // parametric growth (alone or as the fallback): grow_parametric.
      std::string origin = e.example < 0       ? std::string("grow_parametric")
                           : example_sets > 1 ? "grow_example:" + std::to_string(e.example + 1) + ":" +
                                                     std::to_string(e.example_id)
                                               : "grow_example:" + std::to_string(e.example_id);
      out.push_back(pg::grown_row(e, std::move(origin), srid));
    }
    rows.emplace(std::move(out));
  });
  pg::raise_if_failed(error);

  // Phase 3.
  ereport(DEBUG1, (errmsg("grow: %zu steps, %zu coherent, %zu unmatched, %zu parametric fallback, %zu guided "
                          "(%zu by the direction raster), %zu chosen by the weight raster, %zu proposals, "
                          "%zu accepted, %zu snapped, %zu clipped, %zu rejected, %zu pruned, %zu reseeds, %zu restarts; "
                          "example dead-end share %.3f, small block %.1f m (%zu joins refused), "
                          "median block %.1f m (%zu failed fronts' joins refused), "
                          "%zu sibling joins refused, %zu short example segments contracted, %zu segments under "
                          "0.5 m dropped",
                          stats.steps, stats.coherent, stats.unmatched, stats.fallback, stats.guided, stats.directed,
                          stats.weighted, stats.proposals,
                          stats.accepted, stats.snapped, stats.clipped, stats.rejected, stats.pruned, stats.reseeds,
                          stats.restarts, stats.dead_end_share, stats.small_block, stats.small_cycles_refused,
                          stats.median_block, stats.median_joins_refused, stats.sibling_joins_refused,
                          stats.example_contracted, stats.short_segments_dropped)));
  // The junction mix: where dead ends and 4-way junctions are made or lost.
  ereport(DEBUG1, (errmsg("grow junctions: dead-end copies %zu, made %zu, lost %zu/%zu/%zu/%zu (angle, clipped, "
                          "short, crowded); node joins by degree 0/1/2/3/4+: snap %zu/%zu/%zu/%zu/%zu, contact "
                          "%zu/%zu/%zu/%zu/%zu, front %zu/%zu/%zu/%zu/%zu; splits snap %zu, contact %zu, front %zu; "
                          "mix refused at degree 2/3/4+ %zu/%zu/%zu, new T's refused %zu (%zu at the example's "
                          "junction density); fronts failed %zu: ahead "
                          "node %zu, ahead split %zu, near node %zu (%zu off their heading refused), dead end %zu "
                          "(%zu cut back when finished), pruned %zu; "
                          "copies of a degree-3 "
                          "node ending at degree "
                          "1/2/3/4+ %zu/%zu/%zu/%zu, of a degree-4+ node %zu/%zu/%zu/%zu",
                          stats.dead_end_proposals, stats.dead_end_made, stats.dead_end_lost[0],
                          stats.dead_end_lost[1], stats.dead_end_lost[2], stats.dead_end_lost[3],
                          stats.node_joins[0][0], stats.node_joins[0][1], stats.node_joins[0][2],
                          stats.node_joins[0][3], stats.node_joins[0][4], stats.node_joins[1][0],
                          stats.node_joins[1][1], stats.node_joins[1][2], stats.node_joins[1][3],
                          stats.node_joins[1][4], stats.node_joins[2][0], stats.node_joins[2][1],
                          stats.node_joins[2][2], stats.node_joins[2][3], stats.node_joins[2][4], stats.splits[0],
                          stats.splits[1], stats.splits[2], stats.mix_refused[2], stats.mix_refused[3],
                          stats.mix_refused[4], stats.new_ts_refused, stats.dense_ts_refused, stats.fronts_failed,
                          stats.fronts_ahead_node,
                          stats.fronts_ahead_split, stats.fronts_near_node, stats.fronts_off_heading_refused,
                          stats.fronts_dead_end, stats.fronts_trimmed,
                          stats.fronts_pruned, stats.copy_result[3][1], stats.copy_result[3][2],
                          stats.copy_result[3][3], stats.copy_result[3][4], stats.copy_result[4][1],
                          stats.copy_result[4][2], stats.copy_result[4][3], stats.copy_result[4][4])));
  ereport(DEBUG1, (errmsg("grow front corners: kept %zu, taken back %zu, straight on %zu",
                          stats.front_corners_kept, stats.front_corners_taken_back, stats.front_corners_straight)));
  ereport(DEBUG1, (errmsg("grow rejections: angle %zu, clipped %zu, first half %zu, snap node %zu, snap edge %zu, "
                          "crowded %zu, contact node %zu, no new T %zu, contact short %zu, split %zu; copied dead "
                          "ends joined by snap %zu, contact %zu, front %zu",
                          stats.reject_reason[0], stats.reject_reason[1], stats.reject_reason[2],
                          stats.reject_reason[3], stats.reject_reason[4], stats.reject_reason[5],
                          stats.reject_reason[6], stats.reject_reason[7], stats.reject_reason[8],
                          stats.reject_reason[9], stats.dead_ends_joined[0], stats.dead_ends_joined[1],
                          stats.dead_ends_joined[2])));
  pg::emit_grown_rows(fcinfo, *rows);
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
