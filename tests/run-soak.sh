#!/usr/bin/env bash
# Soak layer: a bounded pgbench run of random edits by 8 clients on a real city (Liechtenstein,
# 2,287 axes), then tests/soak/check.sql: no committed edit lost, the outputs equal a full
# recompute, every output geometry valid. Fails as well if a client aborted on an error pgbench
# cannot retry or if the server log shows a crashed backend. tests/soak/replay.sql replays a
# failed soak's log in one session to name the edit that broke the invariant.
#   SOAK_EDITS    edits per client (default 20: 160 edits, every one of which must commit)
#   SOAK_SECONDS  run for this long instead (pgbench -T; at least one edit per 6 s must commit)
#   SOAK_CLIENTS  concurrent editors (default 8; 1 tells a concurrency bug from a scope bug)
source "$(dirname "$0")/lib.sh"
: "${STREETGEN_SHARED_DATA:?}"
pgbench="${PG_BINDIR:-/usr/lib/postgresql/15/bin}/pgbench"
clients=${SOAK_CLIENTS:-8}
# A number of edits, not a duration, by default: an edit of Liechtenstein with its sidewalks and
# blocks takes 0.4 s of serialised work on an idle machine and 0.8 s on a busy one, so a 60 s
# run proved anything from 79 to 153 edits. Every transaction must commit (pgbench retries
# 40001 and 40P01).
if [ -n "${SOAK_SECONDS:-}" ]; then
  seconds=$SOAK_SECONDS
  run_for=(-T "$seconds")
  min_edits=$(( seconds / 6 > 10 ? seconds / 6 : 10 ))
  what="$seconds s"
else
  per_client=${SOAK_EDITS:-20}
  run_for=(-t "$per_client")
  # Nine in ten transactions at least: a transaction can commit without an edit when the axis it
  # picked was deleted by another client first (its UPDATE then finds no row; a CI run logged 159
  # of 160), and the invariant checks below count what was logged, not what was attempted.
  min_edits=$(( clients * per_client * 9 / 10 ))
  what="$per_client edits each"
fi
model=liechtenstein
mark=$(log_mark)
db=streetgen_soak
fresh_db "$db" pgtap streetgen
export PGDATABASE=$db
work="$BIN/soak"
rm -rf "$work"; mkdir -p "$work"

"$SRC/scripts/streetgen-import" -m "$model" "$STREETGEN_SHARED_DATA/osm/liechtenstein.osm.pbf"
psql -X -q -v ON_ERROR_STOP=1 -v model="$model" -f "$SRC/tests/soak/setup.sql"

# READ COMMITTED, as the README asks of editors: edits of one model queue on its refresh_state
# row. No lock_timeout: pgbench retries only 40001 and 40P01 (--max-tries), and a 55P03 would
# abort the client, so waiting in the queue is what we soak. statement_timeout only turns a hang
# (a wait the deadlock detector misses) into a failed run instead of a stuck one.
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
status=0
PGOPTIONS="$PGOPTIONS -c search_path=$model,public -c statement_timeout=120s" \
  "$pgbench" -n -c "$clients" -j "$(( clients < 2 ? clients : 2 ))" "${run_for[@]}" -P 10 --max-tries=10 --failures-detailed \
  -f "$SRC/tests/soak/move-axis.sql@25" -f "$SRC/tests/soak/move-vertex.sql@20" \
  -f "$SRC/tests/soak/width.sql@15" -f "$SRC/tests/soak/speed.sql@15" \
  -f "$SRC/tests/soak/insert.sql@15" -f "$SRC/tests/soak/delete.sql@10" \
  >"$work/pgbench.out" 2>"$work/pgbench.err" || status=$?
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
cat "$work/pgbench.out" "$work/pgbench.err"
if [ $status -ne 0 ]; then echo "FAIL: pgbench exited with $status (a client aborted on an error it cannot retry)" >&2; fi
# A backend can still be finishing (and committing) a statement its client gave up on: the checks
# must see the final state (statement_timeout bounds the wait).
for _ in $(seq 150); do
  [ "$(psql -X -At -c "SELECT count(*) FROM pg_stat_activity WHERE datname = current_database()
                          AND application_name = 'pgbench'")" = 0 ] && break
  sleep 1
done

if ! pg_prove -d "$db" -S model="$model" -S min_edits="$min_edits" "$SRC/tests/soak/check.sql"; then
  status=1
  # The edits in commit order, so that a failure seen only in a CI log (its cluster is gone) can
  # be replayed: tests/soak/replay.sql says how to load them.
  psql -X -q -c "\\copy (SELECT * FROM soak_log ORDER BY refresh, seq) TO '$work/soak_log.csv' CSV"
  echo "soak_log:begin ($(wc -l <"$work/soak_log.csv") edits, commit order, CSV)"
  cat "$work/soak_log.csv"
  echo "soak_log:end"
fi

# What the clients were told, by message (the retried deadlocks and serialization failures among them).
tail -c +"$((mark + 1))" "$PGHOST/server.log" | grep -o 'ERROR: .*' | sed 's/[0-9]\{3,\}/N/g' | sort | uniq -c | sort -rn || true

# Local refreshes whose overlap check found a miss and refreshed again (sql/65-refresh.sql):
# the outputs are right all the same, but each one is a case the neighbourhood search missed.
repairs=$(tail -c +"$((mark + 1))" "$PGHOST/server.log" | grep -c 'wrote overlapping outputs' || true)

pgbench_stat() { sed -n "s/^$1[ =:]*\([0-9.]*\).*/\1/p" "$work/pgbench.out"; }
edits=$(psql -X -At -c "SELECT sum(n) || ' (' || string_agg(kind || ' ' || n, ', ') || ')'
                          FROM (SELECT kind, count(*) AS n FROM soak_log GROUP BY kind ORDER BY kind) k")
echo "soak: $clients clients, $what, committed edits $edits of $(pgbench_stat 'number of transactions actually processed') transactions," \
  "tps $(pgbench_stat tps), latency avg $(pgbench_stat 'latency average') ms, failed $(pgbench_stat 'number of failed transactions')" \
  "(serialization $(pgbench_stat 'number of serialization failures'), deadlock $(pgbench_stat 'number of deadlock failures')), retried" \
  "$(pgbench_stat 'number of transactions retried') (retries $(pgbench_stat 'total number of retries')); load average $load_before before," \
  "$load_after after; refreshes repaired by the overlap check $repairs; whole layer ${SECONDS} s"
assert_no_crash_since "$mark" || status=1
exit $status
