#!/usr/bin/env bash
# The import's backend memory: stages an OSM file as scripts/streetgen-import does (osmium sort,
# osm2pgsql with style/streetgen-osm.lua), then runs create_model and load_osm_ways in one fresh
# session, as the import does, ROUNDS times (default 1), each into a new model, and prints the
# backend's peak private memory (RssAnon, sampled by bench/anon_peak.sh) and its CPU seconds
# (user + system). Settings as the import's defaults (details on).
#
#   PGHOST=... PGPORT=... PGDATABASE=... bash bench/surfaces/import-memory.sh FILE [ROUNDS]
#
# The database must have streetgen installed; the staging table and the model (mem_<name>) are
# dropped at the end.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
file=${1:?usage: import-memory.sh FILE [ROUNDS]}
rounds=${2:-1}
name="$(basename "$file")"; name="${name%%.*}"; name="${name//-/_}"
staging=streetgen_staging.mem_$name
model=mem_$name
export PGOPTIONS="-c client_min_messages=warning"
tmp=$(mktemp -d)
cleanup() {
  psql -X -q -c "DROP TABLE IF EXISTS $staging, ${staging}_parking" \
       -c "SELECT streetgen.drop_model('$model') FROM streetgen.model WHERE name = '$model'" >/dev/null 2>&1 || true
  rm -rf "$tmp"
}
trap cleanup EXIT

psql -X -q -c "CREATE SCHEMA IF NOT EXISTS streetgen_staging" -c "DROP TABLE IF EXISTS $staging, ${staging}_parking"
if [ "$(osmium fileinfo -e -g data.objects_ordered "$file")" != "yes" ]; then
  osmium sort --overwrite --no-progress -f pbf,pbf_compression=none -o "$tmp/sorted.osm.pbf" "$file"
  file="$tmp/sorted.osm.pbf"
fi
STREETGEN_STAGING_SCHEMA=streetgen_staging STREETGEN_STAGING_TABLE=mem_$name \
PGOPTIONS="$PGOPTIONS -c default_statistics_target=1" \
  osm2pgsql --output=flex --style="$repo/style/streetgen-osm.lua" --create --log-level=warn --log-progress=false \
    ${PGDATABASE:+--database="$PGDATABASE"} "$file"

echo "| file | round | peak private MB | backend CPU s | load |"
echo "|---|---|---|---|---|"
for r in $(seq "$rounds"); do
  psql -X -q -c "SELECT streetgen.drop_model('$model') FROM streetgen.model WHERE name = '$model'" >/dev/null
  out=$(psql -X -q -At -v ON_ERROR_STOP=1 -v model="$model" <<SQL
SELECT pg_backend_pid() AS pid \gset
\setenv SGPID :pid
\! bash "$repo/bench/anon_peak.sh" \$SGPID "$tmp/peak.kb" >/dev/null 2>&1 &
SELECT pg_sleep(0.1) \g /dev/null
SELECT streetgen.utm_srid(ST_SetSRID(ST_Extent(geom)::geometry, 4326))::text AS srid FROM $staging \gset
SELECT streetgen.create_model(:'model', :'srid'::integer) \g /dev/null
SELECT loaded FROM streetgen.load_osm_ways(:'model', '$staging') \g /dev/null
\! awk '{ print \$14 + \$15 }' /proc/\$SGPID/stat
SQL
)
  sleep 0.3  # (the sampler stops with the backend)
  awk -v f="$name" -v r="$r" -v kb="$(cat "$tmp/peak.kb")" -v t="$out" -v hz="$(getconf CLK_TCK)" -v l="$(cut -d' ' -f1-3 /proc/loadavg)" \
    'BEGIN { printf "| %s | %d | %.1f | %.2f | %s |\n", f, r, kb / 1024, t / hz, l }'
done
