#!/usr/bin/env bash
# Import layer: every OSM file of ../shared/data/osm (all four formats) through streetgen-import
# (libosmium's reader, streetgen-osm-stage), and the GeoJSON demo network (Gothenburg, npm geojson-path-finder@2.1.0)
# through ogr2ogr, into models of one database; then tests/import/check-import.sql checks the
# result against facts gathered here with independent tools (osmium, python's json);
# tests/import/check-surfaces.sql generates street surfaces on every network and checks them;
# tests/import/check-refresh.sql checks the always-current invariant over random edits.
source "$(dirname "$0")/lib.sh"
: "${STREETGEN_SHARED_DATA:?}"
osm_dir="$STREETGEN_SHARED_DATA/osm"
[ -d "$osm_dir" ] || { echo "FAIL: no OSM data in $osm_dir (the shared data folder must sit beside the checkout)" >&2; exit 1; }
mark=$(log_mark)
db=streetgen_import
fresh_db "$db" pgtap streetgen
export PGDATABASE=$db
work="$BIN/import"
rm -rf "$work"; mkdir -p "$work"

psql -X -q -v ON_ERROR_STOP=1 -c "CREATE TABLE import_fact (model text PRIMARY KEY, file text, kind text,
  highway_ways bigint, driveable_class_ways bigint, loaded bigint, not_driveable bigint, degenerate bigint,
  minlon float8, minlat float8, maxlon float8, maxlat float8, seconds float8);
  CREATE TABLE import_source_id (model text, source text);"
classes=$(psql -X -At -c "SELECT string_agg(highway, ',' ORDER BY highway) FROM streetgen.highway_class")

# What streetgen-osm-stage stages from FILE against what osm2pgsql's flex output with the shipped
# style stages from it (sorted first: osm2pgsql needs order, the reader does not), as one row of
# stage_parity: lines by (source, tags, EWKB bytes), street parking areas by (source, tags) and
# ST_Equals.
psql -X -q -v ON_ERROR_STOP=1 -c "CREATE SCHEMA oracle;
  CREATE TABLE stage_parity (name text PRIMARY KEY, osm2pgsql_lines bigint, reader_lines bigint,
    lines_only_osm2pgsql bigint, lines_only_reader bigint, osm2pgsql_areas bigint, reader_areas bigint,
    areas_differing bigint)"
stage_parity() {
  local file=$1 name=$2 input=$1
  if [ "$(osmium fileinfo -e -g data.objects_ordered "$file")" != yes ]; then
    input="$work/$name-sorted.osm.pbf"
    osmium sort -O --no-progress -o "$input" "$file"
  fi
  STREETGEN_STAGING_SCHEMA=oracle STREETGEN_STAGING_TABLE="o_$name" \
    osm2pgsql --output=flex --style="$SRC/style/streetgen-osm.lua" --create --log-level=warn \
    --log-progress=false "$input" 2>&1 | grep -v 'osm2pgsql version' || true
  "$BIN/streetgen-osm-stage" "$file" >"$work/$name.staged"
  psql -X -q -v ON_ERROR_STOP=1 <<SQL
CREATE TABLE oracle.s_$name (kind text, source text, tags jsonb, geom geometry);
\\copy oracle.s_$name FROM '$work/$name.staged'
INSERT INTO stage_parity
SELECT '$name',
  (SELECT count(*) FROM oracle.o_$name), (SELECT count(*) FROM oracle.s_$name WHERE kind = 'way'),
  (SELECT count(*) FROM (SELECT source, tags, ST_AsEWKB(geom) FROM oracle.o_$name
                         EXCEPT ALL SELECT source, tags, ST_AsEWKB(geom) FROM oracle.s_$name WHERE kind = 'way') d),
  (SELECT count(*) FROM (SELECT source, tags, ST_AsEWKB(geom) FROM oracle.s_$name WHERE kind = 'way'
                         EXCEPT ALL SELECT source, tags, ST_AsEWKB(geom) FROM oracle.o_$name) d),
  (SELECT count(*) FROM oracle.o_${name}_parking), (SELECT count(*) FROM oracle.s_$name WHERE kind = 'parking'),
  (SELECT count(*) FROM oracle.o_${name}_parking o FULL JOIN (SELECT * FROM oracle.s_$name WHERE kind = 'parking') s USING (source)
    WHERE o.source IS NULL OR s.source IS NULL OR o.tags <> s.tags OR NOT ST_Equals(o.geom, s.geom));
SQL
}
stage_parity "$SRC/tests/import/stage-cases.osm" cases
# The same cases sorted by type, as most files are: the reader takes them in one pass (and reads
# the ways again for the multipolygon's members), where the file above, out of order, takes two.
osmium sort -O --no-progress -o "$work/cases-by-type.osm" "$SRC/tests/import/stage-cases.osm"
stage_parity "$work/cases-by-type.osm" cases_by_type

