#!/usr/bin/python3
"""Exports the generator of a train.py checkpoint to the streetgen generator file format
(sgan.py write_generator; README.md, "StreetGAN"), for loading with streetgen.gan_load_generator.

train.py already writes generator.sgan after every epoch; this picks any other epoch.

Example: /usr/bin/python3 tools/sgan/export.py out/ny/checkpoint-020.pt ny-020.sgan
"""
import argparse
import os
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgan  # noqa: E402


def load_checkpoint_generator(path):
    state = torch.load(path)
    args = state["args"]
    kernel = args.get("gen_kernel", sgan.KERNEL)  # checkpoints before --gen-kernel: 5
    g = sgan.Generator(args["noise_channels"], tuple(int(v) for v in args["gen_channels"].split(",")), kernel,
                       sgan.STRIDE, (kernel - 1) // 2)
    g.load_state_dict(state["generator"])
    g.eval()
    return g, state


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("checkpoint")
    ap.add_argument("output")
    ap.add_argument("--metres-per-pixel", type=float, default=None, help="default: the training's, else 3")
    ap.add_argument("--recalibrate", type=int, default=None, metavar="NOISE_SIDE",
                    help="recompute the batch-norm statistics first (train.py does it before saving a "
                         "checkpoint; for checkpoints of older versions)")
    args = ap.parse_args()
    g, state = load_checkpoint_generator(args.checkpoint)
    if args.recalibrate:
        sgan.recalibrate_batchnorm(g, args.recalibrate)
    mpp = args.metres_per_pixel or state.get("metres_per_pixel") or 3.0
    size = sgan.write_generator(g, args.output, mpp)
    print(f"export: {args.output}: {size} bytes, {sum(p.numel() for p in g.parameters())} parameters")


if __name__ == "__main__":
    main()
