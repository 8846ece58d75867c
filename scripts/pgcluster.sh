#!/usr/bin/env bash
# A throwaway PostgreSQL 15 cluster on a unix socket and loopback, owned by a non-root user
# (initdb refuses root: when run as root, the cluster belongs to the 'postgres' system user).
#
#   pgcluster.sh start DIR PORT [--fast]   initdb if DIR is new, then start; --fast: fsync off (tests)
#   pgcluster.sh stop DIR [PORT]           stop (the data stays until DIR is removed)
#   pgcluster.sh destroy DIR [PORT]        stop and remove DIR
# With PORT, start, stop and destroy refuse a cluster in DIR that was made for another port: a
# build folder whose cached cluster folder was another build's once destroyed that build's
# cluster under its running tests.
#   pgcluster.sh env DIR PORT              print the PG* variables for clients
#
# Authentication is 'trust' for local socket and loopback connections: it is a throwaway
# cluster for one machine. Superuser: postgres.
set -euo pipefail

pg_bindir() {
  local d
  d=$(pg_config --bindir 2>/dev/null || true)
  if [ -x "$d/initdb" ]; then echo "$d"; else echo /usr/lib/postgresql/15/bin; fi
}
BIN=$(pg_bindir)

as_owner() {
  if [ "$(id -u)" -eq 0 ]; then runuser -u postgres -- "$@"; else "$@"; fi
}

cmd=${1:-}
dir=${2:-}
[ -n "$cmd" ] && [ -n "$dir" ] || { sed -n '2,15p' "$0"; exit 2; }

# Refuses (exit 1) when DIR holds a cluster configured for a port other than $1 (if given).
check_port() {
  local want=${1:-} have
  [ -n "$want" ] && [ -f "$dir/data/postgresql.conf" ] || return 0
  have=$(sed -n 's/^port = \([0-9]*\).*/\1/p' "$dir/data/postgresql.conf" | tail -1)
  if [ -n "$have" ] && [ "$have" != "$want" ]; then
    echo "pgcluster: $dir holds the cluster of port $have, not $want: left alone" >&2
    exit 1
  fi
}

case "$cmd" in
  start)
    port=${3:?port required}
    fast=${4:-}
    check_port "$port"
    if [ ! -f "$dir/data/PG_VERSION" ]; then
      mkdir -p "$dir"
      if [ "$(id -u)" -eq 0 ]; then chown postgres: "$dir"; fi
      as_owner "$BIN/initdb" --pgdata="$dir/data" --username=postgres --auth=trust --encoding=UTF8 \
        --locale=C.UTF-8 >"$dir/initdb.log" 2>&1 || { cat "$dir/initdb.log"; exit 1; }
      {
        echo "listen_addresses = 'localhost'"
        echo "port = $port"
        echo "unix_socket_directories = '$dir'"
        echo "max_connections = 50"
        echo "max_locks_per_transaction = 256"
        echo "log_min_messages = warning"
        echo "log_line_prefix = '%m [%p] %q%a '"
        if [ "$fast" = "--fast" ]; then
          echo "fsync = off"
          echo "synchronous_commit = off"
          echo "full_page_writes = off"
        fi
      } | as_owner tee -a "$dir/data/postgresql.conf" >/dev/null
    fi
    if as_owner "$BIN/pg_ctl" --pgdata="$dir/data" status >/dev/null 2>&1; then
      echo "pgcluster: already running in $dir"
    else
      as_owner "$BIN/pg_ctl" --pgdata="$dir/data" --log="$dir/server.log" --wait --timeout=60 start >/dev/null \
        || { tail -20 "$dir/server.log"; exit 1; }
      echo "pgcluster: started in $dir (socket $dir, port $port)"
    fi
    ;;
  stop)
    check_port "${3:-}"
    if [ -f "$dir/data/PG_VERSION" ] && as_owner "$BIN/pg_ctl" --pgdata="$dir/data" status >/dev/null 2>&1; then
      as_owner "$BIN/pg_ctl" --pgdata="$dir/data" --mode=fast --wait stop >/dev/null
      echo "pgcluster: stopped $dir"
    fi
    ;;
  destroy)
    "$0" stop "$dir" "${3:-}"
    rm -rf "$dir"
    ;;
  env)
    port=${3:?port required}
    echo "export PGHOST='$dir' PGPORT='$port' PGUSER=postgres"
    ;;
  *)
    sed -n '2,15p' "$0"; exit 2 ;;
esac
