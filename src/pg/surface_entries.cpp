// The street surface SRF: axes in as parallel arrays (EWKB geometries), every output of the
// StreetGen engine out as rows tagged by kind (node, section, corner, intersection, issue).
// sql/60-surfaces.sql turns them into tables (generate) or geometries (street_surfaces).
#include <malloc.h>  // malloc_trim (glibc)
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/geometry_checks.hpp"
#include "core/streets/street_surfaces.hpp"
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

constexpr int kSettingCount = 13;  // the order of SurfaceSettings' fields, see _settings_vector in 25-settings.sql

struct AxisArg {  // plain data, filled in phase 1
  std::int64_t id;
  const std::uint8_t* ewkb;
  std::size_t ewkb_size;
  double width;
  double speed;
  int layer;
  bool has_radius;
  double radius;
  int lanes;               // 0: unknown
  bool oneway;
  const char* lane_tags;   // "key=value" lines (palloc'd), or null
  double sidewalk_left;    // m, 0: none
  double sidewalk_right;
};

struct OutRow {
  const char* kind;
  std::optional<std::int64_t> node_id, to_node, axis_id, axis_b;
  std::optional<std::int64_t> part, part_b;
  std::optional<int> degree, layer;
  std::optional<bool> end_a, end_b;
  std::string status, detail;
  std::optional<double> radius, radius_wanted, start_border, end_border;
  std::optional<std::vector<std::int64_t>> axis_ids;
  core::Bytes geom, geom2, geom3;  // empty: NULL
  std::optional<int> item;          // lane index, marking position
  std::optional<double> width;      // lane width
  std::string direction;            // lane direction
};
constexpr int kColumns = 24;

// "key=value" lines (see _compute_model) into the lane tags; a line without '=' is skipped.
std::map<std::string, std::string> parse_lane_tags(const char* text) {
  std::map<std::string, std::string> tags;
  if (text == nullptr) return tags;
  std::string all(text);
  std::size_t start = 0;
  while (start <= all.size()) {
    std::size_t end = all.find('\n', start);
    if (end == std::string::npos) end = all.size();
    std::string line = all.substr(start, end - start);
    std::size_t eq = line.find('=');
    if (eq != std::string::npos && eq > 0) tags[line.substr(0, eq)] = line.substr(eq + 1);
    start = end + 1;
  }
  return tags;
}

core::Polyline read_axis_line(core::GeosContext& geos, const AxisArg& arg, int& srid, bool first) {
  std::string name = "geometry of axis " + std::to_string(arg.id);
  core::SridGeometry g = core::read_ewkb(geos, arg.ewkb, arg.ewkb_size, name.c_str());
  core::require_axis_line(geos, g.geom.get(), name.c_str());
  if (first) {
    srid = g.srid;
  } else if (g.srid != srid) {
    core::throw_invalid_argument("axes must share one SRID",
                                 "Axis " + std::to_string(arg.id) + " has SRID " + std::to_string(g.srid) +
                                     ", the first axis " + std::to_string(srid) + ".");
  }
  const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(geos.handle(), g.geom.get());
  unsigned int n = 0;
  GEOSCoordSeq_getSize_r(geos.handle(), seq, &n);
  core::Polyline line(n);
  for (unsigned int i = 0; i < n; ++i) GEOSCoordSeq_getXY_r(geos.handle(), seq, i, &line[i].x, &line[i].y);
  return line;
}

// The engine's result and how far its rows have been emitted. Rows are made and emitted a chunk
// at a time, and every geometry is freed once written: a whole city's rows at once (an OutRow is
// ~450 bytes) beside the GEOS result they come from raised the backend's peak by half again
// (Reisterstown, 4,560 axes: +55 MB over the engine's own peak).
struct SurfaceEmission {
  // The engine between its two steps: the lanes and markings are written out after the first
  // and freed before the sidewalks are built (SurfaceRun).
  std::unique_ptr<core::SurfaceRun> run;
  core::SurfaceResult result;
  std::size_t kind = 0, next = 0;  // the list being emitted (case of next_rows), its next item
  std::size_t last_kind = 0;       // the last list of this pass
  std::vector<OutRow> chunk;
  int srid = 0;  // of the axes, for the rows' EWKB
};
// The lists, by their case in next_rows: the first pass writes the lanes (5) and markings (6)
// the engine's first step made, the second everything else.
constexpr std::size_t kFirstPassKinds[2] = {5, 6};
constexpr std::size_t kSecondPassKinds[2] = {0, 8};
constexpr std::size_t kChunkRows = 2048;

