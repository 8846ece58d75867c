#!/usr/bin/env bash
# Installs the Debian dependencies, builds streetgen in build/ and installs the extension into
# the system's PostgreSQL 15 (needs root, or sudo). Shared by demo.sh, test.sh and the Dockerfile.
#   STREETGEN_BUILD_DIR   build folder (default: <repo>/build)
#   STREETGEN_BUILD_TESTS ON/OFF (default ON)
#   STREETGEN_SHARED_DATA the real data folder the tests read (default: <repo>/../shared/data)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${STREETGEN_BUILD_DIR:-$repo/build}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

bash "$repo/scripts/install-deps.sh"
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSTREETGEN_BUILD_TESTS="${STREETGEN_BUILD_TESTS:-ON}" \
  ${STREETGEN_SHARED_DATA:+-DSTREETGEN_SHARED_DATA="$STREETGEN_SHARED_DATA"} >/dev/null
cmake --build "$build" -j"$(nproc)"
$SUDO cmake --install "$build" >/dev/null
echo "build: streetgen installed into $(pg_config --pkglibdir) and $(pg_config --sharedir)/extension"
