#!/usr/bin/python3
"""The gan layer's checks after a tiny training (tests/run-gan.sh):
  1. the training folder holds what train.py promises (checkpoints, samples, losses, generator);
  2. export.py of the last checkpoint gives the same bytes as train.py's generator.sgan, and the
     exported (folded) network equals the checkpoint's eval-mode generator;
  3. the generator loads into the database, and gan_sample's raw output (C++ forward pass, noise
     from the seed in C++) equals PyTorch's forward pass of the same weights on the noise of the
     same seed (sgan.py), max abs difference < 1e-4, for several sizes and seeds;
  4. gan_sample: size, pixel type, determinism for a seed, another raster for another seed.

usage: check_gan.py DB TRAINING_FOLDER WORK_FOLDER
"""
import csv
import os
import struct
import subprocess
import sys
import time

import numpy as np
import psycopg
import torch

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools", "sgan")
sys.path.insert(0, TOOLS)
import export  # noqa: E402
import sgan  # noqa: E402

failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures += 1


def raster_from_wkb(wkb):
    """One-band PostGIS raster WKB (little-endian) -> (array, pixel type, scale x, scale y)."""
    assert wkb[0] == 1
    nbands, sx, sy = struct.unpack_from("<H2d", wkb, 3)
    width, height = struct.unpack_from("<2H", wkb, 57)
    assert nbands == 1
    pixtype = wkb[61] & 0x0F  # then the nodata value, then the pixels
    if pixtype == 10:
        data = np.frombuffer(wkb, "<f4", width * height, 62 + 4)
    else:
        data = np.frombuffer(wkb, np.uint8, width * height, 62 + 1)
    return data.reshape(height, width), pixtype, sx, sy


