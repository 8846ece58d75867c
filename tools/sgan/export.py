#!/usr/bin/python3
"""Exports the generator of train.py checkpoints to the streetgen generator file format
(sgan.py write_generator; README.md, "StreetGAN"), for loading with streetgen.gan_load_generator.

train.py already writes generator.sgan after every epoch; this picks any other epoch, or averages
several: given more than one checkpoint of the same run, the generator's weights are averaged
uniformly (Yazici et al. 2019: the late iterates of a GAN circle around an equilibrium, their mean
lies nearer it) and the batch norms' running statistics are recomputed for the averaged weights on
fresh noise (as SWA does), with the noise side train.py uses for its checkpoints.

A checkpoint of train.py --ema holds a moving average of the generator beside the trained one; the
average is exported (and averaged) unless --no-ema.

Examples: /usr/bin/python3 tools/sgan/export.py out/ny/checkpoint-020.pt ny-020.sgan
          /usr/bin/python3 tools/sgan/export.py out/ny/checkpoint-0{41..60}.pt ny-avg41-60.sgan
"""
import argparse
import os
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgan  # noqa: E402

# The training options that fix the generator's architecture: checkpoints to average must agree.
ARCHITECTURE = ("noise_channels", "gen_channels", "gen_kernel")


def _generator(args):
    kernel = args.get("gen_kernel", sgan.KERNEL)  # checkpoints before --gen-kernel: 5
    return sgan.Generator(args["noise_channels"], tuple(int(v) for v in args["gen_channels"].split(",")), kernel,
                          sgan.STRIDE, (kernel - 1) // 2)


def generator_state(state, ema=True):
    """The generator's state dict of a checkpoint: the moving average (train.py --ema) if there is one
    and `ema`, else the trained generator."""
    return state["generator_ema"] if ema and "generator_ema" in state else state["generator"]


def load_checkpoint_generator(path, ema=True):
    state = torch.load(path)
    g = _generator(state["args"])
    g.load_state_dict(generator_state(state, ema))
    g.eval()
    return g, state


def average_checkpoints(paths, ema=True, noise_side=None):
    """An eval-mode generator whose weights are the uniform mean of the checkpoints' generators, its
    batch-norm statistics recomputed over fresh noise (recalibration side: noise_side, default the
    one train.py uses, 2 * training noise side - 1). Returns (generator, last checkpoint's state)."""
    states = [torch.load(p) for p in paths]
    first = states[0]["args"]
    for p, s in zip(paths, states):
        for k in ARCHITECTURE:
            if s["args"].get(k) != first.get(k):
                raise SystemExit(f"export: {p}: {k} {s['args'].get(k)} differs from {paths[0]}'s {first.get(k)}")
    g = _generator(first)
    g.load_state_dict(sgan.average_state_dicts([generator_state(s, ema) for s in states]))
    sgan.recalibrate_batchnorm(g, noise_side or 2 * first.get("noise_side", 5) - 1)
    return g, states[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("checkpoint", nargs="+", help="one checkpoint, or several to average")
    ap.add_argument("output")
    ap.add_argument("--metres-per-pixel", type=float, default=None, help="default: the training's, else 3")
    ap.add_argument("--recalibrate", type=int, default=None, metavar="NOISE_SIDE",
                    help="recompute the batch-norm statistics first (train.py does it before saving a "
                         "checkpoint; for checkpoints of older versions). With several checkpoints they are "
                         "always recomputed; this sets the noise side (default 2 * training side - 1)")
    ap.add_argument("--no-ema", action="store_true", help="export the trained generator of --ema checkpoints")
    args = ap.parse_args()
    ema = not args.no_ema
    if len(args.checkpoint) > 1:
        g, state = average_checkpoints(args.checkpoint, ema, args.recalibrate)
    else:
        g, state = load_checkpoint_generator(args.checkpoint[0], ema)
        if args.recalibrate:
            sgan.recalibrate_batchnorm(g, args.recalibrate)
    mpp = args.metres_per_pixel or state.get("metres_per_pixel") or 3.0
    size = sgan.write_generator(g, args.output, mpp)
    what = f"the average of {len(args.checkpoint)} checkpoints" if len(args.checkpoint) > 1 else args.checkpoint[0]
    print(f"export: {args.output} from {what}: {size} bytes, {sum(p.numel() for p in g.parameters())} parameters")


if __name__ == "__main__":
    main()
