#!/usr/bin/python3
"""Trains a StreetGAN generator (spatial GAN, Jetchev et al. 2016) on random patches of one road
raster, on the CPU.

Input: a single-band raster (GeoTIFF or PNG) with 1 (or any value > 0) = road and 0 = background,
3 m per pixel, roads about 15 px wide: what streetgen.rasterise_network produces (export it with
ST_AsGDALRaster / ST_AsPNG) or gdal_rasterize of buffered axes.

Output folder:
  losses.csv                   one row per iteration (discriminator and generator losses, D outputs)
  checkpoint-NNN.pt            generator, discriminator and optimiser states after each epoch
  sample-NNN.png               a sample of the eval-mode generator for a fixed seed after each epoch
  generator.sgan               the last generator in the streetgen file format (see sgan.py)

Deterministic for --seed and --threads (same machine, same PyTorch). The machine is usually shared:
run long trainings with `nice` and --threads 1.

Example: nice /usr/bin/python3 tools/sgan/train.py ny.tif out/ny --epochs 30 --threads 1
"""
import argparse
import csv
import os
import sys
import time

import numpy as np
import torch
from osgeo import gdal
from torch import nn

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgan  # noqa: E402

gdal.UseExceptions()


def read_raster(path):
    ds = gdal.Open(path)
    if ds is None or ds.RasterCount < 1:
        raise SystemExit(f"{path}: not a raster")
    band = ds.GetRasterBand(1).ReadAsArray()
    if band is None or band.size == 0:
        raise SystemExit(f"{path}: empty raster")
    gt = ds.GetGeoTransform(can_return_null=True)
    # A PNG (ST_AsPNG) carries no georeference: assume the agreed 3 m per pixel.
    return (band > 0).astype(np.float32), abs(gt[1]) if gt else 3.0


def save_png(path, image):
    """image in [-1, 1] -> 8-bit greyscale PNG (white = road)."""
    data = np.clip((image + 1.0) * 127.5, 0, 255).astype(np.uint8)
    mem = gdal.GetDriverByName("MEM").Create("", data.shape[1], data.shape[0], 1, gdal.GDT_Byte)
    mem.GetRasterBand(1).WriteArray(data)
    gdal.GetDriverByName("PNG").CreateCopy(path, mem)


