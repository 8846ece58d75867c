// Network metrics: edges in as an EWKB array, one streetgen.network_metrics row out (columns
// filled by name from core's metric table, so the SQL type and the C++ table cannot drift
// silently: an unknown column is an error); and the comparison of two such rows.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/geometry_checks.hpp"
#include "core/interrupts.hpp"
#include "core/metrics/compare_networks.hpp"
#include "core/metrics/network_graph.hpp"
#include "core/metrics/network_stats.hpp"
#include "pg/array_args.hpp"
#include "pg/boundary.hpp"
#include "pg/owned_result.hpp"

extern "C" {
#include "catalog/pg_type.h"
#include "funcapi.h"
#include "utils/array.h"
#include "utils/lsyscache.h"
}

using namespace streetgen;

namespace {

struct GeomArg {
  const std::uint8_t* ewkb;
  std::size_t size;
};


const char* const kArrayColumns[] = {"degrees",     "segment_lengths",   "orientation_histogram",
                                     "block_areas", "block_compactness", "block_aspect_ratios"};
constexpr int kArrayCount = 6;

const std::vector<double>* array_of(const core::NetworkStats& s, int k) {
  switch (k) {
    case 1:
      return &s.segment_lengths;
    case 2:
      return &s.orientation_histogram;
    case 3:
      return &s.block_areas;
    case 4:
      return &s.block_compactness;
    case 5:
      return &s.block_aspect_ratios;
    default:
      return nullptr;
  }
}
std::vector<double>* array_of(core::NetworkStats& s, int k) {
  return const_cast<std::vector<double>*>(array_of(static_cast<const core::NetworkStats&>(s), k));
}

int find_metric(const char* name) {
  const auto& table = core::metric_table();
  for (std::size_t m = 0; m < core::kMetricCount; ++m) {
    if (std::strcmp(table[m].name, name) == 0) return static_cast<int>(m);
  }
  return -1;
}
int find_array(const char* name) {
  for (int k = 0; k < kArrayCount; ++k) {
    if (std::strcmp(kArrayColumns[k], name) == 0) return k;
  }
  return -1;
}

// Phase-1 copy of one streetgen.network_metrics row.
struct MetricsArg {
  double value[core::kMetricCount];
  double* arrays[kArrayCount];
  int counts[kArrayCount];
};

void read_metrics(HeapTupleHeader row, MetricsArg& out, const char* parameter) {
  const auto& table = core::metric_table();
  for (std::size_t m = 0; m < core::kMetricCount; ++m) {
    bool isnull = false;
    Datum d = GetAttributeByName(row, table[m].name, &isnull);
    out.value[m] = isnull ? NAN : table[m].integer ? static_cast<double>(DatumGetInt64(d)) : DatumGetFloat8(d);
  }
  for (int k = 0; k < kArrayCount; ++k) {
    bool isnull = false;
    Datum d = GetAttributeByName(row, kArrayColumns[k], &isnull);
    out.counts[k] = 0;
    out.arrays[k] = nullptr;
    if (isnull) continue;
    ArrayType* array = DatumGetArrayTypeP(d);
    Oid element = ARR_ELEMTYPE(array);
    int16 typlen;
    bool typbyval;
    char typalign;
    get_typlenbyvalalign(element, &typlen, &typbyval, &typalign);
    Datum* values;
    bool* nulls;
    int n;
    deconstruct_array(array, element, typlen, typbyval, typalign, &values, &nulls, &n);
    out.arrays[k] = static_cast<double*>(palloc(sizeof(double) * (n > 0 ? n : 1)));
    for (int i = 0; i < n; ++i) {
      if (nulls[i]) {
        ereport(ERROR, (errcode(ERRCODE_NULL_VALUE_NOT_ALLOWED),
                        errmsg("%s.%s must not contain NULL", parameter, kArrayColumns[k])));
      }
      out.arrays[k][i] = element == INT4OID ? DatumGetInt32(values[i]) : DatumGetFloat8(values[i]);
    }
    out.counts[k] = n;
  }
}

core::NetworkStats to_stats(const MetricsArg& arg) {
  core::NetworkStats s;
  for (std::size_t m = 0; m < core::kMetricCount; ++m) s.value[m] = arg.value[m];
  for (int i = 0; i < arg.counts[0]; ++i) s.degrees.push_back(static_cast<int>(arg.arrays[0][i]));
  for (int k = 1; k < kArrayCount; ++k) array_of(s, k)->assign(arg.arrays[k], arg.arrays[k] + arg.counts[k]);
  return s;
}

Datum float8_array(const std::vector<double>& v) {
  auto* elems = static_cast<Datum*>(palloc(sizeof(Datum) * (v.empty() ? 1 : v.size())));
  for (std::size_t i = 0; i < v.size(); ++i) elems[i] = Float8GetDatum(v[i]);
  return PointerGetDatum(
      construct_array(elems, static_cast<int>(v.size()), FLOAT8OID, 8, FLOAT8PASSBYVAL, TYPALIGN_DOUBLE));
}

}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_network_stats);
// (geoms bytea[], node_tolerance float8, win bytea, split_at_crossings bool, simplify bool,
//  blocks bool, layers int4[]) -> streetgen.network_metrics
Datum _streetgen_network_stats(PG_FUNCTION_ARGS) {
  // Phase 1. A library newer than the installed SQL would read arguments that are not there.
  if (PG_NARGS() != 7) {
    ereport(ERROR, (errcode(ERRCODE_OBJECT_NOT_IN_PREREQUISITE_STATE),
                    errmsg("_streetgen_network_stats expects 7 arguments, got %d", PG_NARGS()),
                    errhint("Run ALTER EXTENSION streetgen UPDATE, or re-create the extension.")));
  }
  pg::ArrayArg geoms = pg::array_arg(fcinfo, 0, BYTEAOID, "edges");
  pg::ArrayArg layer_arg = pg::array_arg(fcinfo, 6, INT4OID, "layers");
  if (layer_arg.count != 0) pg::require_same_length(geoms, "edges", layer_arg, "layers");
  for (int a = 1; a <= 5; ++a) {
    if (a != 2 && PG_ARGISNULL(a)) {
      static const char* const names[] = {"", "node_tolerance", "", "split_at_crossings", "simplify", "blocks"};
      pg::raise_null_argument(names[a]);
    }
  }
  double tolerance = PG_GETARG_FLOAT8(1);
  GeomArg window{nullptr, 0};
  if (!PG_ARGISNULL(2)) {
    bytea* w = PG_GETARG_BYTEA_PP(2);
    window = {reinterpret_cast<const std::uint8_t*>(VARDATA_ANY(w)), VARSIZE_ANY_EXHDR(w)};
  }
  bool split = PG_GETARG_BOOL(3), simplify = PG_GETARG_BOOL(4), blocks = PG_GETARG_BOOL(5);
  auto* edges = static_cast<GeomArg*>(palloc0(sizeof(GeomArg) * (geoms.count > 0 ? geoms.count : 1)));
  auto* edge_layers = static_cast<int*>(palloc0(sizeof(int) * (geoms.count > 0 ? geoms.count : 1)));
  int edge_count = 0;
  for (int i = 0; i < geoms.count; ++i) {
    if (geoms.nulls[i]) continue;  // like an aggregate, NULL edges are skipped
    bytea* g = DatumGetByteaPP(geoms.values[i]);
    edge_layers[edge_count] = layer_arg.count != 0 && !layer_arg.nulls[i] ? DatumGetInt32(layer_arg.values[i]) : 0;
    edges[edge_count++] = {reinterpret_cast<const std::uint8_t*>(VARDATA_ANY(g)), VARSIZE_ANY_EXHDR(g)};
  }
  TupleDesc tupdesc;
  if (get_call_result_type(fcinfo, nullptr, &tupdesc) != TYPEFUNC_COMPOSITE) {
    ereport(ERROR,
            (errcode(ERRCODE_FEATURE_NOT_SUPPORTED), errmsg("_streetgen_network_stats must return a composite")));
  }
  tupdesc = BlessTupleDesc(tupdesc);
  auto stats = pg::OwnedResult<core::NetworkStats>::create();

  // Phase 2.
  pg::CallError error;
  pg::guarded_call(error, [&] {
    core::GeosContext& geos = pg::backend_geos();
    std::vector<core::Polyline> lines;
    std::vector<int> layers;
    lines.reserve(edge_count);
    int srid = 0;
    core::InterruptPoller poller(1024);
    for (int i = 0; i < edge_count; ++i) {
      poller.tick();
      std::string name = "edge " + std::to_string(i + 1);
      core::SridGeometry g = core::read_ewkb(geos, edges[i].ewkb, edges[i].size, name.c_str());
      if (i == 0) {
        srid = g.srid;
      } else if (g.srid != srid) {
        core::throw_invalid_argument(
            "edges must share one SRID",
            "The " + name + " has SRID " + std::to_string(g.srid) + ", the first edge " + std::to_string(srid) + ".");
      }
      core::append_linestrings(geos, g.geom.get(), "edge " + std::to_string(i + 1), "edges must be LineStrings or MultiLineStrings",
                               "Use ST_Boundary for polygons, or filter the edges with ST_Dimension(geom) = 1.", lines);
      layers.resize(lines.size(), edge_layers[i]);  // every part of a MultiLineString on its layer
    }
    core::SridGeometry win;
    core::NetworkStatsOptions options;
    options.blocks = blocks;
    if (window.ewkb != nullptr) {
      win = core::read_ewkb(geos, window.ewkb, window.size, "window");
      if (edge_count > 0 && win.srid != srid) {
        core::throw_invalid_argument(
            "window must have the SRID of the edges",
            "The window has SRID " + std::to_string(win.srid) + ", the edges " + std::to_string(srid) + ".");
      }
      core::require_finite_coordinates(geos, win.geom.get(), "window");
      options.window = win.geom.get();
    }
    core::NetworkGraphOptions graph_options;
    graph_options.node_tolerance = tolerance;
    graph_options.split_at_crossings = split;
    graph_options.simplify = simplify;
    core::NetworkGraph graph = core::build_network_graph(lines, graph_options, layers);
    lines.clear();
    stats.emplace(core::network_stats(geos, graph, options));
  });
  pg::raise_if_failed(error);

  // Phase 3: one row, filled by column name.
  const auto& table = core::metric_table();
  int natts = tupdesc->natts;
  auto* values = static_cast<Datum*>(palloc0(sizeof(Datum) * natts));
  auto* nulls = static_cast<bool*>(palloc0(sizeof(bool) * natts));
  for (int i = 0; i < natts; ++i) {
    Form_pg_attribute att = TupleDescAttr(tupdesc, i);
    const char* name = NameStr(att->attname);
    int m = find_metric(name);
    int k = find_array(name);
    if (m >= 0) {
      double v = stats->value[m];
      nulls[i] = std::isnan(v);
      if (!nulls[i]) values[i] = table[m].integer ? Int64GetDatum(std::llround(v)) : Float8GetDatum(v);
    } else if (k == 0) {
      int n = static_cast<int>(stats->degrees.size());
      auto* elems = static_cast<Datum*>(palloc(sizeof(Datum) * (n > 0 ? n : 1)));
      for (int j = 0; j < n; ++j) elems[j] = Int32GetDatum(stats->degrees[j]);
      values[i] = PointerGetDatum(construct_array(elems, n, INT4OID, 4, true, TYPALIGN_INT));
    } else if (k > 0) {
      values[i] = float8_array(*array_of(*stats, k));
    } else {
      ereport(ERROR, (errcode(ERRCODE_INTERNAL_ERROR), errmsg("unknown network metric column \"%s\"", name)));
    }
  }
  HeapTuple tuple = heap_form_tuple(tupdesc, values, nulls);
  stats.release();
  PG_RETURN_DATUM(HeapTupleGetDatum(tuple));
}

