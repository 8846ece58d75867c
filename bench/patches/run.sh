#!/usr/bin/env bash
# Patch-based growth (streetgen.extract_patches + grow_patches, issue 8) against growth I
# (grow_example, the baseline measured in the same run) on the real example patches of
# ../shared/data/examples/patches: realism, example-based share, speed.
#
#   bash bench/patches/run.sh                 the streetgen installed for the pg_config on PATH
#   PARAMS='{"scale": 5}' SEEDS='1 2 3' bash bench/patches/run.sh    grow_patches params, seeds
#   NAMES='tokyo new-york' SPEED=0 bash bench/patches/run.sh         some examples, no speed part
#   OUT=/tmp/pics bash bench/patches/run.sh   where the PNGs go (default: build/bench-patches)
#   BASELINE=0 bash bench/patches/run.sh      grow_patches only (no grow_example baseline: half the time)
#   STRUCTURES=0 bash bench/patches/run.sh    without the roundabout / cul-de-sac uses
#   SIDES='1200 2600' bash bench/patches/run.sh   the speed part's square sides (m)
#   DEBUG1=1 bash bench/patches/run.sh        grow_patches' DEBUG1 counts (arterial fronts, fallback, ...) into $OUT/debug1.log
#   TILES='200 400' bash bench/patches/run.sh  tile_noise.py's tile sides (m; default 250 500)
#
# 1. Realism: for each example, extract its patches, grow its convex hull from one seed at its
#    centre with grow_patches and with grow_example (default params, max_edges 200000), and
#    compare each with the example by compare_networks, inside the hull shrunk by 50 m, degree-2
#    chains merged (as bench/growth/run.sh): the eight headline metrics and their median per
#    pair (the issue's per-pair median), the 4-way and dead-end shares in percentage points, and
#    whether roundabouts (patches tagged roundabout) and cul-de-sacs were used, and the rings
#    read from the geometry (compact faces bounded by roundabout streets), the example's and a
#    growth's: a patch used is not a ring placed. Patches are
#    extracted with extract_patches' defaults (levels: arterial patches grow first), or with
#    EXTRACT_PARAMS (e.g. EXTRACT_PARAMS='{"levels": false}' for one level).
#    Then where the density comes from: the main streets' share of the length (example, grown),
#    the mean connector length of the library and of the patches used, and the share of junctions
#    with a statistical street (fallback or join); and the avenue ends where only local streets go
#    on (example, grown).
#    And φ against the statistical fallback's share of the length, per seed (does the fallback
#    order or disorder the growth?). And the orientation order of the main and the local streets
#    apart (example, grown): which level loses the example's order. And the streets' bends: turn
#    per km and the share of streets that bend by 10 degrees or more as a whole, the example's
#    against the statistical fallback's.
#    And coverage: the share of the window farther than 100 m from every street (all of it, near
#    the hull's edge, well inside it), and the share of the street length outside the window (the
#    metrics are per area and do not see holes). And the blocks' shapes, the example's against the
#    grown blocks' with and without a statistical street on their perimeter.
#    Then the examples' sampling noise, the realism goal as the example's own tiles would score it,
#    where φ comes from, and where the T-junctions come from (sampling_noise.py, tile_noise.py,
#    phi_sources.py, tee_sources.py).
# 2. Speed: km of road per second of one SQL call (one core) for squares grown from tokyo, for
#    grow_patches and for grow_example in the same run, and their ratio; a 300 km square is the
#    issue's benchmark (< 3 s).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
data="$(cd "$data" && pwd)"
port="${STREETGEN_BENCH_PORT:-54337}"
out="${OUT:-$repo/build/bench-patches}"
params="${PARAMS:-{\}}"
extract_params="${EXTRACT_PARAMS:-{\}}"
seeds="${SEEDS:-1 2 3}"
# the speed part's square sides (m): about 30, 60, 300, 1,000 and 3,000 km of tokyo's streets
sides="${SIDES:-850 1200 2600 4800 8300}"
names="${NAMES:-tokyo canberra_south_large barcelona_east new-york strasbourg quito}"
mkdir -p "$out"
source "$repo/bench/lib.sh"
bench_cluster "$port" nobuild
names_sql=$(printf "'%s'," $names)
psql -X -q -v ON_ERROR_STOP=1 <<SQL
CREATE TABLE example AS
SELECT n AS name, row_number() OVER (PARTITION BY n) AS id, f -> 'properties' ->> 'type' AS road_class,
       (f -> 'properties' ->> 'roundabout')::boolean AS roundabout,
       ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM unnest(ARRAY[${names_sql%,}]) AS n,
       jsonb_array_elements(pg_read_file('$data/examples/patches/' || n || '.geojson')::jsonb -> 'features') AS f;
CREATE TABLE region AS SELECT name, ST_ConvexHull(ST_Collect(geom)) AS geom FROM example GROUP BY name;
CREATE TABLE patch (name text, patch_id bigint, edge_index integer, role text, road_class text, tags text[], edge_tags text[],
                    start_tags text[], end_tags text[], max_uses integer, example_id bigint, geom geometry);
CREATE TABLE grown (method text, name text, seed integer, id bigint, from_node bigint, to_node bigint, road_class text,
                    origin text, geom geometry);
CREATE TABLE timing (method text, name text, seed integer, seconds double precision);
SQL

echo "== patches per example"
for name in $names; do
  psql -X -q -v ON_ERROR_STOP=1 -c "INSERT INTO patch SELECT '$name', * FROM streetgen.extract_patches(
    format('SELECT * FROM example WHERE name = %L', '$name'), '$extract_params')"
done
psql -X -v ON_ERROR_STOP=1 <<'SQL'
\pset footer off
SELECT name, count(DISTINCT patch_id) AS patches, count(DISTINCT patch_id) FILTER (WHERE 'arterial' = ANY (tags)) AS arterial,
       count(*) FILTER (WHERE role = 'connector') AS connectors,
       count(DISTINCT patch_id) FILTER (WHERE 'roundabout' = ANY (tags)) AS roundabout,
       count(DISTINCT patch_id) FILTER (WHERE 'cul-de-sac' = ANY (tags)) AS cul_de_sac,
       count(DISTINCT patch_id) FILTER (WHERE 'loop' = ANY (tags)) AS loop,
       count(DISTINCT patch_id) FILTER (WHERE 'cluster' = ANY (tags)) AS cluster,
       count(DISTINCT patch_id) FILTER (WHERE 'curved' = ANY (tags)) AS curved,
       count(DISTINCT patch_id) FILTER (WHERE 'terminal' = ANY (tags)) AS terminal,
       count(DISTINCT patch_id) FILTER (WHERE 'initial' = ANY (tags)) AS initial
  FROM patch GROUP BY name ORDER BY name;
SQL

