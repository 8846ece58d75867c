#!/usr/bin/env bash
# The import's backend memory: stages an OSM file as scripts/streetgen-import does (the reader,
# streetgen-osm-stage, into an unlogged table from the session), then runs create_model and
# load_osm_ways in that session, as the import does, ROUNDS times (default 1), each into a new
# fresh session and model, and prints the
# backend's peak private memory (RssAnon, sampled by bench/anon_peak.sh) and its CPU seconds
# (user + system). Settings as the import's defaults (details on); DETAILS=false measures a
# surfaces-only import (streetgen-import -c details=false).
#
#   PGHOST=... PGPORT=... PGDATABASE=... [DETAILS=false] bash bench/surfaces/import-memory.sh FILE [ROUNDS]
#
# The database must have streetgen installed; the model (mem_<name>) is dropped at the end. The
# reader: STREETGEN_OSM_STAGE, else streetgen-osm-stage on PATH, else build/ of this checkout.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
file=${1:?usage: import-memory.sh FILE [ROUNDS]}
rounds=${2:-1}
name="$(basename "$file")"; name="${name%%.*}"; name="${name//-/_}"
model=mem_$name
stage_bin="${STREETGEN_OSM_STAGE:-$(command -v streetgen-osm-stage || echo "$repo/build/streetgen-osm-stage")}"
export STREETGEN_OSM_STAGE="$stage_bin" STREETGEN_OSM_FILE="$file"
export PGOPTIONS="-c client_min_messages=warning"
tmp=$(mktemp -d)
cleanup() {
  psql -X -q -c "SELECT streetgen.drop_model('$model') FROM streetgen.model WHERE name = '$model'" \
       -c "DROP TABLE IF EXISTS streetgen_staging.mem_$name CASCADE" >/dev/null 2>&1 || true
  rm -rf "$tmp"
}
trap cleanup EXIT


echo "| file | round | peak private MB | backend CPU s | load |"
echo "|---|---|---|---|---|"
for r in $(seq "$rounds"); do
  psql -X -q -c "SELECT streetgen.drop_model('$model') FROM streetgen.model WHERE name = '$model'" >/dev/null
  out=$(psql -X -q -At -v ON_ERROR_STOP=1 -v model="$model" -v details="${DETAILS:-true}" <<SQL
SELECT pg_backend_pid() AS pid \gset
\setenv SGPID :pid
\! bash "$repo/bench/anon_peak.sh" \$SGPID "$tmp/peak.kb" >/dev/null 2>&1 &
SELECT pg_sleep(0.1) \g /dev/null
CREATE SCHEMA IF NOT EXISTS streetgen_staging;
DROP TABLE IF EXISTS streetgen_staging.mem_$name CASCADE;
CREATE UNLOGGED TABLE streetgen_staging.mem_$name (kind text, source text, tags jsonb, geom geometry);
\\copy streetgen_staging.mem_$name FROM PROGRAM '"\$STREETGEN_OSM_STAGE" "\$STREETGEN_OSM_FILE"'
CREATE TEMP VIEW _osm_ways AS SELECT source, tags, geom FROM streetgen_staging.mem_$name WHERE kind = 'way';
SELECT streetgen.utm_srid(ST_SetSRID(ST_Extent(geom)::geometry, 4326))::text AS srid FROM _osm_ways \gset
SELECT streetgen.create_model(:'model', :'srid'::integer) \g /dev/null
UPDATE :"model".settings SET details = :'details' \g /dev/null
SELECT loaded FROM streetgen.load_osm_ways(:'model', 'pg_temp._osm_ways') \g /dev/null
\! awk '{ print \$14 + \$15 }' /proc/\$SGPID/stat
SQL
)
  sleep 0.3  # (the sampler stops with the backend)
  awk -v f="$name" -v r="$r" -v kb="$(cat "$tmp/peak.kb")" -v t="$out" -v hz="$(getconf CLK_TCK)" -v l="$(cut -d' ' -f1-3 /proc/loadavg)" \
    'BEGIN { printf "| %s | %d | %.1f | %.2f | %s |\n", f, r, kb / 1024, t / hz, l }'
done
