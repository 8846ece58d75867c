#!/usr/bin/env bash
# export-surfaces.sh MODEL OUTDIR: the model's sections (roads) and intersections (junctions) as
# WGS 84 GeoJSON, the format of bench/peers' fidelity and junction-match scripts.
set -euo pipefail
model=$1 out=$2
mkdir -p "$out"
pg="PG:dbname=${PGDATABASE}"
ogr2ogr -f GeoJSON -t_srs EPSG:4326 "$out/streetgen-roads.geojson" "$pg" \
  -sql "SELECT axis_id, part, status, geom FROM $model.section WHERE geom IS NOT NULL" -overwrite
ogr2ogr -f GeoJSON -t_srs EPSG:4326 "$out/streetgen-junctions.geojson" "$pg" \
  -sql "SELECT node_id, status, geom FROM $model.intersection" -overwrite