for file in "$osm_dir"/*.osm "$osm_dir"/*.osm.gz "$osm_dir"/*.osm.bz2 "$osm_dir"/*.pbf; do
  [ -e "$file" ] || continue
  base=$(basename "$file")
  model=$(echo "${base%%.*}" | tr '[:upper:]' '[:lower:]' | sed 's/[^a-z0-9_]/_/g')
  # Facts from osmium, which shares no code with the import path.
  osmium tags-filter -O -o "$work/$model-highway.osm.pbf" "$file" w/highway 2>/dev/null
  osmium tags-filter -O -o "$work/$model-classes.osm.pbf" "$file" "w/highway=$classes" 2>/dev/null
  highway_ways=$(osmium fileinfo -e -g data.count.ways "$work/$model-highway.osm.pbf")
  class_ways=$(osmium fileinfo -e -g data.count.ways "$work/$model-classes.osm.pbf")
  osmium cat -O -t way -f opl "$work/$model-highway.osm.pbf" 2>/dev/null | sed -n 's/^w\([0-9]*\) .*/osm:way\/\1/p' \
    | sed "s/^/$model\t/" >"$work/$model-ids.tsv"
  psql -X -q -v ON_ERROR_STOP=1 -c "\\copy import_source_id FROM '$work/$model-ids.tsv'"
  stage_parity "$file" "$model"
  bbox=$(osmium fileinfo -e -g data.bbox "$file" | tr -d '()' | tr ',' ' ')
  read -r minlon minlat maxlon maxlat <<<"$bbox"

  start=$(date +%s.%N)
  out=$("$SRC/scripts/streetgen-import" -m "$model" "$file")
  seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.2f", e - s }')
  echo "$out"
  read -r loaded not_driveable degenerate < <(echo "$out" | sed -n 's/.*: \([0-9]*\) axes loaded, \([0-9]*\) highway ways not driveable, \([0-9]*\) degenerate.*/\1 \2 \3/p')
  psql -X -q -v ON_ERROR_STOP=1 -c "INSERT INTO import_fact VALUES ('$model', '$base', 'osm', $highway_ways, $class_ways,
    $loaded, $not_driveable, $degenerate, $minlon, $minlat, $maxlon, $maxlat, $seconds)"
done

# The README's demo network, fetched from the npm registry like the main job does.
demo=$("$SRC/scripts/fetch-demo-data.sh")
features=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['features']))" "$demo")
start=$(date +%s.%N)
out=$("$SRC/scripts/streetgen-import" -m gothenburg "$demo")
seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.2f", e - s }')
echo "$out"
read -r loaded not_driveable degenerate < <(echo "$out" | sed -n 's/.*: \([0-9]*\) axes loaded, \([0-9]*\) highway ways not driveable, \([0-9]*\) degenerate.*/\1 \2 \3/p')
psql -X -q -v ON_ERROR_STOP=1 -c "INSERT INTO import_fact VALUES ('gothenburg', 'large-network.json', 'geojson', $features, NULL,
  $loaded, $not_driveable, $degenerate, 11.8, 57.6, 12.1, 57.8, $seconds)"

