#!/usr/bin/env bash
# Pictures of grow_patches' operations (issue 8, item 4; Nishida et al. 2016, section 5) beside
# their examples, from the real example patches of ../shared/data/examples/patches (crops of
# OpenStreetMap: every PNG says "© OpenStreetMap contributors, ODbL"):
#   blended.png  tokyo | canberra_south_large | one growth blended between them by Gaussian
#                fall-off from each style's seed (tokyo's in the west, canberra's in the east)
#   warped.png   tokyo | tokyo grown without a guide | tokyo grown warped along an S-shaped guide
#   interpolated.png  tokyo | t = 0.5 | canberra_south_large (interpolation of the two styles)
# and prints, per picture, what the growth measured (edges, shares by origin, deviation from the
# guide's tangent).
#
#   bash bench/patches/pictures.sh             the streetgen installed for the pg_config on PATH
#   OUT=/tmp/pics SEED=3 bash bench/patches/pictures.sh   where the PNGs go (default: build/bench-patches)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
data="$(cd "$data" && pwd)"
port="${STREETGEN_BENCH_PORT:-54338}"
out="${OUT:-$repo/build/bench-patches}"
seed="${SEED:-3}"
mkdir -p "$out"
source "$repo/bench/lib.sh"
bench_cluster "$port" nobuild
psql -X -q -v ON_ERROR_STOP=1 <<SQL
CREATE TABLE example AS
SELECT n AS name, row_number() OVER (PARTITION BY n) AS id, f -> 'properties' ->> 'type' AS road_class,
       (f -> 'properties' ->> 'roundabout')::boolean AS roundabout,
       ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM unnest(ARRAY['tokyo', 'canberra_south_large']) AS n,
       jsonb_array_elements(pg_read_file('$data/examples/patches/' || n || '.geojson')::jsonb -> 'features') AS f;
CREATE TABLE patch AS
SELECT n AS name, x.* FROM unnest(ARRAY['tokyo', 'canberra_south_large']) AS n,
       streetgen.extract_patches(format('SELECT id, road_class, roundabout, geom FROM example WHERE name = %L', n)) AS x;
CREATE TABLE grown (run text, id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry);
-- An S-shaped guide across a 2.4 km square.
CREATE TABLE guide AS
SELECT ST_MakeLine(ST_MakePoint(x, 350 * sin(x / 400.0)) ORDER BY x) AS geom FROM generate_series(-1200, 1200, 20) AS x;
CREATE TABLE sq AS SELECT ST_MakeEnvelope(-1200, -1200, 1200, 1200, 0) AS geom;
INSERT INTO grown
SELECT 'blended', g.* FROM sq, streetgen.grow_patches('SELECT * FROM patch WHERE name = ''tokyo''', sq.geom,
         'MULTIPOINT((-800 0), (800 0))', NULL,
         '{"seed": $seed, "max_edges": 6000, "blend": "points", "blend_points": [[-800, 0], [800, 0]], "blend_sigma": 500,
           "interpolate": "SELECT * FROM patch WHERE name = ''canberra_south_large''"}') AS g;
INSERT INTO grown
SELECT 'free', g.* FROM sq, streetgen.grow_patches('SELECT * FROM patch WHERE name = ''tokyo''', sq.geom, 'POINT(0 0)',
         NULL, '{"seed": $seed, "max_edges": 6000}') AS g;
INSERT INTO grown
SELECT 'warped', g.* FROM sq, guide, streetgen.grow_patches('SELECT * FROM patch WHERE name = ''tokyo''', sq.geom,
         'POINT(0 0)', NULL, '{"seed": $seed, "max_edges": 6000}', NULL, NULL, guide.geom) AS g;
INSERT INTO grown
SELECT 'interpolated', g.* FROM sq, streetgen.grow_patches('SELECT * FROM patch WHERE name = ''tokyo''', sq.geom,
         'POINT(0 0)', NULL, '{"seed": $seed, "max_edges": 6000, "t": 0.5,
           "interpolate": "SELECT * FROM patch WHERE name = ''canberra_south_large''"}') AS g;
SQL

echo "== edges and shares of the length by origin (a: first style's patches, b: second's, statistical)"
psql -X -v ON_ERROR_STOP=1 <<'SQL'
\pset footer off
SELECT run, count(*) AS edges, round(sum(ST_Length(geom))::numeric / 1000, 1) AS km,
       round((sum(ST_Length(geom)) FILTER (WHERE origin LIKE 'grow_patches:%' AND origin NOT LIKE '%:b')
              / sum(ST_Length(geom)))::numeric, 3) AS share_a,
       round((coalesce(sum(ST_Length(geom)) FILTER (WHERE origin LIKE 'grow_patches:%:b'), 0)
              / sum(ST_Length(geom)))::numeric, 3) AS share_b,
       round((coalesce(sum(ST_Length(geom)) FILTER (WHERE origin = 'grow_parametric'), 0)
              / sum(ST_Length(geom)))::numeric, 3) AS share_statistical
  FROM grown GROUP BY run ORDER BY run;
