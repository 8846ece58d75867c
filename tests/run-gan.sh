#!/usr/bin/env bash
# gan layer: StreetGAN end to end in seconds. Rasterise a small window of a real example city
# (new-york of ../shared/data/examples, © OpenStreetMap contributors, ODbL 1.0) as the project's
# road raster (3 m/px, roads 15 px wide), train two epochs of three iterations (tools/sgan/train.py),
# then tests/gan/check_gan.py: outputs of the training, export and averaging, parity of the SQL sampler with
# PyTorch (< 1e-4), and gan_sample's size and determinism; a second training with the same seed must
# write the same generator file. Then tests/gan/check_models.py on the shipped generators.
source "$(dirname "$0")/lib.sh"
mark=$(log_mark)
fresh_db streetgen_gan streetgen
work=$(mktemp -d /tmp/streetgen-gan.XXXXXX)
trap 'rm -rf "$work"' EXIT
status=0
city="${STREETGEN_SHARED_DATA:?}/examples/cities/new-york.geojson"
# 900 x 900 m of Manhattan's grid: 300 x 300 px.
gdal_rasterize -q -burn 1 -tr 3 3 -te -1200 600 -300 1500 -ot Byte -init 0 -a_srs EPSG:3857 \
  -dialect SQLite -sql 'SELECT ST_Buffer(geometry, 22.5) AS geometry FROM "new-york.gsm"' "$city" "$work/roads.tif"
started=$(date +%s)
/usr/bin/python3 "$SRC"/tools/sgan/train.py "$work/roads.tif" "$work/train" --epochs 2 --iters-per-epoch 3 \
  --batch 4 --noise-side 3 --sample-side 65 --threads 1 --seed 3 || status=$?
echo "gan: tiny training took $(( $(date +%s) - started )) s"
# The same seed and thread count train the same generator, byte for byte; --ema 0 (a moving
# average that is the trained generator itself) must not change that either.
if [ $status -eq 0 ]; then
  /usr/bin/python3 "$SRC"/tools/sgan/train.py "$work/roads.tif" "$work/again" --epochs 2 --iters-per-epoch 3 \
    --batch 4 --noise-side 3 --sample-side 65 --threads 1 --seed 3 --ema 0 >/dev/null || status=$?
  if cmp -s "$work/train/generator.sgan" "$work/again/generator.sgan"; then
    echo "ok   a second training with the same seed gives the same generator file"
  else
    echo "FAIL a second training with the same seed gives another generator file"; status=1
  fi
fi
[ $status -eq 0 ] && { /usr/bin/python3 "$SRC"/tests/gan/check_gan.py streetgen_gan "$work/train" "$work" || status=$?; }
# The shipped generators (models/sgan): parity, and a sample traced back into a graph against the
# example city rasterised and extracted the same way (dead-end share within 20 %: issue 9).
if ls "$SRC"/models/sgan/*.sgan >/dev/null 2>&1; then
  started=$(date +%s)
  /usr/bin/python3 "$SRC"/tests/gan/check_models.py streetgen_gan "$SRC/models/sgan" "${STREETGEN_SHARED_DATA:?}" || status=1
  echo "gan: shipped generators checked in $(( $(date +%s) - started )) s"
fi
assert_no_crash_since "$mark" || status=1
exit $status