PG_FUNCTION_INFO_V1(_streetgen_compare_networks);
// (a streetgen.network_metrics, b streetgen.network_metrics) -> SETOF (metric, kind, a, b,
//  relative_difference, ks, wasserstein, score)
Datum _streetgen_compare_networks(PG_FUNCTION_ARGS) {
  if (PG_ARGISNULL(0)) pg::raise_null_argument("a");
  if (PG_ARGISNULL(1)) pg::raise_null_argument("b");
  auto* args = static_cast<MetricsArg*>(palloc0(sizeof(MetricsArg) * 2));
  read_metrics(PG_GETARG_HEAPTUPLEHEADER(0), args[0], "a");
  read_metrics(PG_GETARG_HEAPTUPLEHEADER(1), args[1], "b");
  InitMaterializedSRF(fcinfo, 0);
  auto rows = pg::OwnedResult<std::vector<core::ComparisonRow>>::create();

  pg::CallError error;
  pg::guarded_call(error, [&] { rows.emplace(core::compare_networks(to_stats(args[0]), to_stats(args[1]))); });
  pg::raise_if_failed(error);

  auto* rsinfo = reinterpret_cast<ReturnSetInfo*>(fcinfo->resultinfo);
  for (const core::ComparisonRow& row : *rows) {
    Datum v[8];
    bool null[8] = {false, false};
    v[0] = CStringGetTextDatum(row.metric.c_str());
    v[1] = CStringGetTextDatum(row.kind.c_str());
    double numbers[6] = {row.a, row.b, row.relative_difference, row.ks, row.wasserstein, row.score};
    for (int c = 0; c < 6; ++c) {
      null[2 + c] = std::isnan(numbers[c]);
      v[2 + c] = null[2 + c] ? Datum(0) : Float8GetDatum(numbers[c]);
    }
    tuplestore_putvalues(rsinfo->setResult, rsinfo->setDesc, v, null);
  }
  rows.release();
  PG_RETURN_NULL();
}

}  // extern "C"
