#!/usr/bin/python3
"""The gan layer's checks after a tiny training (tests/run-gan.sh):
  1. the training folder holds what train.py promises (checkpoints, samples, losses, generator);
  2. export.py of the last checkpoint gives the same bytes as train.py's generator.sgan, and the
     exported (folded) network equals the checkpoint's eval-mode generator; export.py of several
     checkpoints averages their weights (then recomputes the batch-norm statistics), refuses
     checkpoints of another architecture; train.py --ema keeps the average of sgan.WeightAverage
     (decay 0: the trained generator itself, WORK_FOLDER/again of run-gan.sh);
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


def run_export(*args):
    return subprocess.run([sys.executable, os.path.join(TOOLS, "export.py"), *args], capture_output=True, text=True)


def check_averaging(folder, checkpoints, work, weights):
    first, last = (os.path.join(folder, c) for c in checkpoints[:2])
    # The average of a checkpoint with itself is that checkpoint, statistics recomputed the way
    # train.py computed them: the same bytes.
    same = os.path.join(work, "self-average.sgan")
    r = run_export(last, last, same)
    check(r.returncode == 0 and open(same, "rb").read() == weights,
          f"export.py averaging a checkpoint with itself gives its generator file ({r.stderr.strip()[-200:]})")
    # Two checkpoints (the last one's second layer tripled, so that they differ much more than after
    # three iterations; its statistics recomputed): every convolution weight and bias, every batch-norm
    # gain and shift of the average is their mean.
    state = torch.load(last)
    tripled, _ = export.load_checkpoint_generator(last)
    with torch.no_grad():
        tripled.net[3].weight.mul_(3.0)
    sgan.recalibrate_batchnorm(tripled, 5)
    state["generator"] = tripled.state_dict()
    last = os.path.join(work, "tripled.pt")
    torch.save(state, last)
    avg = os.path.join(work, "average.sgan")
    r = run_export(first, last, avg)
    a, b = (torch.load(p)["generator"] for p in (first, last))
    g, _ = export.average_checkpoints([first, last])
    learned = [k for k in a if not k.endswith(("running_mean", "running_var", "num_batches_tracked"))]
    worst = max(float((g.state_dict()[k].double() - (a[k].double() + b[k].double()) / 2).abs().max()) for k in learned)
    check(r.returncode == 0 and worst < 1e-7 and any(not torch.equal(a[k], b[k]) for k in learned),
          f"export.py of two checkpoints: every learned tensor is their mean (max diff {worst:.1e})")
    # ... and its batch-norm statistics are those of the averaged weights (the mean of the batch means
    # over the recalibration's noise: seed 0, 16 batches of 8, side 2 * 3 - 1), not the mean of the two
    # checkpoints' statistics. The second batch norm: the first one's input is linear in the weights.
    bn = g.net[4]
    rng = torch.Generator().manual_seed(0)
    g.train()
    with torch.no_grad():
        means = [g.net[:4](torch.rand(8, g.noise_channels, 5, 5, generator=rng) * 2.0 - 1.0).mean(dim=(0, 2, 3))
                 for _ in range(16)]
    g.eval()
    batch_mean = torch.stack(means).mean(dim=0)
    naive = (a["net.4.running_mean"] + b["net.4.running_mean"]) / 2
    err, naive_err = (float((m - batch_mean).abs().max()) for m in (bn.running_mean, naive))
    check(err < 1e-5 < naive_err, f"the average's batch-norm statistics are recomputed for its weights (max diff {err:.1e}; "
                      f"the mean of the checkpoints' statistics is {naive_err:.1e} off)")
    # Checkpoints of another architecture are refused with a message.
    state = torch.load(last)
    state["args"] = dict(state["args"], gen_channels="8,8,8,8")
    other = os.path.join(work, "other.pt")
    torch.save(state, other)
    r = run_export(last, other, os.path.join(work, "refused.sgan"))
    check(r.returncode != 0 and "gen_channels" in r.stderr and not os.path.exists(os.path.join(work, "refused.sgan")),
          f"export.py refuses to average checkpoints of another architecture: {r.stderr.strip()}")
    # --ema: sgan.WeightAverage is the exponential moving average
    torch.manual_seed(2)
    net = torch.nn.Linear(3, 2)
    start = [p.detach().clone() for p in net.parameters()]
    ema = sgan.WeightAverage(net, 0.75)
    steps = []
    for _ in range(3):
        with torch.no_grad():
            for p in net.parameters():
                p.add_(torch.randn_like(p))
        steps.append([p.detach().clone() for p in net.parameters()])
        ema.update(net)
    expect = [0.75 ** 3 * s0 + sum(0.25 * 0.75 ** (2 - i) * st[j] for i, st in enumerate(steps))
              for j, s0 in enumerate(start)]
    diff = max(float((p - e).abs().max()) for p, e in zip(ema.model.parameters(), expect))
    check(diff < 1e-6, f"WeightAverage(decay 0.75) after 3 steps is the moving average (max diff {diff:.1e})")
    again = os.path.join(work, "again", checkpoints[-1])
    if os.path.exists(again):
        state = torch.load(again)
        ema_state = state.get("generator_ema", {})
        check(state["args"].get("ema") == 0.0 and ema_state.keys() == state["generator"].keys()
              and all(torch.equal(ema_state[k], v) for k, v in state["generator"].items()),
              "train.py --ema 0 checkpoints an average equal to the trained generator")


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
    check_averaging(folder, checkpoints, work, weights)

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