echo "== realism: grow each example's hull from its centre (grow_patches params $params; grow_example defaults)"
for seed in $seeds; do
for name in $names; do
  # DEBUG1=1: grow_patches' DEBUG1 counts (why the arterial phase stops, ...) into $out/debug1.log
  if [ "${DEBUG1:-0}" = 1 ]; then echo "== $name seed $seed" >> "$out/debug1.log"; fi
  PGOPTIONS="-c client_min_messages=$([ "${DEBUG1:-0}" = 1 ] && echo debug1 || echo warning)" \
  psql -X -q -v ON_ERROR_STOP=1 2>> "$([ "${DEBUG1:-0}" = 1 ] && echo "$out/debug1.log" || echo /dev/stderr)" <<SQL
DO \$\$
DECLARE
  t0 timestamptz := clock_timestamp();
BEGIN
  INSERT INTO grown
  SELECT 'patches', r.name, $seed, g.* FROM region r,
         streetgen.grow_patches(format('SELECT * FROM patch WHERE name = %L', r.name), r.geom,
                                ST_PointOnSurface(r.geom), NULL, '$params'::jsonb || '{"seed": $seed, "max_edges": 200000}') AS g
   WHERE r.name = '$name';
  INSERT INTO timing VALUES ('patches', '$name', $seed, extract(epoch FROM clock_timestamp() - t0));
  IF NOT ${BASELINE:-1}::boolean THEN RETURN; END IF;
  t0 := clock_timestamp();
  INSERT INTO grown
  SELECT 'example', r.name, $seed, g.* FROM region r,
         streetgen.grow_example(format('SELECT id, road_class, geom FROM example WHERE name = %L', r.name), r.geom,
                                ST_PointOnSurface(r.geom), NULL, '{"seed": $seed, "max_edges": 200000}') AS g
   WHERE r.name = '$name';
  INSERT INTO timing VALUES ('example', '$name', $seed, extract(epoch FROM clock_timestamp() - t0));
END
\$\$;
SQL
  if [ "$seed" = "$(echo $seeds | cut -d' ' -f1)" ]; then
    /usr/bin/python3 "$repo/bench/growth/plot.py" "host=$PGHOST port=$PGPORT user=postgres dbname=bench" \
      "SELECT geom, road_class FROM example WHERE name = '$name'" \
      "SELECT geom, road_class FROM grown WHERE method = 'patches' AND name = '$name' AND seed = $seed" \
      "$name: example (left) and grow_patches output (right), seed $seed" "$out/$name-seed$seed.png" || true
  fi
done
done
psql -X -q -v ON_ERROR_STOP=1 -v structures="${STRUCTURES:-1}" <<'SQL'
CREATE TABLE cmp AS
SELECT m.method, r.name, s.seed, c.*
  FROM region r CROSS JOIN (SELECT DISTINCT seed FROM timing) s CROSS JOIN (SELECT DISTINCT method FROM timing) AS m,
       LATERAL streetgen.compare_networks(
         streetgen.network_stats(format('SELECT geom FROM example WHERE name = %L', r.name), 0, ST_Buffer(r.geom, -50),
                                 simplify => true),
         streetgen.network_stats(format('SELECT geom FROM grown WHERE method = %L AND name = %L AND seed = %s',
                                        m.method, r.name, s.seed), 0, ST_Buffer(r.geom, -50), simplify => true)) c;
CREATE TABLE headline AS
SELECT * FROM cmp WHERE metric IN ('street_density', 'intersection_density', 'mean_degree', 'dead_end_share',
                                   'degree4_share', 'connected_node_ratio', 'orientation_order', 'block_area_median');
\pset footer off
\echo edges, example-based share (patches: edges and length from patches, the rest statistical fallback), speed
SELECT g.method, g.name, g.seed, count(*) AS edges,
       round(100.0 * count(*) FILTER (WHERE g.origin NOT LIKE 'grow_parametric%') / count(*), 1) AS example_pct,
       round((100 * sum(ST_Length(g.geom)) FILTER (WHERE g.origin NOT LIKE 'grow_parametric%') / sum(ST_Length(g.geom)))::numeric, 1) AS example_len_pct,
       round((sum(ST_Length(g.geom)) / 1000)::numeric, 1) AS km, round(t.seconds::numeric, 2) AS seconds
  FROM grown g JOIN timing t USING (method, name, seed) GROUP BY g.method, g.name, g.seed, t.seconds
 ORDER BY g.name, g.method, g.seed;
\echo headline metrics: example value, grown value and relative difference in % (medians over seeds)
SELECT name, metric, round(min(reference_value)::numeric, 4) AS example,
       round(percentile_cont(0.5) WITHIN GROUP (ORDER BY candidate_value) FILTER (WHERE method = 'patches')::numeric, 4) AS patches,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY relative_difference) FILTER (WHERE method = 'patches'))::numeric, 1) AS patches_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY relative_difference) FILTER (WHERE method = 'example'))::numeric, 1) AS grow_example_pct
  FROM headline GROUP BY name, metric ORDER BY name, metric;
\echo junction mix: 4-way and dead-end shares (percentage points from the example; the goal is within 5)
SELECT name, method, round((100 * min(reference_value) FILTER (WHERE metric = 'degree4_share'))::numeric, 1) AS ex_4way,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY candidate_value - reference_value) FILTER (WHERE metric = 'degree4_share'))::numeric, 1) AS d_4way_pp,
       round((100 * min(reference_value) FILTER (WHERE metric = 'dead_end_share'))::numeric, 1) AS ex_dead,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY candidate_value - reference_value) FILTER (WHERE metric = 'dead_end_share'))::numeric, 1) AS d_dead_pp
  FROM headline GROUP BY name, method ORDER BY name, method;
\echo per pair (method, example, seed): median of the eight headline |relative differences| (capped at 100 %)
SELECT name, seed, round((100 * max(score) FILTER (WHERE method = 'patches'))::numeric, 1) AS patches_pct,
       round((100 * max(score) FILTER (WHERE method = 'example'))::numeric, 1) AS grow_example_pct
  FROM cmp WHERE metric = 'median_abs_relative_difference' GROUP BY name, seed ORDER BY name, seed;
\echo per pair, each headline metric (grow_patches, relative difference in %; * marks the two that set the per-pair median)
WITH r AS (
  SELECT name, seed, metric, 100 * relative_difference AS pct,
         row_number() OVER (PARTITION BY name, seed ORDER BY abs(relative_difference) DESC NULLS LAST) AS rank,
         count(relative_difference) OVER (PARTITION BY name, seed) AS n
    FROM headline WHERE method = 'patches')
