#!/usr/bin/env bash
# The issue's import goal, file by file: the whole `streetgen-import -c details=false` (wall
# seconds, the least of ROUNDS runs, each into a new model) against netconvert (NCRUNS runs of
# bench/peers/run-peers.sh, each in a folder of its own), and their ratio. Run it on a quiet
# machine: netconvert is two to three times faster without other load, streetgen less so, and
# ratios measured under load flatter streetgen. Prints the load average beside each file.
# The first row is a file of one street (two nodes, one way; made here): both programs' fixed
# cost, the floor under every file's time (FLOOR=0 leaves it out).
#
#   PGHOST=... PGPORT=... PGDATABASE=... [ROUNDS=3] [NCRUNS=3] bash bench/surfaces/import-ratio.sh FILE...
#
# The database must have streetgen installed; the model (ratio_bench) is dropped at the end.
# netconvert comes from bench/peers/install-peers.sh.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
[ $# -ge 1 ] || { sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
rounds=${ROUNDS:-3}
ncruns=${NCRUNS:-3}
model=ratio_bench
export PGOPTIONS="-c client_min_messages=warning"
tmp=$(mktemp -d)
drop_model() { psql -X -q -c "SELECT streetgen.drop_model('$model') FROM streetgen.model WHERE name = '$model'" >/dev/null; }
trap 'drop_model || true; rm -rf "$tmp"' EXIT

printf '%-26s %7s %10s %-20s %-12s %s\n' file axes import_s netconvert_s ratio load
files=("$@")
if [ "${FLOOR:-1}" = 1 ]; then
  cat >"$tmp/one-street.osm" <<'OSM'
<?xml version='1.0' encoding='UTF-8'?>
<osm version="0.6" generator="streetgen bench/surfaces/import-ratio.sh">
  <node id="1" lat="51.18" lon="14.42"/>
  <node id="2" lat="51.181" lon="14.42"/>
  <way id="1"><nd ref="1"/><nd ref="2"/><tag k="highway" v="residential"/></way>
</osm>
OSM
  files=("$tmp/one-street.osm" "${files[@]}")
fi
for file in "${files[@]}"; do
  best=""
  for _ in $(seq "$rounds"); do
    drop_model
    start=$(date +%s.%N)
    out=$(bash "$repo/scripts/streetgen-import" -m "$model" -c details=false "$file")
    seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.2f", e - s }')
    if [ -z "$best" ] || awk -v a="$seconds" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$seconds; fi
  done
  axes=$(echo "$out" | sed -n 's/.*: \([0-9]*\) axes loaded.*/\1/p')
  peers=()
  for k in $(seq "$ncruns"); do
    # (a folder per run: run-peers.sh links an .osm input into it)
    s=$(PEERS=netconvert bash "$repo/bench/peers/run-peers.sh" "$file" "$tmp/peers-$k" 2>/dev/null \
        | sed -n 's/^peer=netconvert .*wall_s=\([0-9.]*\).*status=ok$/\1/p')
    [ -n "$s" ] && peers+=("$s")
  done
  if [ ${#peers[@]} -eq 0 ]; then
    printf '%-26s %7s %10s %-20s %-12s %s\n' "$(basename "$file")" "$axes" "$best" failed - "$(cut -d' ' -f1 /proc/loadavg)"
    continue
  fi
  range=$(printf '%s\n' "${peers[@]}" | sort -n | awk 'NR == 1 { lo = $1 } { hi = $1 } END { print (lo == hi ? lo : lo "-" hi) }')
  ratio=$(printf '%s\n' "${peers[@]}" | sort -n | awk -v t="$best" 'NR == 1 { lo = $1 } { hi = $1 }
          END { a = sprintf("%.2f", t / hi); b = sprintf("%.2f", t / lo); print (a == b ? a : a "-" b) }')
  printf '%-26s %7s %10s %-20s %-12s %s\n' "$(basename "$file")" "$axes" "$best" "$range" "$ratio" "$(cut -d' ' -f1 /proc/loadavg)"
done
