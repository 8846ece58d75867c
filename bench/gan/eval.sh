#!/usr/bin/env bash
# StreetGAN evaluation of the shipped generators (issue 9; Hartmann et al. 2017, section 5.2):
# for each models/sgan/<city>.sgan, gan_sample (769 x 769 px, seeds 1-4) -> raster_to_network ->
# network_stats inside the window, against the example city's own graph in the same window and the
# example rasterised and extracted the same way (bench/gan/eval.py). Writes the evaluation table
# (<city>-table.md), metrics.csv and a picture per city into OUT (default bench/gan/out, not
# committed). The example windows are the densest 769 px windows of the training rasters.
#
#   bash bench/gan/eval.sh [OUT [CITY=GENERATOR ...]]   e.g. paris=/tmp/run/generator.sgan; default
#       models/sgan/<city>.sgan. Needs ../shared/data (STREETGEN_SHARED_DATA) and the extension
#       installed for the pg_config on PATH.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
port="${STREETGEN_BENCH_PORT:-54339}"
out="${1:-$repo/bench/gan/out}"
shift || true
declare -A given
for pair in "$@"; do given[${pair%%=*}]=${pair#*=}; done
export STREETGEN_SHARED_DATA="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
source "$repo/bench/lib.sh"
bench_cluster "$port" nobuild
mkdir -p "$out"
# city, upper-left corner of the example window (local metres of the example file)
while read -r city window; do
  generator="${given[$city]:-$repo/models/sgan/$city.sgan}"
  [ -f "$generator" ] || { echo "eval: no $generator, skipped"; continue; }
  /usr/bin/python3 "$repo/bench/gan/eval.py" "$city" "$generator" --window="$window" --seeds 1 2 3 4 --out "$out"
done <<'EOF'
new-york 2700,900
paris -5100,5100
EOF
