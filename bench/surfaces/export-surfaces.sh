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
# EXCLUDE_DRIVEWAYS=1: without service=driveway|parking_aisle (ways on private plots, which the
# public street space of a cadastre leaves out; public service roads stay).
if [ "${EXCLUDE_DRIVEWAYS:-0}" = 1 ]; then
  keep="coalesce(a.tags->>'service', '') NOT IN ('driveway', 'parking_aisle')"
  roads="$roads AND $keep"
  junctions="$junctions WHERE EXISTS (SELECT 1 FROM $model.axis a WHERE a.id = ANY(i.axis_ids) AND $keep)"
fi
if [ "${EXCLUDE_SERVICE:-0}" = 1 ]; then
  roads="$roads AND a.road_class <> 'service'"
  junctions="$junctions WHERE EXISTS (SELECT 1 FROM $model.axis a WHERE a.id = ANY(i.axis_ids) AND a.road_class <> 'service')"
fi
# (GeoJSON cannot -overwrite an existing file: without the rm, a rerun would silently keep the old one)
rm -f "$out/streetgen-roads.geojson" "$out/streetgen-junctions.geojson"
ogr2ogr -f GeoJSON -t_srs EPSG:4326 "$out/streetgen-roads.geojson" "$pg" -sql "$roads"
ogr2ogr -f GeoJSON -t_srs EPSG:4326 "$out/streetgen-junctions.geojson" "$pg" -sql "$junctions"
