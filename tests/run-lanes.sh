#!/usr/bin/env bash
# Lanes layer (issue 5, lanes and markings) on real data: every osm2streets case of
# ../shared/data/osm2streets (the hard junctions: dual carriageways, slip lanes, roundabouts, ...)
# and three OSM extracts with many lane tags (Reno: lanes on 62 % of the ways, turn lanes; Paris
# 11e: bus and contraflow cycle lanes; Bautzen: an old town), imported with the shipped importer;
# tests/lanes/check-lanes.sql checks the acceptance measures on each and the invariant of the
# triggers over random lane edits.
source "$(dirname "$0")/lib.sh"
: "${STREETGEN_SHARED_DATA:?}"
cases_dir="$STREETGEN_SHARED_DATA/osm2streets"
osm_dir="$STREETGEN_SHARED_DATA/osm"
[ -d "$cases_dir" ] && [ -d "$osm_dir" ] || { echo "FAIL: no shared data in $STREETGEN_SHARED_DATA" >&2; exit 1; }
mark=$(log_mark)
db=streetgen_lanes
fresh_db "$db" pgtap streetgen
export PGDATABASE=$db
psql -X -q -v ON_ERROR_STOP=1 -c "CREATE TABLE lane_dataset (model text PRIMARY KEY, kind text, file text)"

load() {  # model kind file
  "$SRC/scripts/streetgen-import" -m "$1" "$3"
  psql -X -q -v ON_ERROR_STOP=1 -c "INSERT INTO lane_dataset VALUES ('$1', '$2', '$(basename "$3")')"
}
for d in "$cases_dir"/*/; do
  c=$(basename "$d" | tr '[:upper:]' '[:lower:]' | sed 's/[^a-z0-9_]/_/g')
  f=$(ls "$d"/input.osm* 2>/dev/null | head -1)
  [ -n "$f" ] || continue
  load "c_$c" osm2streets "$f"
done
for f in reno_east3.osm paris-11e.osm.pbf bautzen.osm; do
  m=$(echo "${f%%.*}" | tr '-' '_')
  load "$m" osm "$osm_dir/$f"
done

status=0
pg_prove -d "$db" "$SRC/tests/lanes/check-lanes.sql" || status=$?
psql -X -c "SELECT d.model, q.sections, q.lanes, q.markings, q.invalid_geometries AS invalid,
                   round((100 * q.max_coverage_difference)::numeric, 6) AS max_coverage_diff_pct,
                   q.sections_over_tolerance AS over_05pct, round(q.lane_overlap_area::numeric, 6) AS lane_overlap_m2,
                   round(q.outside_section_area::numeric, 6) AS outside_own_section_m2,
                   round(q.foreign_overlap_area::numeric, 6) AS into_other_axes_m2
              FROM lane_dataset d, streetgen.lane_quality(d.model) q ORDER BY d.kind DESC, d.model"
assert_no_crash_since "$mark" || status=1
exit $status
