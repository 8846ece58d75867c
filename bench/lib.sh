# Shared by the bench scripts: `bench_cluster PORT [nobuild]` builds and installs streetgen into
# build-bench/ (unless told not to, or STREETGEN_BENCH_NO_BUILD=1), starts a throwaway cluster on
# PORT, removes it on exit, and leaves PG* set to its database "bench" with streetgen installed.
# Needs $repo (the checkout).
bench_cluster() {
  local port=$1 build=${2:-build}
  cluster=/tmp/streetgen-bench-$port
  if [ "$build" = build ] && [ "${STREETGEN_BENCH_NO_BUILD:-0}" != 1 ]; then
    STREETGEN_BUILD_TESTS=OFF STREETGEN_BUILD_DIR="$repo/build-bench" bash "$repo/scripts/build.sh" >/dev/null
  fi
  bash "$repo/scripts/pgcluster.sh" destroy "$cluster" >/dev/null 2>&1 || true
  bash "$repo/scripts/pgcluster.sh" start "$cluster" "$port" --fast >/dev/null
  trap 'bash "$repo/scripts/pgcluster.sh" destroy "$cluster" >/dev/null 2>&1 || true' EXIT
  export PGHOST="$cluster" PGPORT="$port" PGUSER=postgres PGDATABASE=bench
  export PGOPTIONS="-c client_min_messages=warning"
  createdb bench
  psql -X -q -c "CREATE EXTENSION streetgen CASCADE"
}
