#!/usr/bin/env bash
# Isolation layer: pg_isolation_regress runs every spec of tests/isolation/specs against the
# throwaway cluster, in a database with streetgen installed.
source "$(dirname "$0")/lib.sh"
: "${PG_ISOLATION_REGRESS:?}" "${PG_BINDIR:?}"
mark=$(log_mark)
fresh_db isolation_streetgen streetgen
specs=()
for spec in "$SRC"/tests/isolation/specs/*.spec; do specs+=("$(basename "$spec" .spec)"); done
mkdir -p "$BIN/isolation"
status=0
"$PG_ISOLATION_REGRESS" --use-existing --host="$PGHOST" --port="$PGPORT" --user="$PGUSER" \
  --dbname=isolation_streetgen --inputdir="$SRC/tests/isolation" --outputdir="$BIN/isolation" \
  --bindir="$PG_BINDIR" "${specs[@]}" || status=$?
if [ $status -ne 0 ] && [ -f "$BIN/isolation/regression.diffs" ]; then cat "$BIN/isolation/regression.diffs"; fi
assert_no_crash_since "$mark" || status=1
exit $status