// Fills emission.chunk with the next rows (empty at the end), releasing what they were made from.
void next_rows(core::GeosContext& geos, SurfaceEmission& emission) {
  const int srid = emission.srid;
  core::SurfaceResult& r = emission.result;
  std::vector<OutRow>& rows = emission.chunk;
  rows.clear();
  auto take = [&](auto& items, auto&& make_row) {
    // items of one kind: emit from emission.next, a chunk at most; false when the chunk is full
    while (emission.next < items.size()) {
      if (rows.size() >= kChunkRows) return false;
      make_row(items[emission.next]);
      ++emission.next;
    }
    items.clear();
    items.shrink_to_fit();
    ++emission.kind;
    emission.next = 0;
    return true;
  };
  auto geometry_bytes = [&](core::GeomPtr& g) {  // its EWKB; the geometry is freed
    core::Bytes bytes = core::write_ewkb(geos, g.get(), srid);
    g.reset();
    return bytes;
  };
  auto handed_over = [&](core::GeomPtr& g, core::Bytes& ewkb) {  // written by the engine already, or now
    return g ? geometry_bytes(g) : std::move(ewkb);
  };
  for (;;) {
    bool more = true;
    if (emission.kind > emission.last_kind) return;  // this pass emitted
    switch (emission.kind) {
      case 0:
        more = take(r.nodes, [&](core::NodeResult& n) {
          OutRow row{"node"};
          row.node_id = n.id;
          row.degree = n.degree;
          row.layer = n.layer;
          row.axis_ids = std::move(n.axis_ids);
          double xy[2] = {n.position.x, n.position.y};
          row.geom = core::write_ewkb_coordinates(core::WkbType::point, xy, 1, srid);
          rows.push_back(std::move(row));
        });
        break;
      case 1:
        more = take(r.sections, [&](core::SectionResult& s) {
          OutRow row{"section"};
          row.axis_id = s.axis_id;
          row.part = s.part;
          row.node_id = s.from_node;
          row.to_node = s.to_node;
          row.status = s.status;
          row.start_border = s.start_border;
          row.end_border = s.end_border;
          if (s.surface) row.geom = geometry_bytes(s.surface);
          row.geom2 = core::write_ewkb_polyline(core::WkbType::line_string, s.centre_line, srid);
          core::Polyline().swap(s.centre_line);
          rows.push_back(std::move(row));
        });
        break;
      case 2:
        more = take(r.corners, [&](core::CornerResult& c) {
          OutRow row{"corner"};
          row.node_id = c.node_id;
          row.axis_id = c.a.axis_id;
          row.part = c.a.part;
          row.end_a = c.a.at_end;
          row.axis_b = c.b.axis_id;
          row.part_b = c.b.part;
          row.end_b = c.b.at_end;
          row.status = c.status;
          row.radius = c.radius;
          row.radius_wanted = c.radius_wanted;
          if (c.centre && c.radius > 0.0) {
            double arc[6] = {c.arc[0].x, c.arc[0].y, c.arc[1].x, c.arc[1].y, c.arc[2].x, c.arc[2].y};
            row.geom = core::write_ewkb_coordinates(core::WkbType::circular_string, arc, 3, srid);
            row.geom2 = core::write_ewkb_polyline(core::WkbType::line_string, c.arc_points, srid);
            double xy[2] = {c.centre->x, c.centre->y};
            row.geom3 = core::write_ewkb_coordinates(core::WkbType::point, xy, 1, srid);
          } else if (!c.arc_points.empty()) {  // a sharp corner: its point
            double xy[2] = {c.arc_points.front().x, c.arc_points.front().y};
            row.geom3 = core::write_ewkb_coordinates(core::WkbType::point, xy, 1, srid);
          }
          core::Polyline().swap(c.arc_points);
          rows.push_back(std::move(row));
        });
        break;
      case 3:
        more = take(r.intersections, [&](core::IntersectionResult& i) {
          OutRow row{"intersection"};
          row.node_id = i.node_id;
          row.status = i.status;
          row.geom = geometry_bytes(i.surface);
          rows.push_back(std::move(row));
        });
        break;
      case 4:
        more = take(r.issues, [&](core::TopologyIssue& issue) {
          OutRow row{"issue"};
          row.axis_id = issue.axis_id;
          row.part = issue.part;
          row.node_id = issue.node_id;
          row.status = issue.kind;
          row.detail = issue.detail;
          rows.push_back(std::move(row));
        });
        break;
      case 5:
        more = take(r.lanes, [&](core::LaneResult& l) {
          OutRow row{"lane"};
          row.axis_id = l.axis_id;
          row.part = l.part;
          row.item = l.index;
          row.status = l.spec.type;
          row.direction = l.spec.direction;
          row.width = l.spec.width;
          row.detail = l.spec.turn;
          row.geom = handed_over(l.surface, l.ewkb);
          rows.push_back(std::move(row));
        });
        break;
      case 7:
        more = take(r.sidewalks, [&](core::SidewalkResult& w) {
          OutRow row{"sidewalk"};
          if (w.node_id != 0) {
            row.node_id = w.node_id;
          } else {
            row.axis_id = w.axis_id;
            row.part = w.part;
          }
          row.status = w.side;
          row.width = w.width;
          row.geom = handed_over(w.surface, w.ewkb);
          rows.push_back(std::move(row));
        });
        break;
      case 8:
        more = take(r.crossings, [&](core::CrossingResult& c) {
          OutRow row{"crossing"};
          row.axis_id = c.axis_id;
          row.part = c.part;
          row.node_id = c.node_id;
          row.item = c.position;
          row.width = c.width;
          row.geom = handed_over(c.surface, c.ewkb);
          rows.push_back(std::move(row));
        });
        break;
      case 6:
        more = take(r.markings, [&](core::MarkingResult& m) {
          OutRow row{"marking"};
          row.axis_id = m.axis_id;
          row.part = m.part;
          row.item = m.position;
          row.status = m.kind;
          row.detail = m.style;
          row.geom = handed_over(m.line, m.ewkb);
          rows.push_back(std::move(row));
        });
        break;
      default:
        return;  // everything emitted
    }
    if (!more) return;  // the chunk is full
  }
}