SELECT name, seed,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'street_density') AS street_d,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'intersection_density') AS inter_d,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'mean_degree') AS degree,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'dead_end_share') AS dead_end,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'degree4_share') AS four_way,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'connected_node_ratio') AS cnr,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'orientation_order') AS phi,
       max(round(pct::numeric, 1) || CASE WHEN rank BETWEEN (n + 1) / 2 AND n / 2 + 1 THEN '*' ELSE '' END) FILTER (WHERE metric = 'block_area_median') AS block
  FROM r GROUP BY name, seed ORDER BY name, seed;
SELECT method, round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY score))::numeric, 1) AS median_over_pairs_pct,
       round((100 * max(score))::numeric, 1) AS worst_pair_pct
  FROM cmp WHERE metric = 'median_abs_relative_difference' GROUP BY method;
\if :structures
\echo structures: patches tagged roundabout / cul-de-sac in the example, how often grow_patches used them (distinct patches a growth, summed over the seeds), and on how many of the seeds none (the goal: a growth has them when its example has them)
WITH tagged AS (SELECT DISTINCT name, patch_id, 'roundabout' = ANY (tags) AS roundabout, 'cul-de-sac' = ANY (tags) AS cul_de_sac
                  FROM patch),
     example AS (SELECT name, count(*) FILTER (WHERE roundabout) AS roundabouts, count(*) FILTER (WHERE cul_de_sac) AS cul_de_sacs
                   FROM tagged GROUP BY name),
     per_seed AS (
       SELECT s.name, s.seed, count(DISTINCT g.origin) FILTER (WHERE t.roundabout) AS roundabouts,
              count(DISTINCT g.origin) FILTER (WHERE t.cul_de_sac) AS cul_de_sacs
         FROM (SELECT DISTINCT name, seed FROM timing WHERE method = 'patches') s
              LEFT JOIN grown g ON g.method = 'patches' AND g.name = s.name AND g.seed = s.seed
              LEFT JOIN tagged t ON t.name = g.name AND g.origin = 'grow_patches:' || t.patch_id
        GROUP BY s.name, s.seed)
SELECT e.name, e.roundabouts AS ex_roundabout_patches, sum(p.roundabouts) AS roundabout_uses,
       count(*) FILTER (WHERE p.roundabouts = 0) AS seeds_without_roundabout,
       e.cul_de_sacs AS ex_cul_de_sac_patches, sum(p.cul_de_sacs) AS cul_de_sac_uses,
       count(*) FILTER (WHERE p.cul_de_sacs = 0) AS seeds_without_cul_de_sac, count(*) AS seeds
  FROM example e JOIN per_seed p USING (name) GROUP BY e.name, e.roundabouts, e.cul_de_sacs ORDER BY e.name;
\echo rings: roundabouts read from the geometry, the same way on the example and on grow_patches growths. A ring is a bounded face of the network (ST_Polygonize), compact (4 pi area / perimeter^2 >= 0.7) and under 200 m across (area < pi 100^2), whose boundary lies at least half on roundabout streets: the edges of the example flagged roundabout, the streets of a growth from patches tagged roundabout. A patch used is not a ring placed: its ring may be left open or bent where its vertices merged into streets already there. A growth counts its roundabout patches spokes too, so a block bounded half by them counts: an upper bound on its rings.
WITH flagged AS MATERIALIZED (SELECT 'example'::text AS method, name, 0 AS seed, geom FROM example WHERE roundabout
                 UNION ALL
                 SELECT g.method, g.name, g.seed, g.geom FROM grown g
                   JOIN (SELECT DISTINCT name, 'grow_patches:' || patch_id AS origin FROM patch WHERE 'roundabout' = ANY (tags)) t
                     USING (name, origin)
                  WHERE g.method = 'patches'),
     networks AS (SELECT 'example'::text AS method, name, 0 AS seed FROM region
                  UNION ALL
                  SELECT DISTINCT method, name, seed FROM timing WHERE method = 'patches'),
     faces AS MATERIALIZED (SELECT n.method, n.name, n.seed, f.geom AS face
                 FROM networks n,
                      LATERAL (SELECT ST_Polygonize(x.geom) AS geom FROM example x WHERE n.method = 'example' AND x.name = n.name
                               UNION ALL
                               SELECT ST_Polygonize(g.geom) FROM grown g
                                WHERE n.method = 'patches' AND g.method = 'patches' AND g.name = n.name AND g.seed = n.seed) AS p,
                      LATERAL ST_Dump(p.geom) AS f
                WHERE ST_Area(f.geom) < pi() * 100 ^ 2 AND 4 * pi() * ST_Area(f.geom) / ST_Perimeter(f.geom) ^ 2 >= 0.7),
     on_face AS (SELECT f.method, f.name, f.seed, f.face,
                        sum(ST_Length(ST_Intersection(r.geom, ST_Buffer(ST_ExteriorRing(f.face), 0.5)))) AS length
                   FROM faces f JOIN flagged r
                     ON r.method = f.method AND r.name = f.name AND r.seed = f.seed AND r.geom && ST_Expand(f.face, 1)
                  GROUP BY 1, 2, 3, 4),
     rings AS (SELECT method, name, seed, count(*) AS rings FROM on_face WHERE length >= 0.5 * ST_Perimeter(face) GROUP BY 1, 2, 3),
     per_network AS (SELECT n.method, n.name, n.seed, coalesce(r.rings, 0) AS rings FROM networks n LEFT JOIN rings r USING (method, name, seed))
SELECT name, max(rings) FILTER (WHERE method = 'example') AS example_rings,
       round(avg(rings) FILTER (WHERE method = 'patches'), 2) AS rings_a_growth,
       count(*) FILTER (WHERE method = 'patches' AND rings = 0) AS seeds_without_ring,
       count(*) FILTER (WHERE method = 'patches') AS seeds
  FROM per_network GROUP BY name ORDER BY name;
