"""StreetGAN building blocks shared by train.py, export.py and forward.py.

The spatial GAN of Jetchev, Bergmann and Vollgraf ("Texture synthesis with spatial generative
adversarial networks", 2016) as used by Hartmann et al. ("StreetGAN", 2017): a fully convolutional
generator maps a spatial noise tensor (channels x h x w) to an image whose size follows the noise
size, and a fully convolutional discriminator scores every patch of an image.

This file also defines the two things the C++ sampler in src/core/gan must agree on bit for bit:
  * the noise of a seed (counter-based SplitMix64, see noise()), and
  * the generator file format (see write_generator()).
"""
import struct
import zlib

import numpy as np
import torch
from torch import nn

KERNEL = 5
STRIDE = 2
PADDING = 2
MAGIC = b"SGANGEN\0"
FORMAT_VERSION = 1
ACT_RELU = 1
ACT_TANH = 2


def output_size(n, layers, kernel=KERNEL, stride=STRIDE, padding=PADDING):
    """Side of the generator's output for a noise side n (transposed convolution arithmetic)."""
    for _ in range(layers):
        n = (n - 1) * stride - 2 * padding + kernel
    return n


def noise_size(pixels, layers, kernel=KERNEL, stride=STRIDE, padding=PADDING):
    """Smallest noise side whose output covers `pixels` (the sampler crops the rest)."""
    n = 1
    while output_size(n, layers, kernel, stride, padding) < pixels:
        n += 1
    return n


class Generator(nn.Module):
    """Transposed convolutions (kernel 5, stride 2, padding 2: side 2n-1), batch norm and ReLU,
    tanh out. With 5 layers a 25x25 noise gives the paper's 769x769 image.

    kernel 4, padding 1 (side 2n, DCGAN's choice): every output pixel gets the same number of taps,
    so there is no checkerboard of the uneven 5/2 overlap (Odena et al., "Deconvolution and
    checkerboard artifacts", 2016), which dominated the first thousand iterations of the 6 m/px runs."""

    def __init__(self, noise_channels=32, channels=(128, 64, 32, 16), kernel=KERNEL, stride=STRIDE, padding=PADDING):
        super().__init__()
        self.noise_channels = noise_channels
        self.kernel, self.stride, self.padding = kernel, stride, padding
        widths = [noise_channels, *channels, 1]
        layers = []
        for i in range(len(widths) - 1):
            last = i == len(widths) - 2
            layers.append(nn.ConvTranspose2d(widths[i], widths[i + 1], kernel, stride, padding, bias=last))
            if last:
                layers.append(nn.Tanh())
            else:
                layers.append(nn.BatchNorm2d(widths[i + 1]))
                layers.append(nn.ReLU(inplace=True))
        self.net = nn.Sequential(*layers)
        self.layer_count = len(widths) - 1

    def forward(self, z):
        return self.net(z)


class Discriminator(nn.Module):
    """Strided convolutions (kernel 5, stride 2) and leaky ReLU; one logit per patch. Normalised by
    spectral norm (Miyato et al. 2018; the default) or, as in SGAN, batch norm. With batch norm the
    discriminator won within a hundred iterations on road rasters and starved the generator."""

    def __init__(self, channels=(8, 16, 32, 64), norm="spectral", minibatch_std=False):
        super().__init__()
        widths = [1, *channels]
        sn = nn.utils.spectral_norm if norm == "spectral" else (lambda m: m)
        layers = []
        for i in range(len(widths) - 1):
            layers.append(sn(nn.Conv2d(widths[i], widths[i + 1], KERNEL, STRIDE, PADDING, bias=i == 0 or norm != "batch")))
            if i > 0 and norm == "batch":
                layers.append(nn.BatchNorm2d(widths[i + 1]))
            layers.append(nn.LeakyReLU(0.2, inplace=True))
        self.net = nn.Sequential(*layers)
        self.minibatch_std = minibatch_std
        self.out = sn(nn.Conv2d(widths[-1] + (1 if minibatch_std else 0), 1, KERNEL, STRIDE, PADDING))

    def forward(self, x):
        h = self.net(x)
        if self.minibatch_std:
            # Karras et al. (2018), per position: the spread of the features over the batch, as one more
            # channel. A generator that ignores its noise draws the same texture at the same place in
            # every sample (seen at 6 m/px: seeds 1 and 2 differed by 0.05 where pixels spread 0.46);
            # real patches are random crops, so the discriminator can now tell.
            spread = h.std(dim=0, keepdim=True, unbiased=False).mean(dim=1, keepdim=True)
            h = torch.cat([h, spread.expand(h.shape[0], -1, -1, -1)], dim=1)
        return self.out(h)


def init_weights(module):
    """DCGAN initialisation (normal 0.02; batch-norm gain around 1). Spectrally normalised
    convolutions keep PyTorch's default (their weight is recomputed from weight_orig)."""
    if hasattr(module, "weight_orig"):
        return
    if isinstance(module, (nn.Conv2d, nn.ConvTranspose2d)):
        nn.init.normal_(module.weight, 0.0, 0.02)
        if module.bias is not None:
            nn.init.zeros_(module.bias)
    elif isinstance(module, nn.BatchNorm2d):
        nn.init.normal_(module.weight, 1.0, 0.02)
        nn.init.zeros_(module.bias)