class Patches:
    """Random square patches of the road raster, as tensors in [-1, 1]. Patches with less than
    min_road of road are redrawn a few times (the examples have water and empty margins)."""

    def __init__(self, road, size, rng, min_road, augment):
        if road.shape[0] < size or road.shape[1] < size:
            raise SystemExit(f"raster {road.shape[1]}x{road.shape[0]} is smaller than the patch size {size}")
        share = float(road.mean())
        if share == 0.0 or share == 1.0:
            raise SystemExit("raster is all background or all road: nothing to learn")
        self.road, self.size, self.rng, self.min_road, self.augment = road, size, rng, min_road, augment

    def batch(self, n):
        out = np.empty((n, 1, self.size, self.size), dtype=np.float32)
        h, w = self.road.shape
        for i in range(n):
            for _ in range(20):
                y = int(self.rng.integers(0, h - self.size + 1))
                x = int(self.rng.integers(0, w - self.size + 1))
                patch = self.road[y:y + self.size, x:x + self.size]
                if patch.mean() >= self.min_road:
                    break
            if self.augment:
                patch = np.rot90(patch, int(self.rng.integers(0, 4)))
                if self.rng.integers(0, 2):
                    patch = patch[:, ::-1]
            out[i, 0] = patch * 2.0 - 1.0
        return torch.from_numpy(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("raster", help="road raster (GeoTIFF/PNG, band 1: >0 road, 0 background)")
    ap.add_argument("out", help="output folder (created)")
    ap.add_argument("--epochs", type=int, default=20)
    ap.add_argument("--iters-per-epoch", type=int, default=100)
    ap.add_argument("--batch", type=int, default=8)
    ap.add_argument("--noise-side", type=int, default=5,
                    help="spatial noise side during training; the patch side follows (5 -> 129 px)")
    ap.add_argument("--noise-channels", type=int, default=32)
    ap.add_argument("--gen-kernel", type=int, default=sgan.KERNEL,
                    help="generator kernel (5: side 2n-1, the paper's 769 px from 25; 4: side 2n, no checkerboard)")
    ap.add_argument("--gen-channels", default="128,64,32,16", help="hidden generator widths, coarse to fine")
    ap.add_argument("--disc-channels", default="8,16,32,64",
                    help="discriminator widths (narrower than the generator: a strong D starves G on CPU budgets)")
    ap.add_argument("--minibatch-std", action="store_true",
                    help="give the discriminator the per-position spread of its features over the batch "
                         "(against generators that ignore their noise)")
    ap.add_argument("--disc-norm", choices=("spectral", "batch"), default="spectral")
    ap.add_argument("--real-label", type=float, default=0.9, help="one-sided label smoothing of real patches")
    ap.add_argument("--instance-noise", type=float, default=0.3,
                    help="std of Gaussian noise added to every image the discriminator sees, decaying linearly "
                         "to 0 over --noise-decay iterations: real patches are exactly -1/1, and without it the "
                         "discriminator wins by telling binary from non-binary pixels")
    ap.add_argument("--noise-decay", type=int, default=4000)
    ap.add_argument("--lr", type=float, default=2e-4)
    ap.add_argument("--lr-d", type=float, default=None,
                    help="discriminator learning rate (default --lr); lower it when D(fake) falls below ~0.05 early")
    ap.add_argument("--beta1", type=float, default=0.5)
    ap.add_argument("--min-road", type=float, default=0.05, help="redraw patches with less road than this share")
    ap.add_argument("--augment", action="store_true", help="random 90-degree rotations and flips of patches")
    ap.add_argument("--crop", default=None, help="x,y,w,h: train on this window of the raster only")
    ap.add_argument("--metres-per-pixel", type=float, default=None,
                    help="pixel size stored in the generator (default: the raster's, or 3 without one)")
    ap.add_argument("--share-weight", type=float, default=0.0,
                    help="weight of a road-share term in the generator loss: (mean road of the fake batch - mean "
                         "road of the real batch)^2, road = (tanh + 1) / 2. Without it the samples drew too much "
                         "road (0.56-0.66 against 0.48 on new-york at 3 m/px)")
    ap.add_argument("--out-init-std", type=float, default=None,
                    help="init std of the last (tanh) layer's weights, its bias set to the raster's road share "
                         "(default: DCGAN's 0.02 and 0)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=1, help="torch.set_num_threads (default 1: shared machine)")
    ap.add_argument("--sample-side", type=int, default=257, help="side of the per-epoch sample PNG")
    ap.add_argument("--resume", default=None, help="checkpoint to continue from")
    ap.add_argument("--ema", type=float, default=None, metavar="DECAY",
                    help="also keep an exponential moving average of the generator's weights (e.g. 0.999: about "
                         "the last 1,000 iterations; Yazici et al. 2019) and write it as the epoch's sample and "
                         "generator.sgan; checkpoints hold both (export.py exports the average)")
    args = ap.parse_args()

    torch.set_num_threads(args.threads)
    torch.manual_seed(args.seed)
    torch.use_deterministic_algorithms(True)
    rng = np.random.default_rng(args.seed)
    os.makedirs(args.out, exist_ok=True)

    road, metres_per_pixel = read_raster(args.raster)
    if args.metres_per_pixel:
        metres_per_pixel = args.metres_per_pixel
    if args.crop:
        x, y, w, h = (int(v) for v in args.crop.split(","))
        road = road[y:y + h, x:x + w]
    gen_channels = tuple(int(v) for v in args.gen_channels.split(","))
    layers = len(gen_channels) + 1
    gen_padding = (args.gen_kernel - 1) // 2  # 5 -> 2 (side 2n-1), 4 -> 1 (side 2n)
    patch = sgan.output_size(args.noise_side, layers, args.gen_kernel, sgan.STRIDE, gen_padding)
    data = Patches(road, patch, rng, args.min_road, args.augment)

    G = sgan.Generator(args.noise_channels, gen_channels, args.gen_kernel, sgan.STRIDE, gen_padding)
    D = sgan.Discriminator(tuple(int(v) for v in args.disc_channels.split(",")), args.disc_norm, args.minibatch_std)
    G.apply(sgan.init_weights)
    if args.out_init_std:
        # The DCGAN init (std 0.02) gives the tanh layer pre-activations of about +-0.2: grey images that
        # the discriminator tells from the binary real patches at once (D(fake) 0.008 by iteration 150 on
        # paris at 6 m/px), while Adam's steps of 2e-4 take hundreds of iterations to scale the weights
        # up. Start near the real contrast and the real road share instead (D(fake) stayed 0.1-0.3).
        last = G.net[-2]
        nn.init.normal_(last.weight, 0.0, args.out_init_std)
        share = float(np.clip(road.mean(), 0.02, 0.98))
        nn.init.constant_(last.bias, float(np.arctanh(2.0 * share - 1.0)))
    D.apply(sgan.init_weights)
    opt_g = torch.optim.Adam(G.parameters(), lr=args.lr, betas=(args.beta1, 0.999))
    opt_d = torch.optim.Adam(D.parameters(), lr=args.lr_d or args.lr, betas=(args.beta1, 0.999))
    bce = nn.BCEWithLogitsLoss()
    start_epoch = 0
    if args.resume:
        state = torch.load(args.resume)
        G.load_state_dict(state["generator"])
        d_state = state["discriminator"]
        if not any(k.startswith("out.") for k in d_state):
            # Checkpoints before --minibatch-std kept the last convolution at the end of D.net.
            last = max(int(k.split(".")[1]) for k in d_state if k.startswith("net."))
            d_state = {("out." + k.split(".", 2)[2] if k.startswith(f"net.{last}.") else k): v
                       for k, v in d_state.items()}
        D.load_state_dict(d_state)
        opt_g.load_state_dict(state["opt_g"])
        opt_d.load_state_dict(state["opt_d"])
        torch.set_rng_state(state["torch_rng"])
        rng.bit_generator.state = state["numpy_rng"]
        start_epoch = state["epoch"]
    ema = None
    if args.ema is not None:
        if not 0.0 <= args.ema < 1.0:
            raise SystemExit("--ema: the decay must be in [0, 1)")
        # resuming a run without --ema: the average starts at the resumed generator
        ema = sgan.WeightAverage(G, args.ema)
        if args.resume and "generator_ema" in state:
            ema.model.load_state_dict(state["generator_ema"])

    g_params = sum(p.numel() for p in G.parameters())
    print(f"train: raster {road.shape[1]}x{road.shape[0]} px ({metres_per_pixel:g} m/px, road share "
          f"{road.mean():.3f}), patch {patch} px, generator {g_params} parameters, {args.threads} thread(s)",
          flush=True)

    losses_path = os.path.join(args.out, "losses.csv")
    new_file = start_epoch == 0 or not os.path.exists(losses_path)
    log = open(losses_path, "w" if new_file else "a", newline="")
    writer = csv.writer(log)
    if new_file:
        writer.writerow(["epoch", "iteration", "d_loss", "g_loss", "d_real", "d_fake", "seconds"])
    started = time.monotonic()
    iteration = start_epoch * args.iters_per_epoch
    for epoch in range(start_epoch + 1, start_epoch + args.epochs + 1):
        G.train()
        D.train()
        for _ in range(args.iters_per_epoch):
            iteration += 1
            real = data.batch(args.batch)
            real_clean = real
            z = torch.rand(args.batch, args.noise_channels, args.noise_side, args.noise_side) * 2.0 - 1.0
            fake = G(z)
            # Discriminator: every patch logit of a real image says 1, of a fake one 0.
            sigma = args.instance_noise * max(0.0, 1.0 - iteration / args.noise_decay)
            if sigma > 0:
                real = real + sigma * torch.randn_like(real)
                seen_fake = fake + sigma * torch.randn_like(fake)
            else:
                seen_fake = fake
            opt_d.zero_grad()
            out_real = D(real)
            out_fake = D(seen_fake.detach())
            d_loss = (bce(out_real, torch.full_like(out_real, args.real_label))
                      + bce(out_fake, torch.zeros_like(out_fake)))
            d_loss.backward()
            opt_d.step()
            # Generator: the non-saturating loss of Goodfellow et al. (maximise log D(G(z))).
            opt_g.zero_grad()
            out = D(seen_fake)
            g_loss = bce(out, torch.ones_like(out))
            if args.share_weight > 0:
                share_gap = ((fake + 1.0) * 0.5).mean() - ((real_clean + 1.0) * 0.5).mean()
                g_loss = g_loss + args.share_weight * share_gap * share_gap
            g_loss.backward()
            opt_g.step()
            if ema is not None:
                ema.update(G)
            writer.writerow([epoch, iteration, f"{d_loss.item():.5f}", f"{g_loss.item():.5f}",
                             f"{torch.sigmoid(out_real).mean().item():.4f}",
                             f"{torch.sigmoid(out_fake).mean().item():.4f}",
                             f"{time.monotonic() - started:.1f}"])
        log.flush()
        # Statistics of a larger noise than the patches' (9 for 5): at 129 px much of the image is
        # border, where fewer kernel taps add up; samples are mostly interior. Leaves G in eval mode.
        sgan.recalibrate_batchnorm(G, 2 * args.noise_side - 1)
        state = {"generator": G.state_dict(), "discriminator": D.state_dict(), "opt_g": opt_g.state_dict(),
                 "opt_d": opt_d.state_dict(), "epoch": epoch, "torch_rng": torch.get_rng_state(),
                 "numpy_rng": rng.bit_generator.state, "args": vars(args), "metres_per_pixel": metres_per_pixel}
        shown = G
        if ema is not None:
            # the average's own statistics (the trained generator's do not fit its weights)
            sgan.recalibrate_batchnorm(ema.model, 2 * args.noise_side - 1)
            state["generator_ema"] = ema.model.state_dict()
            shown = ema.model
        tag = f"{epoch:03d}"
        torch.save(state, os.path.join(args.out, f"checkpoint-{tag}.pt"))
        save_png(os.path.join(args.out, f"sample-{tag}.png"), sgan.sample(shown, 1, args.sample_side, args.sample_side))
        size = sgan.write_generator(shown, os.path.join(args.out, "generator.sgan"), metres_per_pixel)
        print(f"epoch {epoch}: d_loss {d_loss.item():.3f} g_loss {g_loss.item():.3f} "
              f"({time.monotonic() - started:.0f} s, generator {size} bytes)", flush=True)
    log.close()


if __name__ == "__main__":
    main()