\endif
\echo where the density comes from (grow_patches, median over seeds): share of the length on main streets (example, grown), mean connector length of the library and of the patches used (weighted by their uses: edges placed over the segments of the patch), junctions (degree >= 3, inside the hull shrunk by 50 m, not simplified) with a statistical street (fallback or join) among their streets
WITH conn AS (SELECT name, patch_id, avg(ST_Length(geom)) FILTER (WHERE role = 'connector') AS len,
                     sum(ST_NPoints(geom) - 1) AS segments FROM patch GROUP BY 1, 2),
     used AS (SELECT name, seed, split_part(origin, ':', 2)::bigint AS patch_id, count(*) AS n FROM grown
               WHERE method = 'patches' AND origin LIKE 'grow_patches:%' GROUP BY 1, 2, 3),
     ends AS (SELECT g.name, g.seed, ST_SnapToGrid(e.p, 0.05) AS p, bool_or(g.origin = 'grow_parametric') AS stat
                FROM grown g, LATERAL (VALUES (ST_StartPoint(g.geom)), (ST_EndPoint(g.geom))) AS e(p)
               WHERE g.method = 'patches' GROUP BY 1, 2, 3 HAVING count(*) >= 3),
     per_seed AS (
       SELECT s.name, s.seed,
              (SELECT sum(ST_Length(geom)) FILTER (WHERE road_class ~ '^((motorway|trunk|primary|secondary|tertiary)(_link)?|avenue|highway|boulevard)$') / sum(ST_Length(geom)) FROM grown g
                WHERE g.method = 'patches' AND g.name = s.name AND g.seed = s.seed) AS main_share,
              (SELECT sum(c.len * u.n / c.segments) / sum(u.n::float8 / c.segments) FROM used u JOIN conn c USING (name, patch_id)
                WHERE u.name = s.name AND u.seed = s.seed AND c.len IS NOT NULL) AS used_len,
              (SELECT count(*) FILTER (WHERE e.stat)::float8 / count(*) FROM ends e JOIN region r USING (name)
                WHERE e.name = s.name AND e.seed = s.seed AND ST_Within(e.p, ST_Buffer(r.geom, -50))) AS stat_junctions
         FROM (SELECT DISTINCT name, seed FROM timing WHERE method = 'patches') s)
SELECT p.name,
       round((100 * (SELECT sum(ST_Length(geom)) FILTER (WHERE road_class ~ '^((motorway|trunk|primary|secondary|tertiary)(_link)?|avenue|highway|boulevard)$') / sum(ST_Length(geom))
                       FROM example e WHERE e.name = p.name))::numeric, 1) AS ex_main_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY p.main_share))::numeric, 1) AS grown_main_pct,
       round((SELECT avg(len) FROM conn c WHERE c.name = p.name)::numeric, 1) AS library_connector_m,
       round(percentile_cont(0.5) WITHIN GROUP (ORDER BY p.used_len)::numeric, 1) AS used_connector_m,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY p.stat_junctions))::numeric, 1) AS junctions_with_stat_pct
  FROM per_seed p GROUP BY p.name ORDER BY p.name;
\echo main streets grown against the example (grow_patches, per seed): main-street length, whole hull, grown over example
WITH k AS (SELECT '^((motorway|trunk|primary|secondary|tertiary)(_link)?|avenue|highway|boulevard)$' AS re),
     ex AS (SELECT e.name, sum(ST_Length(e.geom)) AS len FROM example e, k WHERE e.road_class ~ k.re GROUP BY e.name),
     gr AS (SELECT g.name, g.seed, sum(ST_Length(g.geom)) FILTER (WHERE g.road_class ~ k.re) AS len
              FROM grown g, k WHERE g.method = 'patches' GROUP BY g.name, g.seed)
SELECT gr.name, round((ex.len / 1000)::numeric, 1) AS example_main_km,
       string_agg(gr.seed || ': ' || round((coalesce(gr.len, 0) / ex.len)::numeric, 2), ', ' ORDER BY gr.seed) AS grown_over_example
  FROM gr JOIN ex USING (name) GROUP BY gr.name, ex.len ORDER BY gr.name;
\echo avenue ends (grow_patches, mean over seeds): nodes inside the hull shrunk by 50 m where one main street ends and only local streets go on (promote_arterials continues those it can), example and grown
WITH k AS (SELECT '^((motorway|trunk|primary|secondary|tertiary)(_link)?|avenue|highway|boulevard)$' AS re),
     nets AS (SELECT name, -1 AS seed, road_class, geom FROM example
              UNION ALL SELECT name, seed, road_class, geom FROM grown WHERE method = 'patches'),
     ends AS (SELECT n.name, n.seed, ST_SnapToGrid(e.p, 0.05) AS p, count(*) AS streets,
                     count(*) FILTER (WHERE n.road_class ~ k.re) AS mains
                FROM nets n CROSS JOIN k, LATERAL (VALUES (ST_StartPoint(n.geom)), (ST_EndPoint(n.geom))) AS e(p)
               GROUP BY 1, 2, 3),
     per_seed AS (SELECT e.name, e.seed, count(*) FILTER (WHERE e.mains = 1 AND e.streets > 1) AS n
                    FROM ends e JOIN region r USING (name) WHERE ST_Within(e.p, ST_Buffer(r.geom, -50)) GROUP BY 1, 2)
SELECT name, max(n) FILTER (WHERE seed = -1) AS example, round(avg(n) FILTER (WHERE seed >= 0), 1) AS grown
  FROM per_seed GROUP BY name ORDER BY name;
\echo φ against the statistical share (grow_patches, per seed): the share of the length the statistical fallback grew (origin grow_parametric, its joins included; median), the correlation between it and the relative difference of φ, the change of φ per 10 points of it (least squares), the median difference of φ on the seeds in the top quarter of that share and on the rest, and the seeds with φ past +15 % / under -15 % (of them in the top quarter)
WITH s AS (SELECT name, seed, sum(ST_Length(geom)) FILTER (WHERE origin LIKE 'grow_parametric%') / sum(ST_Length(geom)) AS stat
             FROM grown WHERE method = 'patches' GROUP BY 1, 2),
     j AS (SELECT s.name, coalesce(s.stat, 0) AS stat, c.relative_difference AS phi
             FROM s JOIN cmp c USING (name, seed) WHERE c.method = 'patches' AND c.metric = 'orientation_order'),
     q AS (SELECT name, percentile_cont(0.75) WITHIN GROUP (ORDER BY stat) AS q3 FROM j GROUP BY name)
SELECT j.name, count(*) AS seeds, round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY stat))::numeric, 1) AS stat_pct,
       round(corr(stat, phi)::numeric, 2) AS correlation, round((10 * regr_slope(phi, stat))::numeric, 1) AS phi_pct_per_10_points,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY phi) FILTER (WHERE stat >= q3))::numeric, 1) AS phi_pct_top_quarter,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY phi) FILTER (WHERE stat < q3))::numeric, 1) AS phi_pct_rest,
       count(*) FILTER (WHERE phi > 0.15) || ' (' || count(*) FILTER (WHERE phi > 0.15 AND stat >= q3) || ')' AS over,
       count(*) FILTER (WHERE phi < -0.15) || ' (' || count(*) FILTER (WHERE phi < -0.15 AND stat >= q3) || ')' AS under
  FROM j JOIN q USING (name) GROUP BY j.name ORDER BY j.name;
