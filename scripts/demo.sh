#!/usr/bin/env bash
# The main job, end to end on a fresh Debian 12 machine: install dependencies, build and install
# streetgen, start a throwaway local PostgreSQL cluster, create the extension, import the real road
# network of central Gothenburg (OpenStreetMap, fetched from the npm registry) and print what is
# there and how to connect. Re-running it re-imports the model; the cluster keeps running.
#   STREETGEN_DEMO_DIR   cluster folder (default /var/tmp/streetgen-demo)
#   STREETGEN_DEMO_PORT  port on localhost (default 54321)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dir="${STREETGEN_DEMO_DIR:-/var/tmp/streetgen-demo}"
port="${STREETGEN_DEMO_PORT:-54321}"
started=$(date +%s)

STREETGEN_BUILD_TESTS=OFF STREETGEN_BUILD_DIR="${STREETGEN_BUILD_DIR:-$repo/build-demo}" bash "$repo/scripts/build.sh"
bash "$repo/scripts/pgcluster.sh" start "$dir" "$port"
export PGHOST="$dir" PGPORT="$port" PGUSER=postgres PGDATABASE=streetgen
export PGOPTIONS="-c client_min_messages=warning"
psql -X -q -d postgres -tAc "SELECT 1 FROM pg_database WHERE datname = 'streetgen'" | grep -q 1 || createdb streetgen
psql -X -q -v ON_ERROR_STOP=1 -c "CREATE EXTENSION IF NOT EXISTS streetgen CASCADE" \
  -c "ALTER EXTENSION streetgen UPDATE" \
  -c "SELECT streetgen.drop_model('gothenburg') FROM streetgen.model WHERE name = 'gothenburg'" >/dev/null

network="$(bash "$repo/scripts/fetch-demo-data.sh")"
"$repo/scripts/streetgen-import" -m gothenburg "$network"

echo
echo "== streetgen demo: what is there =="
psql -X -q -P footer=off -c "SELECT extension AS streetgen, geos, cgal, postgis, postgresql FROM streetgen.version()"
psql -X -q -P footer=off -c "
  SELECT m.name AS model, m.srid, count(a.*) AS axes, round(sum(ST_Length(a.geom))::numeric / 1000, 1) AS km,
         round(avg(a.roadway_width)::numeric, 2) AS mean_width_m, round(avg(a.speed_kmh)::numeric, 1) AS mean_speed_kmh,
         round(100.0 * avg(('roadway_width' = ANY(a.estimated))::int), 1) AS width_estimated_pct,
         round(100.0 * avg(('speed_kmh' = ANY(a.estimated))::int), 1) AS speed_estimated_pct,
         sum((a.structure = 'bridge')::int) AS bridges, sum((a.structure = 'tunnel')::int) AS tunnels
    FROM streetgen.model m, gothenburg.axis a WHERE m.name = 'gothenburg' GROUP BY m.name, m.srid"
psql -X -q -P footer=off -c "
  SELECT road_class, count(*) AS axes, round(sum(ST_Length(geom))::numeric / 1000, 1) AS km,
         round(avg(roadway_width)::numeric, 2) AS mean_width_m, round(avg(speed_kmh)::numeric, 1) AS mean_speed_kmh
    FROM gothenburg.axis GROUP BY road_class ORDER BY km DESC"
cat <<TXT
Road data: (c) OpenStreetMap contributors, ODbL 1.0 (via npm geojson-path-finder@2.1.0).

== connect ==
  psql:  psql "host=localhost port=$port dbname=streetgen user=postgres"
         (or: PGHOST=$dir PGPORT=$port psql -U postgres streetgen)
  QGIS:  Layer > Data Source Manager > PostgreSQL > New
         Name: streetgen-demo   Host: localhost   Port: $port   Database: streetgen
         Authentication: Basic, user postgres, no password (trust on loopback: a throwaway cluster)
         then add the layer gothenburg.axis (geometry geom, EPSG:32632).
  Try:   SELECT * FROM streetgen.roadway_borders((SELECT geom FROM gothenburg.axis LIMIT 1), 7);
  Stop:  bash $repo/scripts/pgcluster.sh stop $dir      (remove: ... destroy $dir)
Demo ready in $(( $(date +%s) - started )) s.
TXT
