#!/usr/bin/python3
"""A picture of a generator's samples, beside a window of its training raster if given: what
streetgen.gan_sample(generator, side, side, seed) returns (the PyTorch reference sampler of sgan.py,
equal to the SQL one within 1e-4), thresholded at 0, white = road. Also prints the road share of
each sample and of the example window.

Pictures of OpenStreetMap-derived examples carry "© OpenStreetMap contributors, ODbL 1.0".

Example: /usr/bin/python3 tools/sgan/preview.py ny/generator.sgan ny.png --example ny.tif --seeds 1 2 3
"""
import argparse
import os
import sys

import numpy as np
import torch
from osgeo import gdal

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgan  # noqa: E402
from train import read_raster, save_png  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("generator")
    ap.add_argument("output")
    ap.add_argument("--side", type=int, default=769)
    ap.add_argument("--seeds", type=int, nargs="+", default=[1])
    ap.add_argument("--example", help="training raster: a window of the same size goes first")
    ap.add_argument("--at", default=None, help="x,y of the example window (default: the raster's centre)")
    args = ap.parse_args()
    torch.set_num_threads(1)
    gdal.UseExceptions()
    g, _ = sgan.read_generator(args.generator)
    tiles = []
    if args.example:
        road, _ = read_raster(args.example)
        if args.at:
            x, y = (int(v) for v in args.at.split(","))
        else:
            y, x = (road.shape[0] - args.side) // 2, (road.shape[1] - args.side) // 2
        window = road[y:y + args.side, x:x + args.side]
        print(f"example window at {x},{y}: road share {window.mean():.3f}")
        tiles.append(window * 2.0 - 1.0)
    for seed in args.seeds:
        image = sgan.sample(g, seed, args.side, args.side)
        print(f"seed {seed}: road share {(image > 0).mean():.3f}")
        tiles.append(np.where(image > 0, 1.0, -1.0))
    gap = np.zeros((args.side, 12), dtype=np.float32)
    strip = np.concatenate([t for tile in tiles for t in (tile, gap)][:-1], axis=1)
    save_png(args.output, strip)


if __name__ == "__main__":
    main()
