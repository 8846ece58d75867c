#!/usr/bin/env bash
# pgTAP layer: every file of tests/pgtap runs in its own transaction, rolled back.
source "$(dirname "$0")/lib.sh"
mark=$(log_mark)
# The growth tests read real example patches server-side (pg_read_file; the tests run as superuser).
export PGOPTIONS="$PGOPTIONS -c streetgen_test.shared_data=${STREETGEN_SHARED_DATA:?}"
fresh_db streetgen_pgtap pgtap streetgen
psql -X -q -v ON_ERROR_STOP=1 -d streetgen_pgtap -f "$SRC"/tests/pgtap/lib/helpers.sql
status=0
pg_prove -d streetgen_pgtap --ext .sql "$SRC"/tests/pgtap/*.sql || status=$?
assert_no_crash_since "$mark" || status=1
exit $status