\echo orientation order by level (grow_patches, median over seeds; degree-2 chains merged, inside the hull shrunk by 50 m): main and local streets apart, example and grown
WITH k AS (SELECT '^((motorway|trunk|primary|secondary|tertiary)(_link)?|avenue|highway|boulevard)$' AS re),
     lv AS (SELECT r.name, s.seed, r.geom,
                   (streetgen.network_stats(format('SELECT geom FROM example WHERE name = %L AND road_class ~ %L', r.name, k.re),
                                            0, ST_Buffer(r.geom, -50), simplify => true)).orientation_order AS ex_main,
                   (streetgen.network_stats(format('SELECT geom FROM example WHERE name = %L AND NOT coalesce(road_class ~ %L, false)', r.name, k.re),
                                            0, ST_Buffer(r.geom, -50), simplify => true)).orientation_order AS ex_local,
                   (streetgen.network_stats(format('SELECT geom FROM grown WHERE method = ''patches'' AND name = %L AND seed = %s AND road_class ~ %L',
                                                   r.name, s.seed, k.re), 0, ST_Buffer(r.geom, -50), simplify => true)).orientation_order AS gr_main,
                   (streetgen.network_stats(format('SELECT geom FROM grown WHERE method = ''patches'' AND name = %L AND seed = %s AND NOT coalesce(road_class ~ %L, false)',
                                                   r.name, s.seed, k.re), 0, ST_Buffer(r.geom, -50), simplify => true)).orientation_order AS gr_local
              FROM region r CROSS JOIN k CROSS JOIN (SELECT DISTINCT seed FROM timing WHERE method = 'patches') s)
SELECT name, round(min(ex_main)::numeric, 3) AS ex_main, round(percentile_cont(0.5) WITHIN GROUP (ORDER BY gr_main)::numeric, 3) AS grown_main,
       round(min(ex_local)::numeric, 3) AS ex_local, round(percentile_cont(0.5) WITHIN GROUP (ORDER BY gr_local)::numeric, 3) AS grown_local
  FROM lv GROUP BY name ORDER BY name;
\echo street bends (grow_patches, median over seeds; degree-2 chains merged): turn per km (all the turns at shape points) and the share of streets that bend as a whole by 10 degrees or more (chord under 0.99873 of the length, as an arc turning by 10 degrees), the example's streets against the statistical fallback's (origin grow_parametric, its joins included)
CREATE FUNCTION pg_temp.turn(g geometry) RETURNS double precision LANGUAGE sql IMMUTABLE AS $$
  WITH p AS (SELECT (d).path[1] AS i, (d).geom AS pt FROM ST_DumpPoints(g) AS d),
       s AS (SELECT i, ST_Azimuth(pt, lead(pt) OVER (ORDER BY i)) AS az FROM p),
       t AS (SELECT az - lag(az) OVER (ORDER BY i) AS d FROM s WHERE az IS NOT NULL)
  SELECT coalesce(sum(abs(mod((d + 3 * pi())::numeric, (2 * pi())::numeric) - pi()::numeric)), 0)::double precision
    FROM t WHERE d IS NOT NULL $$;
WITH ex AS (SELECT name, (ST_Dump(ST_LineMerge(ST_Collect(geom)))).geom AS g FROM example GROUP BY name),
     gr AS (SELECT name, seed, (ST_Dump(ST_LineMerge(ST_Collect(geom)))).geom AS g
              FROM grown WHERE method = 'patches' AND origin = 'grow_parametric' GROUP BY name, seed),
     exs AS (SELECT name, 1000 * sum(pg_temp.turn(g)) / sum(ST_Length(g)) AS per_km,
                    avg((ST_Distance(ST_StartPoint(g), ST_EndPoint(g)) < 0.99873 * ST_Length(g))::int) AS bent
               FROM ex GROUP BY name),
     grs AS (SELECT name, seed, 1000 * sum(pg_temp.turn(g)) / nullif(sum(ST_Length(g)), 0) AS per_km,
                    avg((ST_Distance(ST_StartPoint(g), ST_EndPoint(g)) < 0.99873 * ST_Length(g))::int) AS bent,
                    count(*) AS streets
               FROM gr GROUP BY name, seed)
SELECT e.name, round(e.per_km::numeric, 2) AS example_rad_per_km,
       round(percentile_cont(0.5) WITHIN GROUP (ORDER BY g.per_km)::numeric, 2) AS fallback_rad_per_km,
       round((100 * e.bent)::numeric, 1) AS example_bent_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY g.bent))::numeric, 1) AS fallback_bent_pct,
       percentile_cont(0.5) WITHIN GROUP (ORDER BY g.streets) AS fallback_streets
  FROM exs e LEFT JOIN grs g USING (name) GROUP BY e.name, e.per_km, e.bent ORDER BY e.name;
CREATE INDEX ON grown USING gist (geom);
ANALYZE grown;
SELECT method, (SELECT count(*) FROM grown g2 WHERE g2.method = m.method) AS edges_checked,
       (SELECT count(*) FROM grown a JOIN grown b ON a.method = m.method AND b.method = m.method AND a.name = b.name
           AND a.seed = b.seed AND a.id < b.id AND ST_Intersects(a.geom, b.geom)
         WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))) AS crossings_without_node,
       (SELECT count(*) FROM grown g JOIN region r USING (name) WHERE g.method = m.method AND NOT ST_CoveredBy(g.geom, r.geom)) AS outside_region
  FROM (VALUES ('patches'), ('example')) AS m(method);
\echo crossings without a shared node, if any
SELECT a.method, a.name, a.seed, a.id, b.id, a.origin, b.origin, ST_AsText(ST_Intersection(a.geom, b.geom)) AS at
  FROM grown a JOIN grown b ON a.method = b.method AND a.name = b.name AND a.seed = b.seed AND a.id < b.id
   AND ST_Intersects(a.geom, b.geom)
 WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node));
SQL

