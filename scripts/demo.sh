#!/usr/bin/env bash
# The main job, end to end on a fresh Debian 12 machine: install dependencies, build and install
# streetgen, start a throwaway local PostgreSQL cluster, create the extension, import the real road
# network of central Gothenburg (OpenStreetMap, fetched from the npm registry) and print what is
# there and how to connect. Re-running it makes the demo database anew; the cluster keeps running.
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
# A throwaway demo: the database is made anew each run, with the extension just built.
dropdb --if-exists streetgen
createdb streetgen
psql -X -q -v ON_ERROR_STOP=1 -c "CREATE EXTENSION streetgen CASCADE"

network="$(bash "$repo/scripts/fetch-demo-data.sh")"
# The model's triggers generate the street surfaces as the axes arrive.
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
  SELECT q.nodes, q.junctions, q.intersections, q.sections, q.invalid_geometries AS invalid,
         q.missing_intersections AS junctions_without_surface,
         round(q.surface_area::numeric / 10000, 1) AS roadway_ha,
         (SELECT count(*) FROM gothenburg.corner WHERE arc IS NOT NULL) AS curb_arcs
    FROM streetgen.surface_quality('gothenburg') q"
psql -X -q -P footer=off -c "
  SELECT 'corner' AS kind, status, count(*) FROM gothenburg.corner GROUP BY 1, 2
  UNION ALL SELECT 'intersection', status, count(*) FROM gothenburg.intersection GROUP BY 1, 2
  ORDER BY 1, 3 DESC"
psql -X -q -P footer=off -c "
  SELECT road_class, count(*) AS axes, round(sum(ST_Length(geom))::numeric / 1000, 1) AS km,
         round(avg(roadway_width)::numeric, 2) AS mean_width_m, round(avg(speed_kmh)::numeric, 1) AS mean_speed_kmh
    FROM gothenburg.axis GROUP BY road_class ORDER BY km DESC"
# A QGIS project for the demo model, styled, its layers repainting when an edit commits.
project="$dir/gothenburg.qgs"
if ! QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR="$(mktemp -d)" /usr/bin/python3 "$repo/qgis/make_project.py" \
     "host=localhost port=$port dbname=streetgen user=postgres" gothenburg "$project" >/dev/null 2>&1; then
  project="(not written: PyQGIS missing; apt-get install python3-qgis)"
fi

cat <<TXT
Road data: (c) OpenStreetMap contributors, ODbL 1.0 (via npm geojson-path-finder@2.1.0).

== connect ==
  psql:  psql "host=localhost port=$port dbname=streetgen user=postgres"
         (or: PGHOST=$dir PGPORT=$port psql -U postgres streetgen)
  QGIS:  open the project $project
         or: Layer > Data Source Manager > PostgreSQL > New
         Name: streetgen-demo   Host: localhost   Port: $port   Database: streetgen
         Authentication: Basic, user postgres, no password (trust on loopback: a throwaway cluster)
         then add the layers gothenburg.section, gothenburg.intersection (surfaces),
         gothenburg.corner (arc_segmentized: the curb arcs) and gothenburg.axis (EPSG:32632).
  Try:   edit gothenburg.axis in QGIS or psql: the surfaces follow at commit
         UPDATE gothenburg.settings SET turn_speed_ratio = 0.3;   -- a full recompute
  Stop:  bash $repo/scripts/pgcluster.sh stop $dir      (remove: ... destroy $dir)
Demo ready in $(( $(date +%s) - started )) s.
TXT
