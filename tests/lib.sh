# Shared by the tests/run-*.sh layers (sourced). CTest sets PGHOST, PGPORT, PGUSER and the
# STREETGEN_* folders; see tests/CMakeLists.txt.
set -euo pipefail
: "${PGHOST:?run through ctest (or set PGHOST/PGPORT/PGUSER)}"
export PGOPTIONS="${PGOPTIONS:-} -c client_min_messages=warning"
SRC="${STREETGEN_SOURCE_DIR:?}"
BIN="${STREETGEN_BINARY_DIR:?}"
# streetgen-import reads OSM files with this build's reader (not an older one on PATH).
export STREETGEN_OSM_STAGE="$BIN/streetgen-osm-stage"

# A fresh database with streetgen (and the given extra extensions) installed.
fresh_db() {
  local db=$1; shift
  dropdb --if-exists "$db"
  createdb "$db"
  local ext
  for ext in "$@"; do psql -X -q -v ON_ERROR_STOP=1 -d "$db" -c "CREATE EXTENSION $ext CASCADE"; done
}

# Fails if the server log shows a backend crash since the mark given by log_mark.
log_mark() { wc -c <"$PGHOST/server.log"; }
assert_no_crash_since() {
  local mark=$1
  if tail -c +"$((mark + 1))" "$PGHOST/server.log" | grep -E "terminated by signal|PANIC|server process .* exited"; then
    echo "FAIL: the server log shows a crashed backend" >&2
    return 1
  fi
}