def recalibrate_batchnorm(generator, noise_side, batches=16, batch=8, seed=0):
    """Sets the batch norms' running statistics to the exact mean over `batches` batches of fresh
    noise in train mode, then leaves the generator in eval mode. The momentum average of training
    lags behind the weights (on new-york the eval-mode road share was 0.77 where train mode gave
    0.68); sampling (C++ and PyTorch) uses these statistics. Own RNG: training stays deterministic."""
    rng = torch.Generator().manual_seed(seed)
    norms = [m for m in generator.modules() if isinstance(m, nn.BatchNorm2d)]
    saved = [m.momentum for m in norms]
    for m in norms:
        m.reset_running_stats()
        m.momentum = None  # cumulative average
    generator.train()
    with torch.no_grad():
        for _ in range(batches):
            z = torch.rand(batch, generator.noise_channels, noise_side, noise_side, generator=rng) * 2.0 - 1.0
            generator(z)
    for m, momentum in zip(norms, saved):
        m.momentum = momentum
    generator.eval()


def average_state_dicts(states):
    """Uniform average of generator state dicts (Yazici et al., "The unusual effectiveness of averaging
    in GAN training", ICLR 2019): a GAN's generator circles around an equilibrium instead of settling,
    and the mean of its late iterates lies nearer the centre than any one of them. Floating-point
    entries are averaged in float64; integer ones (batch norm's num_batches_tracked) are taken from the
    last state. The batch norms' running statistics of an average are no statistics of the averaged
    weights: recompute them afterwards (recalibrate_batchnorm), as SWA does (Izmailov et al. 2018)."""
    if not states:
        raise ValueError("nothing to average")
    keys = list(states[0].keys())
    for s in states[1:]:
        if list(s.keys()) != keys or any(s[k].shape != states[0][k].shape for k in keys):
            raise ValueError("the generators to average have different architectures")
    out = {}
    for k in keys:
        if states[0][k].is_floating_point():
            out[k] = (sum(s[k].double() for s in states) / len(states)).to(states[0][k].dtype)
        else:
            out[k] = states[-1][k].clone()
    return out


class WeightAverage:
    """Exponential moving average of a generator's parameters (--ema of train.py; Yazici et al. 2019),
    kept in a copy of the generator. The copy's batch-norm statistics are not tracked: recalibrate
    them before use. decay 0 follows the trained weights exactly."""

    def __init__(self, generator, decay):
        import copy
        self.decay = decay
        self.model = copy.deepcopy(generator)
        for p in self.model.parameters():
            p.requires_grad_(False)

    @torch.no_grad()
    def update(self, generator):
        for a, p in zip(self.model.parameters(), generator.parameters()):
            a.mul_(self.decay).add_(p.detach(), alpha=1.0 - self.decay)


# ---- noise of a seed: the same numbers as core::gan::noise() in C++ -------------------------------
_M64 = np.uint64(0xFFFFFFFFFFFFFFFF)


def _mix(z):
    """SplitMix64 (Steele, Lea, Flood 2014; the finaliser of java.util.SplittableRandom) on uint64."""
    z = z + np.uint64(0x9E3779B97F4A7C15)
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def noise(seed, channels, height, width):
    """Uniform noise in [-1, 1) of shape (channels, height, width) for a 64-bit seed.

    Counter-based: element (c, y, x) is mix(mix(seed) ^ (c << 42 | y << 21 | x)); its top 24 bits
    k give 2 k / 2^24 - 1, exact in float32. An element depends on its position only, so a larger
    sample of the same seed extends a smaller one."""
    with np.errstate(over="ignore"):
        key = _mix(np.array([seed & 0xFFFFFFFFFFFFFFFF], dtype=np.uint64))[0]
        c = np.arange(channels, dtype=np.uint64)[:, None, None] << np.uint64(42)
        y = np.arange(height, dtype=np.uint64)[None, :, None] << np.uint64(21)
        x = np.arange(width, dtype=np.uint64)[None, None, :]
        z = _mix(key ^ (c | y | x))
    k = (z >> np.uint64(40)).astype(np.float64)
    return (2.0 * k / 16777216.0 - 1.0).astype(np.float32)


