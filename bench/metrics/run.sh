#!/usr/bin/env bash
# Network metrics on the 34k-edge Paris example graph: streetgen.network_stats against OSMnx on
# the same edges, measured in the same run (issue: network metrics; goal < 2 s on one core).
#
#   bash bench/metrics/run.sh
#   RUNS=9 bash bench/metrics/run.sh
#   STREETGEN_BENCH_NO_BUILD=1 bash bench/metrics/run.sh   use the streetgen already installed
#                                                          for the pg_config on PATH
#
# streetgen: one SQL call, the edges aggregated from a table (EWKB across the boundary, graph,
# every metric, GEOS-polygonized blocks); the median of RUNS, also without blocks. A single
# function call runs on one core. OSMnx (python3-osmnx, /usr/bin/python3): street counts,
# basic_stats, bearings and orientation entropy on the graph built from the same edges; blocks,
# which OSMnx does not compute, with shapely's polygonize (bench/metrics/osmnx_stats.py).
# Then compare_networks baselines on real data: what realism_score two real networks get (Paris
# west against Paris east, each in a window shrunk 50 m from the cut; Paris against New York).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
runs="${RUNS:-5}"
port="${STREETGEN_BENCH_PORT:-54333}"
paris="$data/examples/cities/paris.geojson"
source "$repo/bench/lib.sh"
bench_cluster "$port"
psql -X -q -c "CREATE TABLE paris (id integer, geom geometry(LineString, 0))"
/usr/bin/python3 "$repo/tests/metrics/geojson_edges.py" "$paris" | psql -X -q -c "COPY paris FROM STDIN"
psql -X -q -c "CREATE TABLE new_york (id integer, geom geometry(LineString, 0))"
/usr/bin/python3 "$repo/tests/metrics/geojson_edges.py" "$data/examples/cities/new-york.geojson" | psql -X -q -c "COPY new_york FROM STDIN"
psql -X -q -c "VACUUM ANALYZE paris, new_york"

# Median of RUNS calls, each timed by the server clock around the one function call.
time_call() {
  psql -X -q -At <<SQL
CREATE TEMP TABLE t (ms float8);
DO \$\$
DECLARE s timestamptz; r streetgen.network_metrics;
BEGIN
  FOR i IN 1..$runs LOOP
    s := clock_timestamp();
    r := $1;
    INSERT INTO t VALUES (extract(epoch FROM clock_timestamp() - s) * 1000);
  END LOOP;
END \$\$;
SELECT percentile_cont(0.5) WITHIN GROUP (ORDER BY ms) FROM t;
SQL
}
full_ms=$(time_call "streetgen.network_stats('SELECT geom FROM paris')")
noblock_ms=$(time_call "streetgen.network_stats('SELECT geom FROM paris', blocks => false)")
ours=$(psql -X -q -At -c "SELECT json_build_object('edges', edge_count, 'duplicates', duplicate_edges, 'nodes', node_count,
  'intersections', intersection_count, 'mean_degree', mean_degree, 'street_density', street_density,
  'circuity', circuity, 'orientation_entropy', orientation_entropy, 'blocks', block_count)
  FROM streetgen.network_stats('SELECT geom FROM paris')")
peer=$(/usr/bin/python3 "$repo/bench/metrics/osmnx_stats.py" "$paris")

echo "streetgen $(psql -X -At -c "SELECT extension FROM streetgen.version()"), OSMnx $(/usr/bin/python3 -c 'import osmnx; print(osmnx.__version__)'), $(nproc) cores, $(date -u +%Y-%m-%d)"
echo "paris: $(psql -X -At -c "SELECT count(*) FROM paris") edges"
/usr/bin/python3 - "$ours" "$peer" "$full_ms" "$noblock_ms" <<'PY'
import json, sys
ours, peer = json.loads(sys.argv[1]), json.loads(sys.argv[2])
full, noblock = float(sys.argv[3]) / 1000, float(sys.argv[4]) / 1000
print(f"streetgen network_stats, every metric and blocks: {full:.3f} s (median); without blocks: {noblock:.3f} s"
      f"  (goal < 2 s: {'met' if full < 2 else 'NOT met'})")
