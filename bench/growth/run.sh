#!/usr/bin/env bash
# Example-based growth (streetgen.grow_example) on the real example patches of
# ../shared/data/examples/patches (issue 7): speed, growth of cost with size, and realism.
#
#   bash bench/growth/run.sh                  the streetgen installed for the pg_config on PATH
#   OUT=/tmp/pics bash bench/growth/run.sh    where the PNGs go (default: build/bench-growth)
#   PARAMS='{"rotation": false}' SEEDS='1 2 3 4 5' bash bench/growth/run.sh   params and seeds of part 1
#   SPEED=0 bash bench/growth/run.sh          part 1 only
#   PLOTS=0 SEEDS="$(seq 1 30)" bash bench/growth/run.sh   no PNGs: judge a change on many seeds quickly
#                                             (30 seeds, five examples: under a minute of growth)
#
# 1. Realism: for tokyo, canberra_south_large, barcelona_east, new-york and strasbourg, grow the
#    example's convex hull from one seed point at its centre (default params; seeds 1, 2, 3), then
#    compare_networks(example, grown) with both measured inside the hull shrunk by 50 m, degree-2
#    chains merged (simplify: the example's edges are polylines, the output's are segments); the
#    eight headline metrics' relative differences and their median (the issue's per-pair median).
#    A PNG per example (example beside output, with the ODbL line).
# 2. Speed: km of road grown per second of the one SQL call (one core), in squares from tokyo of
#    growing size (about 10 km to 1,000 km of road), so the growth of cost with size shows.
# Nothing is built or installed here: the extension must be installed for the pg_config on PATH.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
data="$(cd "$data" && pwd)"
port="${STREETGEN_BENCH_PORT:-54336}"
out="${OUT:-$repo/build/bench-growth}"
params="${PARAMS:-{\}}"
seeds="${SEEDS:-1 2 3}"
mkdir -p "$out"
source "$repo/bench/lib.sh"
bench_cluster "$port" nobuild
psql -X -q -v ON_ERROR_STOP=1 <<SQL
-- ids, and the table's order the grower reads the example in, follow the features' order in the file:
-- without the window's ORDER BY they depended on what else the table held (growth17).
CREATE TABLE patch AS
SELECT n AS name, row_number() OVER (PARTITION BY n ORDER BY i) AS id, f -> 'properties' ->> 'type' AS road_class,
       ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM unnest(ARRAY['tokyo', 'canberra_south_large', 'barcelona_east', 'new-york', 'strasbourg']) AS n,
       jsonb_array_elements(pg_read_file('$data/examples/patches/' || n || '.geojson')::jsonb -> 'features')
         WITH ORDINALITY AS e(f, i);
CREATE TABLE region AS
SELECT name, ST_ConvexHull(ST_Collect(geom)) AS geom FROM patch GROUP BY name;
CREATE TABLE grown (name text, seed integer, id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry);
CREATE TABLE timing (name text, seed integer, seconds double precision);
SQL

echo "== realism: grow each example's hull from its centre (params $params), compare inside the hull shrunk by 50 m"
for seed in $seeds; do
for name in tokyo canberra_south_large barcelona_east new-york strasbourg; do
  psql -X -q -v ON_ERROR_STOP=1 <<SQL
DO \$\$
DECLARE
  t0 timestamptz := clock_timestamp();
BEGIN
  INSERT INTO grown
  SELECT r.name, $seed, g.* FROM region r,
         streetgen.grow_example(format('SELECT id, road_class, geom FROM patch WHERE name = %L', r.name), r.geom,
                                ST_PointOnSurface(r.geom), NULL, '$params'::jsonb || '{"seed": $seed, "max_edges": 200000}') AS g
   WHERE r.name = '$name';
  INSERT INTO timing VALUES ('$name', $seed, extract(epoch FROM clock_timestamp() - t0));
END
\$\$;
SQL
  [ "${PLOTS:-1}" = 0 ] || /usr/bin/python3 "$repo/bench/growth/plot.py" "host=$PGHOST port=$PGPORT user=postgres dbname=bench" \
    "SELECT geom, road_class FROM patch WHERE name = '$name'" \
    "SELECT geom, road_class FROM grown WHERE name = '$name' AND seed = $seed" \
    "$name: example (left) and grow_example output (right), params $params, seed $seed" "$out/$name-seed$seed.png"