Datum bytes_or_null(const core::Bytes& b, bool& isnull) {
  isnull = b.empty();
  return isnull ? Datum(0) : PointerGetDatum(pg::to_bytea(b));
}

}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_street_surfaces);
// (ids int8[], geoms bytea[], widths float8[], speeds float8[], layers int4[],
//  radius_overrides float8[], settings float8[10], override_nodes int8[], override_keys int8[],
//  override_radii float8[], lanes int4[], oneways bool[], lane_tags text[], sidewalk_left float8[],
//  sidewalk_right float8[]) -> SETOF record (see kColumns)
Datum _streetgen_street_surfaces(PG_FUNCTION_ARGS) {
  // Phase 1: arguments into plain arrays.
  pg::ArrayArg ids = pg::array_arg(fcinfo, 0, INT8OID, "ids");
  pg::ArrayArg geoms = pg::array_arg(fcinfo, 1, BYTEAOID, "geoms");
  pg::ArrayArg widths = pg::array_arg(fcinfo, 2, FLOAT8OID, "widths");
  pg::ArrayArg speeds = pg::array_arg(fcinfo, 3, FLOAT8OID, "speeds");
  pg::ArrayArg layers = pg::array_arg(fcinfo, 4, INT4OID, "layers");
  pg::ArrayArg radii = pg::array_arg(fcinfo, 5, FLOAT8OID, "radius_overrides");
  pg::ArrayArg settings_arg = pg::array_arg(fcinfo, 6, FLOAT8OID, "settings");
  pg::ArrayArg override_nodes = pg::array_arg(fcinfo, 7, INT8OID, "override_nodes");
  pg::ArrayArg override_keys = pg::array_arg(fcinfo, 8, INT8OID, "override_keys");
  pg::ArrayArg override_radii = pg::array_arg(fcinfo, 9, FLOAT8OID, "override_radii");
  pg::ArrayArg lane_counts = pg::array_arg(fcinfo, 10, INT4OID, "lanes");
  pg::ArrayArg oneways = pg::array_arg(fcinfo, 11, BOOLOID, "oneways");
  pg::ArrayArg lane_tags = pg::array_arg(fcinfo, 12, TEXTOID, "lane_tags");
  pg::ArrayArg sidewalk_left = pg::array_arg(fcinfo, 13, FLOAT8OID, "sidewalk_left");
  pg::ArrayArg sidewalk_right = pg::array_arg(fcinfo, 14, FLOAT8OID, "sidewalk_right");
  pg::require_same_length(ids, "ids", geoms, "geoms");
  pg::require_same_length(ids, "ids", widths, "widths");
  pg::require_same_length(ids, "ids", speeds, "speeds");
  if (layers.count != 0) pg::require_same_length(ids, "ids", layers, "layers");
  if (radii.count != 0) pg::require_same_length(ids, "ids", radii, "radius_overrides");
  if (lane_counts.count != 0) pg::require_same_length(ids, "ids", lane_counts, "lanes");
  if (oneways.count != 0) pg::require_same_length(ids, "ids", oneways, "oneways");
  if (lane_tags.count != 0) pg::require_same_length(ids, "ids", lane_tags, "lane_tags");
  if (sidewalk_left.count != 0) pg::require_same_length(ids, "ids", sidewalk_left, "sidewalk_left");
  if (sidewalk_right.count != 0) pg::require_same_length(ids, "ids", sidewalk_right, "sidewalk_right");
  pg::require_same_length(override_nodes, "override_nodes", override_radii, "override_radii");
  if (override_keys.count != 6 * override_nodes.count) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("override_keys must hold six values per override")));
  }
  if (settings_arg.count != kSettingCount) {
    ereport(ERROR, (errcode(ERRCODE_INVALID_PARAMETER_VALUE), errmsg("settings must hold %d values", kSettingCount)));
  }
  double setting_values[kSettingCount];
  for (int i = 0; i < kSettingCount; ++i) {
    if (settings_arg.nulls[i]) pg::raise_null_argument("a setting");
    setting_values[i] = DatumGetFloat8(settings_arg.values[i]);
  }
  auto* axes = static_cast<AxisArg*>(palloc0(sizeof(AxisArg) * std::max(ids.count, 1)));
  for (int i = 0; i < ids.count; ++i) {
    if (ids.nulls[i]) pg::raise_null_argument("an axis id");
    AxisArg& a = axes[i];
    a.id = DatumGetInt64(ids.values[i]);
    if (geoms.nulls[i] || widths.nulls[i] || speeds.nulls[i]) {
      ereport(ERROR, (errcode(ERRCODE_NULL_VALUE_NOT_ALLOWED),
                      errmsg("axis %lld has a NULL geometry, roadway width or speed", static_cast<long long>(a.id))));
    }
    bytea* g = DatumGetByteaPP(geoms.values[i]);
    a.ewkb = reinterpret_cast<const std::uint8_t*>(VARDATA_ANY(g));
    a.ewkb_size = VARSIZE_ANY_EXHDR(g);
    a.width = DatumGetFloat8(widths.values[i]);
    a.speed = DatumGetFloat8(speeds.values[i]);
    a.layer = layers.count != 0 && !layers.nulls[i] ? DatumGetInt32(layers.values[i]) : 0;
    a.has_radius = radii.count != 0 && !radii.nulls[i];
    a.radius = a.has_radius ? DatumGetFloat8(radii.values[i]) : 0.0;
    a.lanes = lane_counts.count != 0 && !lane_counts.nulls[i] ? DatumGetInt32(lane_counts.values[i]) : 0;
    a.oneway = oneways.count != 0 && !oneways.nulls[i] && DatumGetBool(oneways.values[i]);
    a.lane_tags = lane_tags.count != 0 && !lane_tags.nulls[i] ? TextDatumGetCString(lane_tags.values[i]) : nullptr;
    a.sidewalk_left = sidewalk_left.count != 0 && !sidewalk_left.nulls[i] ? DatumGetFloat8(sidewalk_left.values[i]) : 0.0;
    a.sidewalk_right = sidewalk_right.count != 0 && !sidewalk_right.nulls[i] ? DatumGetFloat8(sidewalk_right.values[i]) : 0.0;
  }
  auto* overrides = static_cast<core::CornerOverride*>(palloc0(sizeof(core::CornerOverride) * std::max(override_nodes.count, 1)));
  for (int i = 0; i < override_nodes.count; ++i) {
    for (int k = 0; k < 6; ++k) {
      if (override_keys.nulls[6 * i + k]) pg::raise_null_argument("an override key");
    }
    if (override_nodes.nulls[i] || override_radii.nulls[i]) pg::raise_null_argument("an override");
    auto key = [&](int k) { return DatumGetInt64(override_keys.values[6 * i + k]); };
    overrides[i].node_id = DatumGetInt64(override_nodes.values[i]);
    overrides[i].a = {key(0), key(1), key(2) != 0};
    overrides[i].b = {key(3), key(4), key(5) != 0};
    overrides[i].radius = DatumGetFloat8(override_radii.values[i]);
  }
  int axis_count = ids.count;
  int override_count = override_nodes.count;
  // (rows past the first 256 kB go to the tuplestore's file: a city's rows are written while
  // the engine's result is held, at its peak; see init_materialized_srf)
  pg::init_materialized_srf(fcinfo, pg::kSrfMemoryKb);
  auto emission = pg::OwnedResult<SurfaceEmission>::create();

  // Phase 2: the engine.
  pg::CallError error;
  bool built_details = true;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    core::SurfaceSettings settings;
    double* fields[kSettingCount - 1] = {&settings.snap_tolerance, &settings.turn_speed_ratio, &settings.lateral_acceleration,
                                     &settings.min_radius, &settings.max_radius, &settings.misplaced_factor,
                                     &settings.min_border_distance, &settings.transition_length_per_metre,
                                     &settings.min_transition_length, &settings.max_transition_deflection_deg,
                                     &settings.crossing_width, &settings.crossing_max_speed_kmh};
    for (int i = 0; i < kSettingCount - 1; ++i) *fields[i] = setting_values[i];
    settings.details = setting_values[kSettingCount - 1] != 0.0;  // (a boolean, as 1 or 0)
    built_details = settings.details;
    std::vector<core::SurfaceAxis> input;
    input.reserve(axis_count);
    int srid = 0;
    for (int i = 0; i < axis_count; ++i) {
      core::SurfaceAxis a;
      a.id = axes[i].id;
      a.line = read_axis_line(geos, axes[i], srid, i == 0);
      a.roadway_width = axes[i].width;
      a.speed_kmh = axes[i].speed;
      a.layer = axes[i].layer;
      if (axes[i].has_radius) a.radius_override = axes[i].radius;
      if (axes[i].lanes > 0) a.lane_input.lanes = axes[i].lanes;
      a.lane_input.oneway = axes[i].oneway;
      a.lane_input.tags = parse_lane_tags(axes[i].lane_tags);
      a.sidewalk_left = axes[i].sidewalk_left;
      a.sidewalk_right = axes[i].sidewalk_right;
      input.push_back(std::move(a));
    }
    std::vector<core::CornerOverride> corner_overrides(overrides, overrides + override_count);
    SurfaceEmission& out = emission.emplace();
    core::SurfaceOutput output;
    output.ewkb_srid = srid;  // (the rows are EWKB anyway: the engine writes lanes to sidewalks as it goes)
    out.run = std::make_unique<core::SurfaceRun>(geos, std::move(input), std::move(corner_overrides), settings, output);
    out.run->through_lanes();
    out.result.lanes = std::move(out.run->lanes());
    out.result.markings = std::move(out.run->markings());
    out.srid = srid;
  });
  pg::raise_if_failed(error);

  // Phases 2 and 3 in turn, a chunk of rows at a time: rows from the result (C++), then out
  // (PostgreSQL; each row's datums in a context reset after tuplestore_putvalues has copied them).
  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  MemoryContext row_context = AllocSetContextCreate(CurrentMemoryContext, "streetgen surface row", ALLOCSET_DEFAULT_SIZES);
  // Writes the rows of kinds [first, last] (cases of next_rows), a chunk at a time.
  auto emit_rows = [&](std::size_t first, std::size_t last) {
    emission->kind = first;
    emission->last_kind = last;
    emission->next = 0;
    for (;;) {
      pg::guarded_call(error, [&] { next_rows(pg::backend_geos(), *emission); });
      pg::raise_if_failed(error);
      if (emission->chunk.empty()) break;
      for (const OutRow& row : emission->chunk) {
        MemoryContext caller_context = MemoryContextSwitchTo(row_context);
        Datum v[kColumns];
        bool null[kColumns];
        auto put_i64 = [&](int c, const std::optional<std::int64_t>& x) {
          null[c] = !x;
          v[c] = x ? Int64GetDatum(*x) : Datum(0);
        };
        auto put_i32 = [&](int c, const std::optional<int>& x) {
          null[c] = !x;
          v[c] = x ? Int32GetDatum(*x) : Datum(0);
        };
        auto put_bool = [&](int c, const std::optional<bool>& x) {
          null[c] = !x;
          v[c] = x ? BoolGetDatum(*x) : Datum(0);
        };
        auto put_f8 = [&](int c, const std::optional<double>& x) {
          null[c] = !x;
          v[c] = x ? Float8GetDatum(*x) : Datum(0);
        };
        auto put_text = [&](int c, const std::string& s) {
          null[c] = s.empty();
          v[c] = s.empty() ? Datum(0) : CStringGetTextDatum(s.c_str());
        };
        v[0] = CStringGetTextDatum(row.kind);
        null[0] = false;
        put_i64(1, row.node_id);
        put_i64(2, row.to_node);
        put_i64(3, row.axis_id);
        put_i64(4, row.part);
        put_bool(5, row.end_a);
        put_i64(6, row.axis_b);
        put_i64(7, row.part_b);
        put_bool(8, row.end_b);
        put_text(9, row.status);
        put_text(10, row.detail);
        put_i32(11, row.degree);
        put_i32(12, row.layer);
        put_f8(13, row.radius);
        put_f8(14, row.radius_wanted);
        put_f8(15, row.start_border);
        put_f8(16, row.end_border);
        if (row.axis_ids) {
          int n = static_cast<int>(row.axis_ids->size());
          auto* elems = static_cast<Datum*>(palloc(sizeof(Datum) * std::max(n, 1)));
          for (int k = 0; k < n; ++k) elems[k] = Int64GetDatum((*row.axis_ids)[k]);
          v[17] = PointerGetDatum(construct_array(elems, n, INT8OID, 8, FLOAT8PASSBYVAL, TYPALIGN_DOUBLE));
          null[17] = false;
        } else {
          v[17] = Datum(0);
          null[17] = true;
        }
        v[18] = bytes_or_null(row.geom, null[18]);
        v[19] = bytes_or_null(row.geom2, null[19]);
        v[20] = bytes_or_null(row.geom3, null[20]);
        put_i32(21, row.item);
        put_f8(22, row.width);
        put_text(23, row.direction);
        MemoryContextSwitchTo(caller_context);
        tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, v, null);
        MemoryContextReset(row_context);
      }
    }
  };
  // The lanes and markings, then the rest of the engine, then everything else.
  emit_rows(kFirstPassKinds[0], kFirstPassKinds[1]);
  std::vector<OutRow>().swap(emission->chunk);  // (2,048 rows' room, not held through the engine's peak)
  pg::guarded_call(error, [&] {
    core::SurfaceResult rest = emission->run->finish();
    emission->run.reset();
    emission->result = std::move(rest);
  });
  pg::raise_if_failed(error);
  const core::SurfaceRunStats& t = emission->result.stats;
  elog(DEBUG1,
       "streetgen: surfaces in CPU seconds: topology %.3f, corners %.3f, sections %.3f, lanes %.3f, junctions %.3f, "
       "sidewalks %.3f",
       t.topology, t.corners, t.sections, t.lanes, t.junctions, t.sidewalks);
  elog(DEBUG1,
       "streetgen: junction sidewalks %ld by corner (%ld corners of them by buffer), %ld by buffer; %ld sidewalks "
       "without an overlay; %ld sidewalk claims, at most %ld held at once; their first build %.3f CPU seconds",
       t.junction_sidewalks_by_corner, t.junction_corners_by_buffer, t.junction_sidewalks_by_buffer,
       t.sidewalks_without_overlay, t.sidewalk_claims, t.sidewalk_claims_held_peak, t.sidewalk_claim_builds);
  elog(DEBUG1,
       "streetgen: junctions under sections: %ld touching them, %ld touching but for rounding, %ld by an overlay",
       t.junctions_touching, t.junctions_touching_but_for_rounding, t.junction_overlays);
  elog(DEBUG1,
       "streetgen: near pairs of sections: %ld touching, %ld by an overlay; of junctions: %ld touching, %ld by an overlay",
       t.section_pairs_touching, t.section_pair_overlays, t.junction_pairs_touching, t.junction_pair_overlays);
  emit_rows(kSecondPassKinds[0], kSecondPassKinds[1]);
  emission.release();
  MemoryContextDelete(row_context);
  // The engine's heap is free now, but glibc keeps it mapped (freed as many small chunks, most
  // of them below the top of the heap). With details, the blocks come next and would stack their
  // peak on it: handed back to the system, Reisterstown's import peaks at 64.4-64.6 MB (67-68 kept).
  // Without details nothing after the store needs it (Reisterstown's surfaces-only peak is 54 MB
  // either way), and the trim itself is a madvise per free run of pages: 20-40 ms on München,
  // 120-150 ms on Reisterstown, each page faulting in again when the store reuses it.
  // An edit's local recompute (tens of axes) frees little, but the trim still walks the whole
  // heap a city's run left fragmented: 300-450 madvise calls an edit on Reisterstown, for nothing.
  const bool trim = built_details && axis_count >= pg::kTrimMinAxes;
  if (trim) malloc_trim(0);
  elog(DEBUG1, "streetgen: surfaces of %d axes, heap %s", axis_count, trim ? "trimmed" : "kept");
  PG_RETURN_NULL();
}

PG_FUNCTION_INFO_V1(_streetgen_street_parking);
// (lane_tags text) -> float8[2]: the roadway street parking takes left and right, m.
Datum _streetgen_street_parking(PG_FUNCTION_ARGS) {
  const char* lines = PG_ARGISNULL(0) ? nullptr : TextDatumGetCString(PG_GETARG_DATUM(0));
  std::pair<double, double> widths{0.0, 0.0};
  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::LaneInput in;
    in.tags = parse_lane_tags(lines);
    widths = core::street_parking_widths(in);
  });
  pg::raise_if_failed(error);
  Datum elems[2] = {Float8GetDatum(widths.first), Float8GetDatum(widths.second)};
  PG_RETURN_ARRAYTYPE_P(construct_array(elems, 2, FLOAT8OID, 8, FLOAT8PASSBYVAL, TYPALIGN_DOUBLE));
}

}  // extern "C"