def main():
    db, folder, work = sys.argv[1:4]
    # 1. what the training wrote
    names = sorted(os.listdir(folder))
    checkpoints = [n for n in names if n.startswith("checkpoint-")]
    samples = [n for n in names if n.startswith("sample-") and n.endswith(".png")]
    check(len(checkpoints) == 2 and len(samples) == 2, f"two epochs: two checkpoints and two sample PNGs ({names})")
    with open(os.path.join(folder, "losses.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 6 and all(np.isfinite(float(r["d_loss"])) and np.isfinite(float(r["g_loss"])) for r in rows),
          f"losses.csv has one finite row per iteration ({len(rows)} rows)")
    with open(os.path.join(folder, samples[-1]), "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "the samples are PNG files")
    generator_file = os.path.join(folder, "generator.sgan")
    weights = open(generator_file, "rb").read()

    # 2. export of the last checkpoint, and folding
    exported = os.path.join(work, "exported.sgan")
    subprocess.run([sys.executable, os.path.join(TOOLS, "export.py"), os.path.join(folder, checkpoints[-1]), exported],
                   check=True)
    check(open(exported, "rb").read() == weights, "export.py of the last checkpoint equals train.py's generator.sgan")
    trained, _ = export.load_checkpoint_generator(os.path.join(folder, checkpoints[-1]))
    folded, mpp = sgan.read_generator(generator_file)
    a = sgan.sample(trained, 5, 97, 61)
    b = sgan.sample(folded, 5, 97, 61)
    check(float(np.abs(a - b).max()) < 1e-5, f"folded batch norm: exported network = checkpoint (max diff {np.abs(a - b).max():.2e})")
    check(mpp == 3.0, "the generator carries the raster's 3 m per pixel")

    # 3. and 4. in the database
    with psycopg.connect(dbname=db, autocommit=True) as conn:
        conn.execute("SELECT streetgen.gan_load_generator('ci', %s, 'gan layer tiny training')", (weights,))
        worst = 0.0
        for width, height, seed in [(65, 65, 1), (100, 37, -9), (129, 200, 123456789012), (1, 1, 0), (300, 300, 7)]:
            wkb = conn.execute("SELECT ST_AsBinary(streetgen.gan_sample('ci', %s, %s, %s, raw => true))",
                               (width, height, seed)).fetchone()[0]
            cpp, pixtype, _, _ = raster_from_wkb(bytes(wkb))
            ref = sgan.sample(folded, seed, width, height)
            ok_shape = cpp.shape == ref.shape == (height, width) and pixtype == 10
            diff = float(np.abs(cpp - ref).max()) if ok_shape else float("inf")
            # and against the unfolded checkpoint network too
            diff_trained = float(np.abs(cpp - sgan.sample(trained, seed, width, height)).max()) if ok_shape else diff
            worst = max(worst, diff, diff_trained)
            check(ok_shape and diff < 1e-4 and diff_trained < 1e-4,
                  f"parity {width}x{height} seed {seed}: C++ in SQL vs PyTorch max abs diff {diff:.2e} "
                  f"(vs checkpoint {diff_trained:.2e})")
        print(f"parity: worst max abs difference {worst:.2e}")

        # A barely trained generator gives outputs near 0; parity must also hold where the values
        # span [-1, 1]: a generator of the shipped shape with large random weights and batch-norm
        # statistics.
        torch.manual_seed(17)
        wide = sgan.Generator(32, (128, 64, 32, 16))
        with torch.no_grad():
            for m in wide.modules():
                if isinstance(m, torch.nn.ConvTranspose2d):
                    m.weight.normal_(0.0, 0.12)
                    if m.bias is not None:
                        m.bias.normal_(0.0, 0.3)
                elif isinstance(m, torch.nn.BatchNorm2d):
                    m.weight.uniform_(0.5, 1.5)
                    m.bias.normal_(0.0, 0.2)
                    m.running_mean.normal_(0.0, 0.3)
                    m.running_var.uniform_(0.5, 2.0)
        wide.eval()
        wide_file = os.path.join(work, "wide.sgan")
        sgan.write_generator(wide, wide_file)
        conn.execute("SELECT streetgen.gan_load_generator('wide', %s)", (open(wide_file, "rb").read(),))
        for width, height, seed in [(129, 129, 3), (200, 77, -4)]:
            wkb = conn.execute("SELECT ST_AsBinary(streetgen.gan_sample('wide', %s, %s, %s, raw => true))",
                               (width, height, seed)).fetchone()[0]
            cpp, _, _, _ = raster_from_wkb(bytes(wkb))
            ref = sgan.sample(wide, seed, width, height)
            diff = float(np.abs(cpp - ref).max()) if cpp.shape == ref.shape else float("inf")
            check(diff < 1e-4 and float(ref.std()) > 0.3,
                  f"parity {width}x{height} seed {seed}, large weights (output std {ref.std():.2f}): "
                  f"max abs diff {diff:.2e}")

        # statement_timeout stops a long forward pass promptly (the C++ loop polls between blocks).
        conn.execute("SET statement_timeout = 200")
        started = time.monotonic()
        try:
            conn.execute("SELECT ST_Width(streetgen.gan_sample('wide', 2048, 2048, 1))")
            state = "00000"
        except psycopg.errors.QueryCanceled as e:
            state = e.sqlstate
        seconds = time.monotonic() - started
        conn.execute("RESET statement_timeout")
        check(state == "57014" and seconds < 3, f"statement_timeout cancels a 2048 x 2048 sample: {state} after {seconds:.2f} s")
        check(conn.execute("SELECT ST_Width(streetgen.gan_sample('wide', 9, 9, 1))").fetchone()[0] == 9,
              "and the session samples again")

        road = lambda seed: conn.execute(  # noqa: E731
            "SELECT ST_AsBinary(streetgen.gan_sample('ci', 257, 129, %s))", (seed,)).fetchone()[0]
        first, again, other = bytes(road(11)), bytes(road(11)), bytes(road(12))
        img, pixtype, sx, sy = raster_from_wkb(first)
        check(img.shape == (129, 257) and pixtype == 4 and (sx, sy) == (3.0, -3.0),
              f"gan_sample: 257 x 129 8BUI at 3 m ({img.shape}, type {pixtype}, scale {sx}, {sy})")
        check(set(np.unique(img)) <= {0, 1}, "values are 0 and 1")
        check(first == again, "the same seed gives the same raster")
        check(first != other, "another seed gives another raster")
        raw = sgan.sample(folded, 11, 257, 129)
        differ = np.count_nonzero(((img == 1) != (raw > 0)) & (np.abs(raw) > 1e-4))
        check(differ == 0, f"the road raster is PyTorch's output thresholded at 0 ({differ} pixels differ "
                           "away from the threshold)")
    print(f"check_gan: {failures} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
