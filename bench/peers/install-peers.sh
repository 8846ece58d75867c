#!/usr/bin/env bash
# Idempotent install of what bench/peers needs.
#   apt: sumo (netconvert), sumo-tools (netconvert's OSM type map, /usr/share/sumo/data: only
#        recommended by sumo, so --no-install-recommends skips it and netconvert quits), osmium-tool, time (/usr/bin/time), python3-pyproj, python3-shapely
#   npm: osm2streets-js pinned to 0.1.2 (package.json + package-lock.json) into bench/peers/node_modules
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"

pkgs=(sumo sumo-tools osmium-tool time python3-pyproj python3-shapely nodejs npm)
missing=()
for p in "${pkgs[@]}"; do
  # nodejs/npm may come from elsewhere (e.g. nodesource); only install if the command is absent
  case "$p" in
    nodejs) command -v node >/dev/null 2>&1 && continue ;;
    npm)    command -v npm  >/dev/null 2>&1 && continue ;;
  esac
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "install-peers: apt-get install ${missing[*]}" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

want="$(node -e 'console.log(require(process.argv[1]).dependencies["osm2streets-js"])' "$here/package.json")"
have=""
[ -f "$here/node_modules/osm2streets-js/package.json" ] && \
  have="$(node -e 'console.log(require(process.argv[1]).version)' "$here/node_modules/osm2streets-js/package.json")"
if [ "$have" != "$want" ]; then
  echo "install-peers: npm ci osm2streets-js@$want" >&2
  (cd "$here" && { [ -f package-lock.json ] && npm ci --no-audit --no-fund --loglevel=error || npm install --no-audit --no-fund --loglevel=error; })
fi

export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
echo "netconvert: $(netconvert --version 2>/dev/null | head -1)"
echo "osmium: $(osmium --version | head -1)"
echo "osm2streets-js: $(node -e 'console.log(require(process.argv[1]).version)' "$here/node_modules/osm2streets-js/package.json")"
echo "node: $(node --version)"
