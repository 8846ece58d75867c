#!/usr/bin/env bash
# Installs everything streetgen needs to build, run and test on Debian 12 (bookworm).
# Idempotent: packages already present are skipped by apt. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git ca-certificates
  postgresql-15 postgresql-server-dev-15 postgresql-15-postgis-3 postgresql-15-pgtap libtap-parser-sourcehandler-pgtap-perl
  libgeos-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libeigen3-dev zlib1g-dev
  libgtest-dev valgrind
  libosmium2-dev osm2pgsql osmium-tool gdal-bin time
  python3 python3-psycopg python3-qgis
  python3-osmnx python3-scipy python3-skimage
  python3-torch python3-gdal
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# npm may come from a non-Debian nodejs (e.g. NodeSource) that conflicts with Debian's npm package.
command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