# ---- generator file (documented in README.md, read by src/core/gan/generator.cpp) -----------------
def folded_layers(generator):
    """(weight, scale, shift, activation) per layer: conv bias and eval-mode batch norm folded into
    one per-channel affine map, y = act(scale * conv(x) + shift)."""
    mods = list(generator.net)
    out = []
    i = 0
    while i < len(mods):
        conv = mods[i]
        assert isinstance(conv, nn.ConvTranspose2d)
        w = conv.weight.detach().double()
        cout = w.shape[1]
        bias = conv.bias.detach().double() if conv.bias is not None else torch.zeros(cout, dtype=torch.float64)
        nxt = mods[i + 1]
        if isinstance(nxt, nn.BatchNorm2d):
            s = nxt.weight.detach().double() / torch.sqrt(nxt.running_var.double() + nxt.eps)
            shift = (bias - nxt.running_mean.double()) * s + nxt.bias.detach().double()
            act = mods[i + 2]
            i += 3
        else:
            s = torch.ones(cout, dtype=torch.float64)
            shift = bias
            act = nxt
            i += 2
        code = ACT_RELU if isinstance(act, nn.ReLU) else ACT_TANH if isinstance(act, nn.Tanh) else None
        assert code is not None, act
        out.append((w.float().numpy(), s.float().numpy(), shift.float().numpy(), code))
    return out


def write_generator(generator, path, metres_per_pixel=3.0):
    """Writes the generator (eval mode) in the streetgen generator format, little-endian:

      magic "SGANGEN\\0" (8 bytes), u32 version (1), u32 noise_channels, u32 layer_count,
      u32 kernel, u32 stride, u32 padding, f64 metres_per_pixel,
      per layer: u32 in_channels, u32 out_channels, u32 activation (1 ReLU, 2 tanh),
                 f32 weight[in][out][kernel][kernel] (PyTorch ConvTranspose2d layout),
                 f32 scale[out], f32 shift[out],
      u32 CRC-32 (zlib) of every byte before it."""
    layers = folded_layers(generator)
    buf = bytearray(MAGIC)
    buf += struct.pack("<6Id", FORMAT_VERSION, generator.noise_channels, len(layers), generator.kernel,
                       generator.stride, generator.padding,
                       metres_per_pixel)
    for w, s, shift, code in layers:
        buf += struct.pack("<3I", w.shape[0], w.shape[1], code)
        buf += np.ascontiguousarray(w, dtype="<f4").tobytes()
        buf += np.ascontiguousarray(s, dtype="<f4").tobytes()
        buf += np.ascontiguousarray(shift, dtype="<f4").tobytes()
    buf += struct.pack("<I", zlib.crc32(bytes(buf)) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(bytes(buf))
    return len(buf)


def read_generator(path):
    """Reads a generator file back into an eval-mode Generator whose batch norms are identities
    (scale/shift are folded), for the parity check and the benchmark."""
    data = open(path, "rb").read()
    if data[:8] != MAGIC:
        raise ValueError("not a streetgen generator file")
    if zlib.crc32(data[:-4]) & 0xFFFFFFFF != struct.unpack("<I", data[-4:])[0]:
        raise ValueError("CRC-32 mismatch")
    version, nz, count, k, s, p, mpp = struct.unpack_from("<6Id", data, 8)
    assert version == FORMAT_VERSION
    off = 8 + struct.calcsize("<6Id")
    convs = []
    for _ in range(count):
        cin, cout, code = struct.unpack_from("<3I", data, off)
        off += 12
        w = np.frombuffer(data, "<f4", cin * cout * k * k, off).reshape(cin, cout, k, k)
        off += 4 * w.size
        scale = np.frombuffer(data, "<f4", cout, off)
        off += 4 * cout
        shift = np.frombuffer(data, "<f4", cout, off)
        off += 4 * cout
        convs.append((w, scale, shift, code))
    return FoldedGenerator(nz, convs, k, s, p), mpp


class FoldedGenerator(nn.Module):
    """The exported network in PyTorch: transposed convolution, per-channel affine, activation."""

    def __init__(self, noise_channels, convs, kernel=KERNEL, stride=STRIDE, padding=PADDING):
        super().__init__()
        self.noise_channels = noise_channels
        self.kernel, self.stride, self.padding = kernel, stride, padding
        self.layer_count = len(convs)
        self.convs = nn.ModuleList()
        self.scales, self.shifts, self.codes = [], [], []
        for w, scale, shift, code in convs:
            conv = nn.ConvTranspose2d(w.shape[0], w.shape[1], kernel, stride, padding, bias=False)
            conv.weight.data = torch.from_numpy(w.copy())
            self.convs.append(conv)
            self.scales.append(torch.from_numpy(scale.copy()).view(1, -1, 1, 1))
            self.shifts.append(torch.from_numpy(shift.copy()).view(1, -1, 1, 1))
            self.codes.append(code)

    def forward(self, z):
        for conv, s, b, code in zip(self.convs, self.scales, self.shifts, self.codes):
            z = conv(z) * s + b
            z = torch.relu(z) if code == ACT_RELU else torch.tanh(z)
        return z


def sample(generator, seed, width, height):
    """The sampler's contract, in PyTorch: noise of the seed for the smallest covering noise size,
    forward, crop to height x width from the top-left. Returns a float32 array in [-1, 1]."""
    geometry = (generator.layer_count, generator.kernel, generator.stride, generator.padding)
    z = noise(seed, generator.noise_channels, noise_size(height, *geometry), noise_size(width, *geometry))
    with torch.no_grad():
        out = generator(torch.from_numpy(z)[None])[0, 0]
    return out[:height, :width].numpy()
