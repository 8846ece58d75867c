#!/usr/bin/env bash
# Fetches the demo road network (central Gothenburg, 20,227 OSM ways as GeoJSON; © OpenStreetMap
# contributors, ODbL) from the npm registry: package geojson-path-finder@2.1.0 (ISC), file
# test/large-network.json. Prints the path of the file; downloads once into the cache folder.
set -euo pipefail
cache="${STREETGEN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/streetgen}"
file="$cache/geojson-path-finder-2.1.0/package/test/large-network.json"
if [ ! -s "$file" ]; then
  mkdir -p "$cache/geojson-path-finder-2.1.0"
  (cd "$cache/geojson-path-finder-2.1.0" && npm pack geojson-path-finder@2.1.0 >/dev/null 2>"$cache/npm.log" || { cat "$cache/npm.log" >&2; exit 1; } \
     && tar -xzf geojson-path-finder-2.1.0.tgz package/test/large-network.json)
fi
[ -s "$file" ] || { echo "fetch-demo-data: could not get $file from npm" >&2; exit 1; }
echo "$file"
