#!/usr/bin/env bash
# export-surfaces.sh MODEL OUTDIR: the model's sections (roads) and intersections (junctions) as
# WGS 84 GeoJSON, the format of bench/peers' fidelity and junction-match scripts.
# EXCLUDE_SERVICE=1: only axes that are not highway=service, and junctions of at least one such.
set -euo pipefail
model=$1 out=$2
mkdir -p "$out"
pg="PG:dbname=${PGDATABASE}"
roads="SELECT s.axis_id, s.part, s.status, s.geom FROM $model.section s JOIN $model.axis a ON a.id = s.axis_id WHERE s.geom IS NOT NULL"
junctions="SELECT i.node_id, i.status, i.geom FROM $model.intersection i"
if [ "${EXCLUDE_SERVICE:-0}" = 1 ]; then
  roads="$roads AND a.road_class <> 'service'"
  junctions="$junctions WHERE EXISTS (SELECT 1 FROM $model.axis a WHERE a.id = ANY(i.axis_ids) AND a.road_class <> 'service')"
fi
ogr2ogr -f GeoJSON -t_srs EPSG:4326 "$out/streetgen-roads.geojson" "$pg" -sql "$roads" -overwrite 2>/dev/null
ogr2ogr -f GeoJSON -t_srs EPSG:4326 "$out/streetgen-junctions.geojson" "$pg" -sql "$junctions" -overwrite 2>/dev/null