echo
echo "coverage: the share of the hull shrunk by 50 m farther than 100 m from every street (points of a 25 m grid), the example's and the grown networks' (median, min-max over the seeds), the same within 150 m of the hull's edge (edge) and 300 m or more inside it (inner), and the share of the street length outside it (between that window and the hull); compare_networks' metrics are per area of the window and do not see where the streets lie inside it (README \"Coverage\")"
psql -X -q -v ON_ERROR_STOP=1 <<'SQL'
CREATE INDEX ON example USING gist (geom);
ANALYZE example;
WITH win AS (SELECT name, ST_Buffer(geom, -50) AS geom, ST_Boundary(geom) AS edge FROM region),
     pts AS (SELECT w.name, q.p, ST_Distance(q.p, w.edge) < 150 AS near_edge, ST_Distance(q.p, w.edge) >= 300 AS inner_part
               FROM win w, ST_SquareGrid(25, w.geom) AS c, LATERAL (SELECT ST_Centroid(c.geom) AS p) q
              WHERE ST_Intersects(q.p, w.geom)),
     ex_pts AS (SELECT p.*, NOT EXISTS (SELECT 1 FROM example e WHERE e.name = p.name AND ST_DWithin(e.geom, p.p, 100)) AS empty
                  FROM pts p),
     ex AS (SELECT name, avg(empty::int) AS empty, avg(empty::int) FILTER (WHERE near_edge) AS edge_empty,
                   avg(empty::int) FILTER (WHERE inner_part) AS inner_empty
              FROM ex_pts GROUP BY name),
     runs AS (SELECT DISTINCT method, name, seed FROM grown),
     gr_pts AS (SELECT r.method, r.name, r.seed, p.near_edge, p.inner_part,
                       NOT EXISTS (SELECT 1 FROM grown g WHERE g.method = r.method AND g.name = r.name AND g.seed = r.seed
                                     AND ST_DWithin(g.geom, p.p, 100)) AS empty
                  FROM runs r JOIN pts p USING (name)),
     gr AS (SELECT method, name, seed, avg(empty::int) AS empty, avg(empty::int) FILTER (WHERE near_edge) AS edge_empty,
                   avg(empty::int) FILTER (WHERE inner_part) AS inner_empty
              FROM gr_pts GROUP BY method, name, seed),
     outside AS (SELECT g.method, g.name, g.seed, sum(ST_Length(ST_Difference(g.geom, w.geom))) / sum(ST_Length(g.geom)) AS share
                   FROM grown g JOIN win w USING (name) GROUP BY g.method, g.name, g.seed),
     ex_outside AS (SELECT e.name, sum(ST_Length(ST_Difference(e.geom, w.geom))) / sum(ST_Length(e.geom)) AS share
                      FROM example e JOIN win w USING (name) GROUP BY e.name)
SELECT gr.method, gr.name, round((100 * min(ex.empty))::numeric, 1) AS example_empty_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY gr.empty))::numeric, 1) AS grown_empty_pct,
       round((100 * min(gr.empty))::numeric, 1) || '-' || round((100 * max(gr.empty))::numeric, 1) AS grown_range,
       round((100 * min(ex.edge_empty))::numeric, 1) AS example_edge_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY gr.edge_empty))::numeric, 1) AS grown_edge_pct,
       round((100 * min(ex.inner_empty))::numeric, 1) AS example_inner_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY gr.inner_empty))::numeric, 1) AS grown_inner_pct,
       round((100 * min(x.share))::numeric, 1) AS example_outside_pct,
       round((100 * percentile_cont(0.5) WITHIN GROUP (ORDER BY o.share))::numeric, 1) AS grown_outside_pct
  FROM gr JOIN ex USING (name) JOIN outside o USING (method, name, seed) JOIN ex_outside x USING (name)
 GROUP BY gr.method, gr.name ORDER BY gr.method DESC, gr.name;
SQL

echo
echo "block shapes and the statistical streets: faces of the network (ST_Polygonize) inside the hull shrunk by 50 m, 200 m² or more; per km² of that window, median area, median compactness (4 pi area / perimeter²), median aspect ratio (long over short side of the oriented envelope) and perimeter per 1000 m², the example's against the grown blocks' (median over the seeds) apart by whether statistical streets (fallback or join) make 2 % or more of their perimeter; with_stat_pct is that share of the grown blocks (README \"Coverage\")"
psql -X -q -v ON_ERROR_STOP=1 <<'SQL'
CREATE INDEX IF NOT EXISTS grown_geom ON grown USING gist (geom);
ANALYZE grown;
-- long over short side of a face's oriented envelope (network_stats' block_aspect_ratio)
CREATE FUNCTION pg_temp.aspect(f geometry) RETURNS double precision LANGUAGE sql IMMUTABLE AS $$
  SELECT greatest(a, b) / nullif(least(a, b), 0)
    FROM (SELECT ST_Distance(ST_PointN(r, 1), ST_PointN(r, 2)) AS a, ST_Distance(ST_PointN(r, 2), ST_PointN(r, 3)) AS b
            FROM (SELECT ST_ExteriorRing(ST_OrientedEnvelope(f)) AS r) e) s $$;
WITH win AS (SELECT name, ST_Buffer(geom, -50) AS geom FROM region),
     ex_faces AS (SELECT 'example'::text AS method, name, 0 AS seed, (ST_Dump(ST_Polygonize(geom))).geom AS f
                    FROM example GROUP BY name),
     gr_faces AS (SELECT method, name, seed, (ST_Dump(ST_Polygonize(geom))).geom AS f FROM grown GROUP BY method, name, seed),
     -- the example's faces (with_stat NULL) and the grown ones, marked by their statistical perimeter
     faces AS (SELECT f.method, f.name, f.seed, f.f,
                      CASE WHEN f.method <> 'example' THEN
                        coalesce((SELECT sum(ST_Length(ST_Intersection(g.geom, ST_Buffer(ST_Boundary(f.f), 0.5))))
                                    FROM grown g
                                   WHERE g.method = f.method AND g.name = f.name AND g.seed = f.seed
                                     AND g.origin LIKE 'grow_parametric%' AND ST_DWithin(g.geom, ST_Boundary(f.f), 0.5)), 0)
                          / ST_Perimeter(f.f) >= 0.02
                      END AS with_stat
                 FROM (SELECT * FROM ex_faces UNION ALL SELECT * FROM gr_faces) f JOIN win w USING (name)
                WHERE ST_Within(f.f, w.geom) AND ST_Area(f.f) >= 200),
     per_seed AS (SELECT x.method, x.name, x.seed, x.with_stat, count(*) AS n,
                         count(*) / (ST_Area(min(w.geom)) / 1e6) AS per_km2,
                         percentile_cont(0.5) WITHIN GROUP (ORDER BY ST_Area(x.f)) AS area,
                         percentile_cont(0.5) WITHIN GROUP (ORDER BY 4 * pi() * ST_Area(x.f) / ST_Perimeter(x.f) ^ 2) AS compact,
                         percentile_cont(0.5) WITHIN GROUP (ORDER BY pg_temp.aspect(x.f)) AS aspect,
                         1000 * sum(ST_Perimeter(x.f)) / sum(ST_Area(x.f)) AS perim
                    FROM faces x JOIN win w USING (name) GROUP BY x.method, x.name, x.seed, x.with_stat),
     shares AS (SELECT method, name, seed, sum(n) FILTER (WHERE with_stat) / sum(n) AS share
                  FROM per_seed WHERE method <> 'example' GROUP BY 1, 2, 3),
     med AS (SELECT method, name, with_stat,
                    percentile_cont(0.5) WITHIN GROUP (ORDER BY per_km2) AS per_km2, percentile_cont(0.5) WITHIN GROUP (ORDER BY area) AS area,
                    percentile_cont(0.5) WITHIN GROUP (ORDER BY compact) AS compact, percentile_cont(0.5) WITHIN GROUP (ORDER BY aspect) AS aspect,
                    percentile_cont(0.5) WITHIN GROUP (ORDER BY perim) AS perim
               FROM per_seed GROUP BY 1, 2, 3)
