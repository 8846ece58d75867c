#!/usr/bin/env bash
# QGIS layer: a real headless QGIS (PyQGIS, Debian's python3-qgis) edits a real city's axes
# through the PostGIS provider and commits; tests/qgis/edit_session.py then checks the surfaces,
# streetgen.outdated, what QGIS reads back, the NOTIFY, and the project qgis/make_project.py writes.
source "$(dirname "$0")/lib.sh"
: "${STREETGEN_SHARED_DATA:?}"
python=/usr/bin/python3  # the system python: PyQGIS is a Debian package, not on PyPI
"$python" -c 'import qgis.core, psycopg' 2>/dev/null \
  || { echo "FAIL: PyQGIS or psycopg missing (apt-get install python3-qgis python3-psycopg)" >&2; exit 1; }
mark=$(log_mark)
model=paris_11e
export PGDATABASE=streetgen_qgis
fresh_db "$PGDATABASE" streetgen
"$SRC/scripts/streetgen-import" -m "$model" "$STREETGEN_SHARED_DATA/osm/paris-11e.osm.pbf"

work="$BIN/qgis"
rm -rf "$work"; mkdir -p -m 700 "$work/runtime"
export QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR="$work/runtime"
status=0
if "$python" "$SRC/qgis/make_project.py" "dbname=$PGDATABASE host=$PGHOST port=$PGPORT user=$PGUSER" "$model" \
     "$work/$model.qgs"; then
  "$python" "$SRC/tests/qgis/edit_session.py" "$model" "$work/$model.qgs" || status=$?
else
  status=1
fi
assert_no_crash_since "$mark" || status=1
exit $status
