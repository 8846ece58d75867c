#!/usr/bin/env bash
# Every test layer in one CTest run: unit (GoogleTest), pgtap (pg_prove), isolation
# (pg_isolation_regress) and import (real OSM files of ../shared/data/osm and the GeoJSON demo
# network), against a throwaway cluster that CTest starts and removes. Ends with CTest's summary.
#   STREETGEN_SHARED_DATA  the real data folder (default: <repo>/../shared/data)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${STREETGEN_BUILD_DIR:-$repo/build}"
shared="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
[ -d "$shared/osm" ] || { echo "test.sh: no real data in $shared (clone beside the shared folder, or set STREETGEN_SHARED_DATA)" >&2; exit 1; }

STREETGEN_BUILD_TESTS=ON STREETGEN_SHARED_DATA="$(cd "$shared" && pwd)" bash "$repo/scripts/build.sh"
cd "$build"
ctest --output-on-failure -j2