SELECT m.method, m.name,
       CASE WHEN m.with_stat IS NULL THEN 'example' WHEN m.with_stat THEN 'grown, with statistical' ELSE 'grown, patch streets only' END AS blocks,
       round(m.per_km2::numeric, 1) AS per_km2, round(m.area::numeric) AS median_m2, round(m.compact::numeric, 3) AS compactness,
       round(m.aspect::numeric, 2) AS aspect, round(m.perim::numeric, 1) AS perimeter_per_1000m2,
       round((100 * (SELECT percentile_cont(0.5) WITHIN GROUP (ORDER BY share) FROM shares s WHERE s.method = m.method AND s.name = m.name))::numeric, 1) AS with_stat_pct
  FROM med m
 ORDER BY 2, 1 DESC, 3;
SQL

echo
echo "sampling noise of three headline metrics (each example's parts inside the hull shrunk by 50 m, resampled with replacement $(grep -m1 '^RESAMPLES' "$repo/bench/patches/sampling_noise.py" | cut -d' ' -f3) times): phi over its streets (degree-2 chains merged), block_median over its blocks, four_way (the 4-way nodes' share) over its nodes; the spread of the relative difference from the example's value and the share of resamples past 15 %; value_here is the script's own value of the full sample (phi's chains are ST_LineMerge's, network_stats' its own simplification: near equal)"
psql -X -q -A -F, -t -v ON_ERROR_STOP=1 <<'SQL' | /usr/bin/python3 "$repo/bench/patches/sampling_noise.py"
WITH win AS (SELECT name, ST_Buffer(geom, -50) AS geom FROM region),
     chain AS (SELECT name, (ST_Dump(ST_LineMerge(ST_Collect(geom)))).geom AS g FROM example GROUP BY name),
     st AS (SELECT w.name, n.* FROM win w,
                   LATERAL streetgen.network_stats(format('SELECT geom FROM example WHERE name = %L', w.name), 0, w.geom,
                                                   simplify => true) AS n)
SELECT 'phi', c.name, ST_Length(ST_Intersection(c.g, w.geom)), degrees(ST_Azimuth(ST_StartPoint(c.g), ST_EndPoint(c.g))), s.orientation_order
  FROM chain c JOIN win w USING (name) JOIN st s USING (name)
 WHERE ST_Intersects(c.g, w.geom) AND NOT ST_IsClosed(c.g) AND ST_Length(ST_Intersection(c.g, w.geom)) > 0
UNION ALL
SELECT 'block_median', s.name, a, NULL, s.block_area_median FROM st s, unnest(s.block_areas) AS a
UNION ALL
SELECT 'four_way', s.name, d, NULL, s.degree4_share FROM st s, unnest(s.degrees) AS d;
SQL

echo
echo "the realism goal as the example itself would score it (tile_noise.py): the window cut into square tiles of ${TILES:-250 500} m, as many drawn with replacement $(grep -m1 '^RESAMPLES' "$repo/bench/patches/tile_noise.py" | cut -d' ' -f3) times, each draw one network scored as compare_networks scores a growth; the share of draws whose per-pair median is over 5 % and their values past 15 % a pair, beside the growths' (grow_patches, this run's seeds), the share of draws and of growths whose 4-way or dead-end share is more than 5 percentage points off the example's (and below, those shares' spread), the share of draws and of growths that meet the whole goal (all three), and by metric the share of draws / of growths past 15 %"
psql -X -q -A -F, -t -v ON_ERROR_STOP=1 -v tiles="{${TILES:-250 500}}" <<'SQL' | /usr/bin/python3 "$repo/bench/patches/tile_noise.py"
WITH win AS (SELECT name, ST_Buffer(geom, -50) AS geom FROM region),
     size AS (SELECT unnest(translate(:'tiles', ' ', ',')::float8[]) AS m),
     tile AS (SELECT w.name, s.m, g.i || ' ' || g.j AS id, ST_Intersection(g.geom, w.geom) AS geom
                FROM win w, size s, LATERAL ST_SquareGrid(s.m, w.geom) AS g
               WHERE ST_Intersects(g.geom, w.geom)),
     face AS (SELECT name, (ST_Dump(ST_Polygonize(geom))).geom AS f FROM example GROUP BY name),
     st AS (SELECT w.name, n.* FROM win w,
                   LATERAL streetgen.network_stats(format('SELECT geom FROM example WHERE name = %L', w.name), 0, w.geom,
                                                   simplify => true) AS n)
SELECT 'tile', t.name, t.m, t.id, n.area, n.total_length, array_to_string(n.degrees, ' '),
       array_to_string(n.orientation_histogram, ' ')
  FROM tile t, LATERAL streetgen.network_stats(format('SELECT geom FROM example WHERE name = %L', t.name), 0, t.geom,
                                               simplify => true) AS n
 WHERE ST_Area(t.geom) > 0
UNION ALL
SELECT 'block', t.name, t.m, t.id, ST_Area(f.f), NULL, NULL, NULL
  FROM face f JOIN win w USING (name) JOIN tile t ON t.name = f.name AND ST_Intersects(t.geom, ST_PointOnSurface(f.f))
 WHERE ST_Within(f.f, w.geom)
UNION ALL
SELECT 'reported', s.name, NULL, m.metric, m.value, NULL, NULL, NULL
  FROM st s, LATERAL (VALUES ('street_density', s.street_density), ('intersection_density', s.intersection_density),
                             ('mean_degree', s.mean_degree), ('dead_end_share', s.dead_end_share),
                             ('degree4_share', s.degree4_share), ('connected_node_ratio', s.connected_node_ratio),
                             ('orientation_order', s.orientation_order),
                             ('block_area_median', s.block_area_median)) AS m(metric, value)
UNION ALL
SELECT 'grown', name, NULL, seed::text, max(score) FILTER (WHERE metric = 'median_abs_relative_difference'), NULL,
       string_agg(metric, ' ') FILTER (WHERE abs(relative_difference) > 0.15),
       max(candidate_value - reference_value) FILTER (WHERE metric = 'degree4_share') || ' ' ||
       max(candidate_value - reference_value) FILTER (WHERE metric = 'dead_end_share')
  FROM cmp WHERE method = 'patches' GROUP BY name, seed;
SQL
echo
echo "where phi comes from (grow_patches): the grown streets (degree-2 chains merged, as network_stats; a row is a segment) by what made them, each kind's share of the length inside the hull shrunk by 50 m and the phi of its streets alone (all seeds together); phi grown is the mean over the seeds (the script's own, near network_stats')"
psql -X -q -A -F, -t -v ON_ERROR_STOP=1 <<'SQL' | /usr/bin/python3 "$repo/bench/patches/phi_sources.py"
WITH win AS (SELECT name, ST_Buffer(geom, -50) AS geom FROM region),
     e AS (SELECT 'example' AS source, name, 0 AS seed, '' AS patch, (ST_Dump(geom)).geom AS g FROM example
           UNION ALL
           SELECT 'grown', name, seed, CASE WHEN origin LIKE 'grow_patches:%' THEN substr(origin, 14) ELSE '' END,
                  (ST_Dump(geom)).geom
             FROM grown WHERE method = 'patches')
