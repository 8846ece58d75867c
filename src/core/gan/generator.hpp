// StreetGAN sampling (Hartmann et al. 2017 on the spatial GAN of Jetchev et al. 2016): the
// generator file format, the noise of a seed, and the generator's forward pass on the CPU.
//
// Why a forward pass of our own instead of libtorch (Debian libtorch-dev 1.13 + TorchScript):
// libtorch_cpu.so alone is 115 MB and pulls 285 shared libraries (OpenCV, FFmpeg, protobuf,
// OpenMP) into every backend that samples, its dlopen took 1.4-1.6 s per backend on the
// development machine, and its intra-op thread pools would start threads inside a PostgreSQL
// backend. The network is five transposed convolutions, a per-channel affine map and an
// activation; the matrix products go to Eigen (header-only, single-threaded here), the rest is a
// few loops, and the gan CTest layer checks parity with PyTorch on the same weights and noise.
//
// The file format and the noise are defined together with tools/sgan/sgan.py (write_generator,
// noise); README.md documents both.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streetgen::core::gan {

// Largest side accepted by sample(): 2048 px (6 km at 3 m/px). Memory grows with the area; at
// 2048 x 2048 with the shipped generator the largest activation is about 70 MB.
constexpr int kMaxSide = 2048;

enum class Activation : std::uint32_t { relu = 1, tanh = 2 };

struct Layer {
  int in_channels = 0;
  int out_channels = 0;
  Activation activation = Activation::relu;
  std::vector<float> weight;  // [in][out][kernel][kernel], PyTorch's ConvTranspose2d layout
  std::vector<float> scale;   // [out]: conv bias and eval-mode batch norm folded:
  std::vector<float> shift;   // [out]  y = act(scale * conv(x) + shift)
};

struct Generator {
  int noise_channels = 0;
  int kernel = 0;
  int stride = 0;
  int padding = 0;
  double metres_per_pixel = 0.0;
  std::vector<Layer> layers;

  // Output side for a noise side n, and the smallest noise side whose output covers `pixels`.
  long output_side(long n) const;
  int noise_side(int pixels) const;
  std::size_t parameter_count() const;
};

// Parses and checks a generator file. Throws Error(bad_data) naming what is wrong: magic,
// version, header values, layer shapes (each layer's input is the previous one's output, the last
// has one channel), truncation or trailing bytes, non-finite numbers, CRC-32 mismatch.
Generator parse_generator(const std::uint8_t* data, std::size_t size);

// Uniform noise in [-1, 1), shape (channels, height, width) row-major. Counter-based SplitMix64:
// element (c, y, x) is mix(mix(seed) ^ (c << 42 | y << 21 | x)), k = its top 24 bits,
// value = 2 k / 2^24 - 1. Identical to tools/sgan/sgan.py noise().
std::vector<float> noise(std::uint64_t seed, int channels, int height, int width);

// One sample image, row-major, values in [-1, 1] (tanh): road where > 0.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;
};

// The forward pass on a noise tensor (noise_channels x height x width).
Image forward(const Generator& generator, const std::vector<float>& noise, int noise_height, int noise_width);

// noise(seed) of the smallest covering noise size, forward, crop to height x width from the
// top-left. Throws Error(invalid_argument) for sides outside [1, kMaxSide]. Polls interrupts.
Image sample(const Generator& generator, std::uint64_t seed, int width, int height);

// A PostGIS raster in WKB (one band, upper-left corner and pixel size given, scale_y negative):
// 8BUI with 1 = road (value > threshold) and 0 = background, or 32BF with the raw values.
std::vector<std::uint8_t> raster_wkb(const Image& image, bool raw, double threshold, double upper_left_x,
                                     double upper_left_y, double pixel_size, std::int32_t srid);

}  // namespace streetgen::core::gan