done
done
psql -X -q -v ON_ERROR_STOP=1 <<'SQL'
CREATE TABLE cmp AS
SELECT r.name, s.seed, c.*
  FROM region r CROSS JOIN (SELECT DISTINCT seed FROM timing) s,
       LATERAL streetgen.compare_networks(
         streetgen.network_stats(format('SELECT geom FROM patch WHERE name = %L', r.name), 0, ST_Buffer(r.geom, -50),
                                 simplify => true),
         streetgen.network_stats(format('SELECT geom FROM grown WHERE name = %L AND seed = %s', r.name, s.seed), 0,
                                 ST_Buffer(r.geom, -50), simplify => true)) c;
CREATE TABLE headline AS
SELECT * FROM cmp WHERE metric IN ('street_density', 'intersection_density', 'mean_degree', 'dead_end_share',
                                   'degree4_share', 'connected_node_ratio', 'orientation_order', 'block_area_median');
\pset footer off
\echo speed of each growth (one SQL call, one core); fallback_pct: share of edges grown by the parametric fallback
SELECT g.name, g.seed, count(*) AS edges,
       round(100.0 * count(*) FILTER (WHERE g.origin = 'grow_parametric') / count(*), 1) AS fallback_pct,
       round((sum(ST_Length(g.geom)) / 1000)::numeric, 1) AS km,
       round(t.seconds::numeric, 2) AS seconds, round((sum(ST_Length(g.geom)) / 1000 / t.seconds)::numeric, 0) AS km_per_s
  FROM grown g JOIN timing t USING (name, seed) GROUP BY g.name, g.seed, t.seconds ORDER BY g.name, g.seed;
\echo headline metrics: example value, grown value (median over seeds), relative difference in % (median over seeds)
SELECT name, metric, round(min(reference_value)::numeric, 4) AS example,
       round(percentile_cont(0.5) WITHIN GROUP (ORDER BY candidate_value)::numeric, 4) AS grown,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY relative_difference))::numeric, 1) AS rel_diff_pct
  FROM headline GROUP BY name, metric ORDER BY name, metric;
\echo per pair (example, seed): median over the eight headline metrics of |relative difference| (capped at 100 %), and the worst metric
SELECT name, seed, round((100 * score)::numeric, 1) AS median_abs_rel_diff_pct,
       (SELECT round((100 * max(abs(h.relative_difference)))::numeric, 1) FROM headline h
         WHERE h.name = cmp.name AND h.seed = cmp.seed) AS worst_metric_pct
  FROM cmp WHERE metric = 'median_abs_relative_difference' ORDER BY name, seed;
SELECT round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY score))::numeric, 1) AS median_over_pairs_pct
  FROM cmp WHERE metric = 'median_abs_relative_difference';
-- The acceptance checks on everything grown above.
CREATE INDEX ON grown USING gist (geom);
ANALYZE grown;
SELECT (SELECT count(*) FROM grown) AS edges_checked,
       (SELECT count(*) FROM grown a JOIN grown b ON a.name = b.name AND a.seed = b.seed AND a.id < b.id AND ST_Intersects(a.geom, b.geom)
         WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))) AS crossings_without_node,
       (SELECT count(*) FROM grown g JOIN region r USING (name) WHERE NOT ST_CoveredBy(g.geom, r.geom)) AS outside_region;
SQL

if [ "${SPEED:-1}" = 0 ]; then
  echo "Road data: © OpenStreetMap contributors, ODbL 1.0 (example patches of Nishida et al. 2016)"
  exit 0
fi
echo "== speed: squares grown from tokyo (rotation off), one SQL call each"
psql -X -q -v ON_ERROR_STOP=1 <<'SQL'
CREATE FUNCTION square(side double precision) RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  t0 timestamptz := clock_timestamp();
  edges bigint;
  km double precision;
  seconds double precision;
BEGIN
  SELECT count(*), sum(ST_Length(g.geom)) / 1000 INTO edges, km
    FROM streetgen.grow_example('SELECT id, road_class, geom FROM patch WHERE name = ''tokyo''',
                                ST_MakeEnvelope(0, 0, side, side, 0), ST_MakePoint(side / 2, side / 2), NULL,
                                '{"seed": 1, "rotation": false, "max_edges": 2000000}') AS g;
  seconds := extract(epoch FROM clock_timestamp() - t0);
  RETURN format('side %s m: %s edges, %s km in %s s: %s km/s, %s us/edge', side, edges, round(km::numeric, 1),
                round(seconds::numeric, 2), round((km / seconds)::numeric, 0), round((1e6 * seconds / edges)::numeric, 1));
END
$$;
SQL
for side in 600 1200 2400 4800 9600; do
  psql -X -q -At -v ON_ERROR_STOP=1 -c "SELECT square($side)"
done
echo "pictures: $out/*.png"
echo "Road data: © OpenStreetMap contributors, ODbL 1.0 (example patches of Nishida et al. 2016)"