SELECT e.source, e.name, e.seed, e.patch, ST_X(ST_StartPoint(e.g)), ST_Y(ST_StartPoint(e.g)), ST_X(ST_EndPoint(e.g)),
       ST_Y(ST_EndPoint(e.g)), CASE WHEN ST_Intersects(e.g, w.geom) THEN ST_Length(ST_Intersection(e.g, w.geom)) ELSE 0 END
  FROM e JOIN win w USING (name);
SQL

echo
echo "where the T's come from (grow_patches): T-junctions inside the hull shrunk by 50 m by their lone street (a patch's or statistical, main or local) and what it reaches at its far end; a T becomes a crossing without a junction more only by joining a T facing it (tee_sources.py)"
psql -X -q -A -F, -t -v ON_ERROR_STOP=1 <<'SQL' | /usr/bin/python3 "$repo/bench/patches/tee_sources.py"
WITH win AS (SELECT name, ST_Buffer(geom, -50) AS geom FROM region),
     e AS (SELECT 'example' AS source, name, 0 AS seed, 'patch' AS kind, road_class, (ST_Dump(geom)).geom AS g FROM example
           UNION ALL
           SELECT 'grown', name, seed, CASE WHEN origin LIKE 'grow_parametric%' THEN 'statistical' ELSE 'patch' END, road_class,
                  (ST_Dump(geom)).geom
             FROM grown WHERE method = 'patches')
SELECT e.source, e.name, e.seed, e.kind,
       CASE WHEN e.road_class ~ '^((motorway|trunk|primary|secondary|tertiary)(_link)?|avenue|highway|boulevard)$' THEN 'main' ELSE 'local' END,
       ST_Intersects(ST_StartPoint(e.g), w.geom)::int, ST_Intersects(ST_EndPoint(e.g), w.geom)::int,
       (SELECT string_agg(ST_X(p.geom) || ' ' || ST_Y(p.geom), ';' ORDER BY p.path) FROM ST_DumpPoints(e.g) AS p)
  FROM e JOIN win w USING (name) WHERE ST_NPoints(e.g) >= 2;
SQL

if [ "${SPEED:-1}" = 0 ]; then
  echo "Road data: © OpenStreetMap contributors, ODbL 1.0 (example patches of Nishida et al. 2016)"
  exit 0
fi
echo "== speed: squares grown from tokyo, one SQL call each, grow_patches against grow_example (same run)"
psql -X -q -v ON_ERROR_STOP=1 <<SQL
INSERT INTO patch SELECT 'tokyo-speed', * FROM streetgen.extract_patches('SELECT * FROM example WHERE name = ''tokyo''')
 WHERE NOT EXISTS (SELECT 1 FROM patch WHERE name = 'tokyo');
SQL
psql -X -q -v ON_ERROR_STOP=1 <<'SQL'
CREATE FUNCTION square(method text, side double precision, OUT km double precision, OUT seconds double precision, OUT edges bigint)
  LANGUAGE plpgsql AS $$
DECLARE
  t0 timestamptz := clock_timestamp();
  src text := CASE WHEN EXISTS (SELECT 1 FROM patch WHERE name = 'tokyo') THEN 'tokyo' ELSE 'tokyo-speed' END;
BEGIN
  IF method = 'patches' THEN
    SELECT count(*), sum(ST_Length(g.geom)) / 1000 INTO edges, km
      FROM streetgen.grow_patches(format('SELECT * FROM patch WHERE name = %L', src),
                                  ST_MakeEnvelope(0, 0, side, side, 0), ST_MakePoint(side / 2, side / 2), NULL,
                                  '{"seed": 1, "max_edges": 2000000}') AS g;
  ELSE
    SELECT count(*), sum(ST_Length(g.geom)) / 1000 INTO edges, km
      FROM streetgen.grow_example('SELECT id, road_class, geom FROM example WHERE name = ''tokyo''',
                                  ST_MakeEnvelope(0, 0, side, side, 0), ST_MakePoint(side / 2, side / 2), NULL,
                                  '{"seed": 1, "rotation": false, "max_edges": 2000000}') AS g;
  END IF;
  seconds := extract(epoch FROM clock_timestamp() - t0);
END
$$;
SQL
psql -X -q -v ON_ERROR_STOP=1 -c "CREATE TABLE speed (side double precision, method text, edges bigint, km double precision,
                                                      seconds double precision)"
for side in $sides; do
  psql -X -q -At -v ON_ERROR_STOP=1 -c "INSERT INTO speed SELECT $side, 'patches', p.edges, p.km, p.seconds FROM square('patches', $side) p" \
       -c "INSERT INTO speed SELECT $side, 'example', e.edges, e.km, e.seconds FROM square('example', $side) e" -c "
    SELECT format('side %s m: grow_patches %s edges %s km in %s s (%s km/s); grow_example %s km in %s s (%s km/s); ratio of speeds patches/example %s',
                  $side, p.edges, round(p.km::numeric, 1), round(p.seconds::numeric, 2), round((p.km / p.seconds)::numeric),
                  round(e.km::numeric, 1), round(e.seconds::numeric, 2), round((e.km / e.seconds)::numeric),
                  round(((p.km / p.seconds) / (e.km / e.seconds))::numeric, 2))
      FROM speed p, speed e WHERE p.side = $side AND p.method = 'patches' AND e.side = $side AND e.method = 'example'"
done
# The issue's cost growth from 30 km to 3,000 km: seconds per km at each size over those of the
# smallest square (1.0: linear; above 1, each km costs more as the network grows).
echo "cost growth: seconds per km over the smallest square's"
psql -X -q -v ON_ERROR_STOP=1 -c "
  SELECT s.method, s.side, s.edges, round(s.km::numeric) AS km, round(s.seconds::numeric, 2) AS seconds,
         round((s.km / s.seconds)::numeric) AS km_per_s,
         round(((s.seconds / s.km) / (f.seconds / f.km))::numeric, 2) AS cost_per_km_vs_smallest
    FROM speed s CROSS JOIN LATERAL (SELECT * FROM speed f WHERE f.method = s.method ORDER BY f.side LIMIT 1) f
   ORDER BY s.method DESC, s.side"
echo "pictures: $out/*.png"
echo "Road data: © OpenStreetMap contributors, ODbL 1.0 (example patches of Nishida et al. 2016)"
