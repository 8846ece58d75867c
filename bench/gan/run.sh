#!/usr/bin/env bash
# StreetGAN sampling speed (issue 9): streetgen.gan_sample for 769 x 769 px (the paper's size,
# from 25 x 25 noise) on one backend, against PyTorch's own forward pass of the same generator on
# the same noise in the same run (1 and 2 threads), as a ratio.
#
#   bash bench/gan/run.sh [GENERATOR_FILE]   default: models/sgan/*.sgan if one is shipped,
#                                            else a random generator of the shipped shape
#   SIDE=1025 RUNS=9 bash bench/gan/run.sh   another size, more runs
# Nothing is built or installed here: the extension must be installed for the pg_config on PATH.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
port="${STREETGEN_BENCH_PORT:-54338}"
side="${SIDE:-769}"
runs="${RUNS:-5}"
work=$(mktemp -d /tmp/streetgen-bench-gan.XXXXXX)
generator="${1:-}"
if [ -z "$generator" ]; then
  generator=$(ls "$repo"/models/sgan/*.sgan 2>/dev/null | head -1 || true)
fi
if [ -z "$generator" ]; then
  generator="$work/random.sgan"
  /usr/bin/python3 - "$generator" "$repo/tools/sgan" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
import torch, sgan
torch.manual_seed(1)
g = sgan.Generator()
g.apply(sgan.init_weights)
g.eval()
sgan.write_generator(g, sys.argv[1])
PY
fi
source "$repo/bench/lib.sh"
bench_cluster "$port" nobuild
trap 'rm -rf "$work"; bash "$repo/scripts/pgcluster.sh" destroy "$cluster" >/dev/null 2>&1 || true' EXIT
/usr/bin/python3 "$repo/bench/gan/bench.py" "$generator" "$side" "$runs"
