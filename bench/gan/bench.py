#!/usr/bin/python3
"""gan_sample speed against PyTorch's own forward pass of the same generator, same noise, same
process run (bench/gan/run.sh starts the cluster). Prints medians and the ratio.

usage: bench.py GENERATOR_FILE SIDE RUNS
"""
import os
import statistics
import struct
import sys
import time

import numpy as np
import psycopg
import torch

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "sgan"))
import sgan  # noqa: E402


def median_seconds(fn, runs):
    fn()  # warm-up
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), min(times)


def main():
    path, side, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    weights = open(path, "rb").read()
    folded, _ = sgan.read_generator(path)
    folded.eval()
    n = sgan.noise_size(side, folded.layer_count, folded.kernel, folded.stride, folded.padding)
    print(f"PyTorch {torch.__version__}; generator {path}: {len(weights)} bytes; sample {side} x {side} px from noise {folded.noise_channels} x "
          f"{n} x {n}; median of {runs} runs after a warm-up")
    with psycopg.connect(autocommit=True) as conn:
        conn.execute("SELECT streetgen.gan_load_generator('bench', %s, replace => true)", (weights,))
        q = "SELECT ST_Width(streetgen.gan_sample('bench', %s, %s, 7))"
        sql_med, sql_min = median_seconds(lambda: conn.execute(q, (side, side)).fetchone(), runs)
        qb = "SELECT ST_Width(streetgen.gan_sample(%s::bytea, %s, %s, 7))"
        bytea_med, _ = median_seconds(lambda: conn.execute(qb, (weights, side, side)).fetchone(), runs)
        wkb = conn.execute("SELECT ST_AsBinary(streetgen.gan_sample('bench', %s, %s, 7, raw => true))",
                           (side, side)).fetchone()[0]
    cpp = np.frombuffer(bytes(wkb), "<f4", side * side, 66).reshape(side, side)
    results = {}
    for threads in (1, 2):
        torch.set_num_threads(threads)
        results[threads] = median_seconds(lambda: sgan.sample(folded, 7, side, side), runs)
    torch.set_num_threads(1)
    z = torch.from_numpy(sgan.noise(7, folded.noise_channels, n, n))[None]
    with torch.no_grad():
        fwd_med, _ = median_seconds(lambda: folded(z), runs)
    diff = float(np.abs(cpp - sgan.sample(folded, 7, side, side)).max())
    print(f"  streetgen.gan_sample (SQL, by name, one backend): {sql_med * 1000:8.1f} ms (min {sql_min * 1000:.1f})")
    print(f"  streetgen.gan_sample (SQL, bytea argument)       : {bytea_med * 1000:8.1f} ms")
    print(f"  PyTorch noise + forward, 1 thread                : {results[1][0] * 1000:8.1f} ms")
    print(f"  PyTorch forward only, 1 thread                   : {fwd_med * 1000:8.1f} ms")
    print(f"  PyTorch noise + forward, 2 threads               : {results[2][0] * 1000:8.1f} ms")
    print(f"  ratio gan_sample / PyTorch (1 thread)            : {sql_med / results[1][0]:8.2f}")
    print(f"  parity on this sample: max abs difference {diff:.2e}")


if __name__ == "__main__":
    main()