SQL
echo "== blended: share of the second style's (canberra's) patch length by x band (its seed at x = 800)"
psql -X -v ON_ERROR_STOP=1 <<'SQL'
\pset footer off
SELECT width_bucket(ST_X(ST_Centroid(geom)), -1200, 1200, 6) AS band,
       round((coalesce(sum(ST_Length(geom)) FILTER (WHERE origin LIKE 'grow_patches:%:b'), 0)
              / nullif(sum(ST_Length(geom)) FILTER (WHERE origin LIKE 'grow_patches:%'), 0))::numeric, 3) AS share_b
  FROM grown WHERE run = 'blended' GROUP BY 1 ORDER BY 1;
SQL
echo "== warped: length-weighted deviation (degrees, grid directions folded to [0, 45]) from the guide's tangent, edges within 60 m of it"
psql -X -v ON_ERROR_STOP=1 <<'SQL'
\pset footer off
SELECT w.run, count(*) AS near,
       round((sum(ST_Length(w.geom) * least(d, 90 - d)) / sum(ST_Length(w.geom)))::numeric, 1) AS deviation
  FROM grown w, guide,
       LATERAL (SELECT ST_LineLocatePoint(guide.geom, ST_Centroid(w.geom)) AS f) l,
       LATERAL (SELECT mod(mod(degrees(ST_Azimuth(ST_StartPoint(w.geom), ST_EndPoint(w.geom))
                           - ST_Azimuth(ST_LineInterpolatePoint(guide.geom, greatest(f - 0.002, 0)),
                                        ST_LineInterpolatePoint(guide.geom, least(f + 0.002, 1))))::numeric, 90) + 90,
                       90)::double precision AS d) a
 WHERE w.run IN ('free', 'warped') AND ST_DWithin(w.geom, guide.geom, 60)
 GROUP BY w.run ORDER BY w.run;
SQL

dsn="host=$PGHOST port=$PGPORT user=postgres dbname=bench"
kind="CASE WHEN origin LIKE 'grow_patches:%:b' THEN 'b' WHEN origin LIKE 'grow_patches:%' THEN 'a' WHEN origin = 'bridge' THEN 'bridge' ELSE 'parametric' END"
/usr/bin/python3 "$repo/bench/patches/plot_panels.py" "$dsn" "$out/blended.png" \
  "Blending by Gaussian fall-off from each style's seed (red dots; sigma 500 m), seed $seed: black tokyo's patches, blue canberra's, orange statistical" \
  "example tokyo|SELECT geom, 'a' AS kind FROM example WHERE name = 'tokyo'" \
  "example canberra_south_large|SELECT geom, 'b' AS kind FROM example WHERE name = 'canberra_south_large'" \
  "blended growth|SELECT geom, $kind AS kind FROM grown WHERE run = 'blended' UNION ALL SELECT 'MULTIPOINT((-800 0), (800 0))'::geometry, 'point'"
/usr/bin/python3 "$repo/bench/patches/plot_panels.py" "$dsn" "$out/warped.png" \
  "Warping along a guide (red dashes): each patch turned to the nearest guide tangent, seed $seed; orange: statistical" \
  "example tokyo|SELECT geom, 'a' AS kind FROM example WHERE name = 'tokyo'" \
  "grown without a guide|SELECT geom, $kind AS kind FROM grown WHERE run = 'free' UNION ALL SELECT geom, 'guide' FROM guide" \
  "grown with the guide (warped)|SELECT geom, $kind AS kind FROM grown WHERE run = 'warped' UNION ALL SELECT geom, 'guide' FROM guide"
/usr/bin/python3 "$repo/bench/patches/plot_panels.py" "$dsn" "$out/interpolated.png" \
  "Interpolation of two styles with t = 0.5, seed $seed: black tokyo's patches, blue canberra's, orange statistical (interpolated statistics)" \
  "example tokyo|SELECT geom, 'a' AS kind FROM example WHERE name = 'tokyo'" \
  "t = 0.5|SELECT geom, $kind AS kind FROM grown WHERE run = 'interpolated'" \
  "example canberra_south_large|SELECT geom, 'b' AS kind FROM example WHERE name = 'canberra_south_large'"
echo "pictures: $out/blended.png $out/warped.png $out/interpolated.png"