status=0
# Street surfaces only, a setting given to the import (check-surfaces.sql compares it with the
# full import of the same file); an unknown setting stops the import before anything is loaded.
"$SRC/scripts/streetgen-import" -m munich_surfaces -c details=false "$osm_dir/munich.osm.pbf" || status=1
if "$SRC/scripts/streetgen-import" -m munich_bad_setting -c no_such_setting=1 "$osm_dir/munich.osm.pbf" 2>"$work/bad-setting.err"; then
  echo "FAIL: streetgen-import accepted an unknown setting" >&2; status=1
elif ! grep -q 'no_such_setting' "$work/bad-setting.err"; then
  echo "FAIL: streetgen-import's error does not name the unknown setting: $(cat "$work/bad-setting.err")" >&2; status=1
elif [ "$(psql -X -At -c "SELECT count(*) FROM streetgen.model WHERE name = 'munich_bad_setting'")" != 0 ]; then
  echo "FAIL: an import with an unknown setting left a model behind" >&2; status=1
fi
# A file as JOSM saves new objects (negative ids, which osm2pgsql refuses) loads; a file that is
# not what its name says fails with the reader's message naming it, and leaves no model behind.
out=$("$SRC/scripts/streetgen-import" -m negative_ids "$SRC/tests/import/stage-negative-ids.osm") || status=1
echo "$out"
if [ "$(psql -X -At -c "SELECT string_agg(source, ' ' ORDER BY id) FROM negative_ids.axis")" != "osm:way/-5 osm:way/6" ]; then
  echo "FAIL: the ways of negative and positive ids are not the axes osm:way/-5 and osm:way/6" >&2; status=1
fi
printf 'this is not a PBF file\n' >"$work/broken.osm.pbf"
if "$SRC/scripts/streetgen-import" -m broken_file "$work/broken.osm.pbf" 2>"$work/broken.err"; then
  echo "FAIL: streetgen-import loaded a broken file" >&2; status=1
elif ! grep -q 'streetgen-osm-stage: .*broken.osm.pbf' "$work/broken.err"; then
  echo "FAIL: the error of a broken file does not name it: $(cat "$work/broken.err")" >&2; status=1
elif [ "$(psql -X -At -c "SELECT count(*) FROM streetgen.model WHERE name = 'broken_file'")" != 0 ]; then
  echo "FAIL: a broken file left a model behind" >&2; status=1
else
  echo "ok: a broken file fails with its name and leaves no model"
fi
# The peers' bench prepares each input as OSM XML in its work folder, an .osm input by a link:
# a later run of another format into the same folder once wrote its conversion through that
# link, over the .osm input (two files of the shared data overwritten). Whatever ran before in
# the folder, an input stays as it was. (PEERS empty: only the preparation runs.)
cp "$osm_dir/bautzen.osm" "$work/peers-input.osm"
PEERS="" bash "$SRC/bench/peers/run-peers.sh" "$work/peers-input.osm" "$work/peers" >/dev/null || status=1
PEERS="" bash "$SRC/bench/peers/run-peers.sh" "$osm_dir/paris-11e.osm.pbf" "$work/peers" >/dev/null || status=1
if ! cmp -s "$osm_dir/bautzen.osm" "$work/peers-input.osm"; then
  echo "FAIL: run-peers.sh wrote over an earlier run's .osm input" >&2; status=1
elif [ -L "$work/peers/work/input.osm" ] || ! grep -q '<osm' "$work/peers/work/input.osm"; then
  echo "FAIL: run-peers.sh did not convert the .pbf input to OSM XML in its own file" >&2; status=1
else
  echo "ok: run-peers.sh leaves its inputs as they were"
fi
pg_prove -d "$db" "$SRC/tests/import/check-import.sql" "$SRC/tests/import/check-surfaces.sql" \
  "$SRC/tests/import/check-refresh.sql" || status=$?
psql -X -c "SELECT model, kind, highway_ways, loaded, not_driveable, degenerate, seconds FROM import_fact ORDER BY model"
assert_no_crash_since "$mark" || status=1
exit $status