print(f"OSMnx: graph from the edges {peer['t_graph']:.2f} s, statistics and orientation entropy {peer['t_stats']:.2f} s; "
      f"shapely blocks {peer['t_blocks']:.2f} s")
print(f"ratio OSMnx statistics / streetgen without blocks: {peer['t_stats'] / noblock:.1f}x")
print(f"ratio OSMnx statistics + shapely blocks / streetgen with blocks: {(peer['t_stats'] + peer['t_blocks']) / full:.1f}x")
print(f"ratio OSMnx graph + statistics + blocks / streetgen with blocks: "
      f"{(peer['t_graph'] + peer['t_stats'] + peer['t_blocks']) / full:.1f}x")
print("same graph? (streetgen drops exact duplicates; OSMnx's get_undirected only reciprocal ones of one osmid)")
rows = [("nodes", ours["nodes"], peer["nodes"]), ("streets", ours["edges"], peer["streets"]),
        ("intersections", ours["intersections"], peer["intersections"]), ("mean degree", ours["mean_degree"], peer["mean_degree"]),
        ("street density km/km2", ours["street_density"], peer["street_density"]), ("circuity", ours["circuity"], peer["circuity"]),
        ("orientation entropy", ours["orientation_entropy"], peer["orientation_entropy"]), ("blocks", ours["blocks"], peer["blocks"])]
for name, a, b in rows:
    print(f"  {name:<22} streetgen {a:>12.6g}  OSMnx {b:>12.6g}  rel. diff {(a - b) / b:+.2e}")
print(f"  (streetgen dropped {ours['duplicates']} exact duplicate edges)")
PY

echo "compare_networks baselines (realism_score; headline metrics' relative differences):"
psql -X -q -At -v ON_ERROR_STOP=1 <<'SQL'
CREATE TEMP TABLE cut AS SELECT ST_XMin(e) AS x0, ST_YMin(e) AS y0, ST_XMax(e) AS x1, ST_YMax(e) AS y1,
                                (ST_XMin(e) + ST_XMax(e)) / 2 AS xm
  FROM (SELECT ST_Extent(geom)::geometry AS e FROM paris) s;
CREATE TEMP TABLE pairs AS
SELECT 'paris west vs paris east' AS pair, c.*
  FROM cut, streetgen.compare_networks(
         streetgen.network_stats('SELECT geom FROM paris', 0, ST_MakeEnvelope(cut.x0 + 50, cut.y0 + 50, cut.xm - 50, cut.y1 - 50, 0)),
         streetgen.network_stats('SELECT geom FROM paris', 0, ST_MakeEnvelope(cut.xm + 50, cut.y0 + 50, cut.x1 - 50, cut.y1 - 50, 0))) c
UNION ALL
SELECT 'paris vs new york', c.*
  FROM streetgen.compare_networks(streetgen.network_stats('SELECT geom FROM paris'),
                                  streetgen.network_stats('SELECT geom FROM new_york')) c;
SELECT '  ' || pair || ': realism_score ' || round(score::numeric, 3) || ';' ||
       (SELECT string_agg(' ' || p2.metric || ' ' || to_char(100 * p2.relative_difference, 'FMSG9999990.0') || ' %', ',' ORDER BY p2.metric)
          FROM pairs p2 WHERE p2.pair = p.pair AND p2.metric IN ('street_density', 'intersection_density', 'mean_degree',
               'dead_end_share', 'degree4_share', 'connected_node_ratio', 'orientation_order', 'block_area_median'))
  FROM pairs p WHERE metric = 'realism_score' ORDER BY pair DESC;
SQL
