#!/usr/bin/env bash
# Import layer: every OSM file of ../shared/data/osm (all four formats) through osm2pgsql and the
# shipped flex style, and the GeoJSON demo network (Gothenburg, npm geojson-path-finder@2.1.0)
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
