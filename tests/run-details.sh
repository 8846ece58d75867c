#!/usr/bin/env bash
# Details layer (issue 5: sidewalks, crossings, blocks) on real data: every osm2streets case of
# ../shared/data/osm2streets and three OSM extracts (Paris 11e: a dense city with sidewalk tags;
# Bautzen: an old town; Krems: a small town with its outskirts), imported with the shipped
# importer; tests/details/check-details.sql checks the acceptance measures on each and the
# invariant of the triggers over random edits of sidewalks, widths and geometries.
source "$(dirname "$0")/lib.sh"
: "${STREETGEN_SHARED_DATA:?}"
cases_dir="$STREETGEN_SHARED_DATA/osm2streets"
osm_dir="$STREETGEN_SHARED_DATA/osm"
[ -d "$cases_dir" ] && [ -d "$osm_dir" ] || { echo "FAIL: no shared data in $STREETGEN_SHARED_DATA" >&2; exit 1; }
mark=$(log_mark)
db=streetgen_details
fresh_db "$db" pgtap streetgen
export PGDATABASE=$db
psql -X -q -v ON_ERROR_STOP=1 -c "CREATE TABLE detail_dataset (model text PRIMARY KEY, kind text, file text)"

load() {  # model kind file
  "$SRC/scripts/streetgen-import" -m "$1" "$3"
  psql -X -q -v ON_ERROR_STOP=1 -c "INSERT INTO detail_dataset VALUES ('$1', '$2', '$(basename "$3")')"
}
for d in "$cases_dir"/*/; do
  c=$(basename "$d" | tr '[:upper:]' '[:lower:]' | sed 's/[^a-z0-9_]/_/g')
  f=$(ls "$d"/input.osm* 2>/dev/null | head -1)
  [ -n "$f" ] || continue
  load "c_$c" osm2streets "$f"
done
for f in paris-11e.osm.pbf bautzen.osm krems.osm.gz; do
  m=$(echo "${f%%.*}" | tr '-' '_')
  load "$m" osm "$osm_dir/$f"
done

status=0
pg_prove -d "$db" "$SRC/tests/details/check-details.sql" || status=$?
psql -X -c "SELECT d.model, q.sidewalks, q.crossings, q.blocks, q.invalid_geometries AS invalid,
                   round(q.sidewalk_area::numeric) AS sidewalk_m2,
                   round((100 * q.sidewalk_roadway_overlap_area / greatest(q.sidewalk_area, 1e-9))::numeric, 6) AS on_roadway_pct,
                   round((100 * q.sidewalk_overlap_area / greatest(q.sidewalk_area, 1e-9))::numeric, 6) AS sidewalk_overlap_pct,
                   round(q.crossing_outside_area::numeric, 6) AS crossing_out_m2,
                   round(q.face_area::numeric) AS face_m2,
                   round((100 * q.overlap_area / greatest(q.face_area, 1e-9))::numeric, 6) AS tiling_overlap_pct,
                   round((100 * q.roadway_overlap_area / greatest(q.face_area, 1e-9))::numeric, 6) AS roadway_overlap_pct,
                   round((100 * q.gap_area / greatest(q.face_area, 1e-9))::numeric, 6) AS tiling_gap_pct
              FROM detail_dataset d, streetgen.detail_quality(d.model) q ORDER BY d.kind DESC, d.model"
# The engine hands the heap's free pages back to the system after a city's run, where the blocks'
# peak comes next, and not after an edit's local recompute, where it only cost a madvise per free
# run of pages (src/pg/srf.hpp, kTrimMinAxes and kTrimMinFaces): the engine says which at DEBUG1.
heap_says() {  # statement: the surfaces' and the blocks' verdicts, one line
  psql -X -q -v ON_ERROR_STOP=1 -c "SET client_min_messages = debug1" -c "BEGIN" -c "$1" -c "ROLLBACK" 2>&1 |
    grep -o 'surfaces of [0-9]* axes, heap [a-z]*\|blocks of [0-9]* faces.*heap [a-z]* before' |
    sed 's/^\(blocks of [0-9]* faces\).*\(heap [a-z]*\) before$/\1, \2/' | paste -sd ';' || true
}
said=$(heap_says "SELECT count(*) FROM streetgen.generate('paris_11e')")
echo "whole model: $said"
[[ "$said" =~ ^surfaces\ of\ [0-9]+\ axes,\ heap\ trimmed\;blocks\ of\ [0-9]+\ faces,\ heap\ trimmed$ ]] ||
  { echo "FAIL: a whole city's run did not trim the heap" >&2; status=1; }
said=$(heap_says "UPDATE paris_11e.axis SET geom = ST_Translate(geom, 0.5, 0) WHERE id = (SELECT min(id) FROM paris_11e.axis)")
echo "an edit: $said"
[[ "$said" =~ ^surfaces\ of\ [0-9]+\ axes,\ heap\ kept\;blocks\ of\ [0-9]+\ faces,\ heap\ kept$ ]] ||
  { echo "FAIL: an edit's local recompute trimmed the heap (or said nothing)" >&2; status=1; }
assert_no_crash_since "$mark" || status=1
exit $status
