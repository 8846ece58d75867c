#!/usr/bin/env bash
# Run the peers on the benchmark files, the Neukölln fidelity and the junction match on
# all osm2streets cases. usage: bench-all.sh OUTDIR [DATA_DIR]   (DATA_DIR default ../../../shared/data)
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:?usage: bench-all.sh OUTDIR [DATA_DIR]}"
data="${2:-$here/../../../shared/data}"
mkdir -p "$out"
for f in "$data/osm2streets/neukolln/input.osm" "$data/osm/liechtenstein.osm.pbf" \
         "$data/osm/munich.osm.pbf" "$data/osm/reisterstown.osm.pbf"; do
  n="$(basename "$f")"; n="${n%%.*}"; [ "$n" = input ] && n=neukolln
  "$here/run-peers.sh" "$f" "$out/$n"
done
for p in netconvert osm2streets; do
  echo "fidelity peer=$p $("$here/fidelity-neukoelln.py" "$out/neukolln/$p-roads.geojson" "$out/neukolln/$p-junctions.geojson")"
done
echo "fidelity peer=osm2streets-full $("$here/fidelity-neukoelln.py" "$out/neukolln/osm2streets-roads-full.geojson" "$out/neukolln/osm2streets-junctions.geojson")"
for d in "$data"/osm2streets/*/; do
  c="$(basename "$d")"; f="$(ls "$d"/input.osm* | head -1)"
  "$here/run-peers.sh" "$f" "$out/cases/$c" >"$out/cases-$c.txt" 2>&1
  for p in netconvert osm2streets; do
    [ -f "$out/cases/$c/$p-junctions.geojson" ] && echo "junctions peer=$p $("$here/junction-match.py" "$out/cases/$c/$p-junctions.geojson" "$d")"
  done
done
