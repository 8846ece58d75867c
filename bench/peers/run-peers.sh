#!/usr/bin/env bash
# Run both peers (SUMO netconvert, osm2streets-js) on one OSM file.
# usage: run-peers.sh FILE OUTDIR        FILE: .osm, .osm.gz, .osm.bz2 or .pbf
# Writes OUTDIR/{netconvert,osm2streets}-{roads,junctions}.geojson (WGS84),
# OUTDIR/osm2streets-roads-full.geojson (osm2streets road polygons with sidewalks)
# and OUTDIR/work/ (XML input, net.xml, raw osm2streets exports, logs).
# Prints one line per peer:
#   peer=<name> file=<base> wall_s=<s> peak_rss_kb=<kb> private_peak_kb=<kb> roads=<n> junctions=<n> convert_s=<s> convert_rss_kb=<kb> prep_s=<s> status=<ok|fail>
# wall_s/peak_rss_kb: the peer process alone (/usr/bin/time). private_peak_kb: its peak without
# mapped files (libraries), the measure bench/surfaces uses for the backend (private_peak.c).
# convert_s: turning its output into the two GeoJSON files (Python). prep_s: osmium conversion of FILE to OSM XML (shared by both).
# Env: PEERS="netconvert osm2streets" to choose (PEERS= runs none); NETCONVERT_EXTRA="..." extra netconvert options.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
[ $# -eq 2 ] || { echo "usage: $0 FILE OUTDIR" >&2; exit 2; }
in="$1"; out="$2"
[ -r "$in" ] || { echo "run-peers: cannot read $in" >&2; exit 2; }
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
PY=/usr/bin/python3
TIME=/usr/bin/time
[ -x "$TIME" ] || { echo "run-peers: $TIME missing: run install-peers.sh" >&2; exit 2; }
mkdir -p "$out/work"
out="$(cd "$out" && pwd)"; w="$out/work"
base="$(basename "$in")"
case "$base" in input.*) base="$(basename "$(dirname "$in")")/$base" ;; esac   # osm2streets cases
PEERS="${PEERS-netconvert osm2streets}"   # (set and empty: no peer, only the XML preparation)

# seconds with 2 decimals and peak RSS of the last timed command
timed() { # timed LABEL cmd... ; sets T_S T_KB RC
  local f="$w/$1.time"; shift
  "$TIME" -f "%e %M" -o "$f" "$@"; RC=$?
  read -r T_S T_KB < <(tail -n 1 "$f")
  case "$T_S" in ''|*[!0-9.]*) T_S=NA; T_KB=NA ;; esac
}

# 1. input as plain OSM XML (both peers read the same file)
xml="$w/input.osm"
# (an .osm input is linked, not copied: a later run into the same OUTDIR wrote its conversion
# through that link, over the earlier run's input file, until the old link was removed first)
rm -f "$xml"
case "$in" in
  *.osm) ln -sf "$(cd "$(dirname "$in")" && pwd)/$(basename "$in")" "$xml"; PREP_S=0 ;;
  *) timed prep osmium cat --overwrite -o "$xml" -f osm "$in" 2>"$w/osmium.log"
     [ "$RC" -eq 0 ] || { echo "run-peers: osmium failed, see $w/osmium.log" >&2; exit 1; }
     PREP_S=$T_S ;;
esac

# the peers' private peak memory: an exit hook preloaded into the peer only, not into time(1)
# (private_peak_kb=NA without a C compiler)
PEAK_ENV=(env)
if cc -shared -fPIC -O2 -o "$w/private_peak.so" "$here/private_peak.c" 2>/dev/null; then
  PEAK_ENV=(env LD_PRELOAD="$w/private_peak.so")
fi
private_kb() {  # the largest value the hook wrote to FILE (a peer's child processes write too), or NA
  sort -n "$1" 2>/dev/null | tail -n 1 | grep -E '^[0-9]+$' || echo NA
}

count() { "$PY" -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["features"]))' "$1" 2>/dev/null || echo 0; }

for peer in $PEERS; do
  case "$peer" in
  netconvert)
    # OSM import as in SUMO's docs: car roads only, simplified geometry, guessed roundabouts/ramps,
    # joined junction clusters, curb arcs of radius 4 m drawn with 5 intermediate points.
    rm -f "$w/netconvert.private"
    timed netconvert "${PEAK_ENV[@]}" PRIVATE_PEAK_OUT="$w/netconvert.private" netconvert --osm-files "$xml" \
      --keep-edges.by-vclass passenger \
      --geometry.remove --roundabouts.guess --ramps.guess \
      --junctions.join --junctions.corner-detail 5 --default.junctions.radius 4 \
      --output.street-names \
      ${NETCONVERT_EXTRA:-} \
      -o "$w/net.xml" >"$w/netconvert.log" 2>&1
    P_RC=$RC; P_S=$T_S; P_KB=$T_KB
    if [ "$P_RC" -eq 0 ]; then
      timed netconvert-convert "$PY" "$here/net2geojson.py" "$w/net.xml" \
        "$out/netconvert-roads.geojson" "$out/netconvert-junctions.geojson" >"$w/net2geojson.log" 2>&1
    else RC=1; T_S=NA; T_KB=NA; fi
    ;;
  osm2streets)
    rm -f "$w/osm2streets.private"
    timed osm2streets "${PEAK_ENV[@]}" PRIVATE_PEAK_OUT="$w/osm2streets.private" node --experimental-detect-module --no-warnings --max-old-space-size=8192 \
      "$here/osm2streets-peer.mjs" "$xml" "$w/osm2streets" >"$w/osm2streets.log" 2>&1
    P_RC=$RC; P_S=$T_S; P_KB=$T_KB
    if [ "$P_RC" -eq 0 ]; then
      timed osm2streets-convert "$PY" "$here/o2s2geojson.py" "$w/osm2streets" \
        "$out/osm2streets-roads.geojson" "$out/osm2streets-junctions.geojson" \
        "$out/osm2streets-roads-full.geojson" >"$w/o2s2geojson.log" 2>&1
    else RC=1; T_S=NA; T_KB=NA; fi
    ;;
  *) echo "run-peers: unknown peer $peer" >&2; continue ;;
  esac
  if [ "$P_RC" -eq 0 ] && [ "$RC" -eq 0 ]; then
    status=ok; r=$(count "$out/$peer-roads.geojson"); j=$(count "$out/$peer-junctions.geojson")
  else
    status=fail; r=0; j=0
    echo "run-peers: $peer failed (peer rc=$P_RC), see $w/$peer.log" >&2
  fi
  echo "peer=$peer file=$base wall_s=$P_S peak_rss_kb=$P_KB private_peak_kb=$(private_kb "$w/$peer.private") roads=$r junctions=$j convert_s=$T_S convert_rss_kb=$T_KB prep_s=$PREP_S status=$status"
done
