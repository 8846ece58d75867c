#include "core/gan/generator.hpp"

#include <zlib.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/error.hpp"
#include "core/interrupts.hpp"

namespace streetgen::core::gan {
namespace {

constexpr char kMagic[8] = {'S', 'G', 'A', 'N', 'G', 'E', 'N', '\0'};
constexpr std::uint32_t kVersion = 1;
constexpr int kMaxChannels = 4096;
constexpr int kMaxLayers = 16;
// Largest activation (channels x height x width floats) a sample may need: 512 MB.
constexpr std::size_t kMaxActivationFloats = std::size_t{1} << 27;
// Rows of the im2col-free transposed convolution are processed in blocks of at most this many
// floats of products (16 MB), so memory does not grow with the image beyond the activations.
constexpr std::size_t kBlockFloats = std::size_t{1} << 22;

[[noreturn]] void corrupt(const std::string& message, std::string detail = {}) {
  throw Error(ErrorKind::bad_data, "generator " + message, std::move(detail),
              "Export the generator again with tools/sgan/export.py (or train.py), then reload it.");
}

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::size_t offset() const { return pos_; }
  std::size_t left() const { return size_ - pos_; }

  void need(std::size_t bytes, const char* what) const {
    if (left() < bytes) {
      corrupt("is truncated", "Reading " + std::string(what) + " needs " + std::to_string(bytes) +
                                  " bytes at offset " + std::to_string(pos_) + ", but only " +
                                  std::to_string(left()) + " are left.");
    }
  }
  std::uint32_t u32(const char* what) {
    need(4, what);
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | data_[pos_ + static_cast<std::size_t>(i)];
    pos_ += 4;
    return v;
  }
  double f64(const char* what) {
    need(8, what);
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | data_[pos_ + static_cast<std::size_t>(i)];
    pos_ += 8;
    double d;
    std::memcpy(&d, &v, sizeof d);
    return d;
  }
  void floats(std::vector<float>& out, std::size_t count, const std::string& what) {
    if (count > left() / 4) need(count * 4, what.c_str());  // checked before allocating
    out.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint8_t* b = data_ + pos_ + 4 * i;
      std::uint32_t v = std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
                        std::uint32_t{b[3]} << 24;
      float f;
      std::memcpy(&f, &v, sizeof f);
      if (!std::isfinite(f)) {
        corrupt("holds a non-finite number", "Element " + std::to_string(i) + " of " + what + " (offset " +
                                                 std::to_string(pos_ + 4 * i) + ") is not finite.");
      }
      out[i] = f;
    }
    pos_ += 4 * count;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

int checked_int(std::uint32_t v, std::uint32_t lo, std::uint32_t hi, const char* what) {
  if (v < lo || v > hi) {
    corrupt("has an invalid " + std::string(what),
            "The " + std::string(what) + " is " + std::to_string(v) + "; it must be between " + std::to_string(lo) +
                " and " + std::to_string(hi) + ".");
  }
  return static_cast<int>(v);
}

std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

void put_bytes(std::vector<std::uint8_t>& out, const void* p, std::size_t n) {
  // WKB is written little-endian (its first byte says so); the hosts we build for are too.
  static_assert(sizeof(double) == 8 && sizeof(float) == 4, "IEEE 754 sizes expected");
  const auto* b = static_cast<const std::uint8_t*>(p);
  out.insert(out.end(), b, b + n);
}
template <class T>
void put(std::vector<std::uint8_t>& out, T v) {
  put_bytes(out, &v, sizeof v);
}

}  // namespace

long Generator::output_side(long n) const {
  for (std::size_t i = 0; i < layers.size(); ++i) n = (n - 1) * stride - 2L * padding + kernel;
  return n;
}

int Generator::noise_side(int pixels) const {
  // stride >= 2 (checked by the parser), so the output more than doubles per layer once n > 2p.
  int n = 1;
  while (output_side(n) < pixels) ++n;
  return n;
}

std::size_t Generator::parameter_count() const {
  std::size_t count = 0;
  for (const auto& layer : layers) count += layer.weight.size() + layer.scale.size() + layer.shift.size();
  return count;
}

Generator parse_generator(const std::uint8_t* data, std::size_t size) {
  Reader in(data, size);
  in.need(sizeof kMagic, "the magic number");
  if (std::memcmp(data, kMagic, sizeof kMagic) != 0) {
    corrupt("is not a streetgen generator file", "The first 8 bytes are not the magic number \"SGANGEN\\0\".");
  }
  Reader header(data + sizeof kMagic, size - sizeof kMagic);
  const std::uint32_t version = header.u32("the format version");
  if (version != kVersion) {
    corrupt("has an unsupported format version",
            "The file has format version " + std::to_string(version) + "; this streetgen reads version " +
                std::to_string(kVersion) + ".");
  }
  Generator g;
  g.noise_channels = checked_int(header.u32("the noise channel count"), 1, kMaxChannels, "noise channel count");
  const int layer_count = checked_int(header.u32("the layer count"), 1, kMaxLayers, "layer count");
  g.kernel = checked_int(header.u32("the kernel size"), 1, 15, "kernel size");
  g.stride = checked_int(header.u32("the stride"), 2, 4, "stride");
  g.padding = checked_int(header.u32("the padding"), 0, static_cast<std::uint32_t>(g.kernel - 1), "padding");
  g.metres_per_pixel = header.f64("the pixel size");
  if (!std::isfinite(g.metres_per_pixel) || g.metres_per_pixel <= 0.0) {
    corrupt("has an invalid pixel size", "metres_per_pixel must be a positive finite number.");
  }
  int previous = g.noise_channels;
  const std::size_t kk = static_cast<std::size_t>(g.kernel) * static_cast<std::size_t>(g.kernel);
  for (int l = 0; l < layer_count; ++l) {
    const std::string name = "layer " + std::to_string(l + 1);
    Layer layer;
    layer.in_channels = checked_int(header.u32("a layer header"), 1, kMaxChannels, "input channel count");
    layer.out_channels = checked_int(header.u32("a layer header"), 1, kMaxChannels, "output channel count");
    const std::uint32_t act = header.u32("a layer header");
    if (act != static_cast<std::uint32_t>(Activation::relu) && act != static_cast<std::uint32_t>(Activation::tanh)) {
      corrupt("has an unknown activation", name + " has activation code " + std::to_string(act) +
                                               " (1 is ReLU, 2 is tanh).");
    }
    layer.activation = static_cast<Activation>(act);
    if (layer.in_channels != previous) {
      corrupt("has inconsistent layer shapes", name + " takes " + std::to_string(layer.in_channels) +
                                                   " channels but receives " + std::to_string(previous) + ".");
    }
    previous = layer.out_channels;
    const std::size_t weights = static_cast<std::size_t>(layer.in_channels) * layer.out_channels * kk;
    header.floats(layer.weight, weights, name + " weights");
    header.floats(layer.scale, static_cast<std::size_t>(layer.out_channels), name + " scales");
    header.floats(layer.shift, static_cast<std::size_t>(layer.out_channels), name + " shifts");
    g.layers.push_back(std::move(layer));
  }
  if (previous != 1) {
    corrupt("has inconsistent layer shapes",
            "The last layer gives " + std::to_string(previous) + " channels; a road image has 1.");
  }
  const std::size_t body = sizeof kMagic + header.offset();
  std::uint32_t stored = header.u32("the CRC-32");
  if (header.left() != 0) {
    corrupt("has trailing bytes", std::to_string(header.left()) + " bytes follow the CRC-32 at offset " +
                                      std::to_string(body) + ".");
  }
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), data, static_cast<uInt>(body));
  if (static_cast<std::uint32_t>(crc) != stored) {
    corrupt("is corrupt (CRC-32 mismatch)", "The stored CRC-32 does not match the " + std::to_string(body) +
                                                " bytes before it: the file was altered or damaged.");
  }
  return g;
}

std::vector<float> noise(std::uint64_t seed, int channels, int height, int width) {
  std::vector<float> out(static_cast<std::size_t>(channels) * height * width);
  const std::uint64_t key = mix(seed);
  std::size_t i = 0;
  for (std::uint64_t c = 0; c < static_cast<std::uint64_t>(channels); ++c) {
    for (std::uint64_t y = 0; y < static_cast<std::uint64_t>(height); ++y) {
      for (std::uint64_t x = 0; x < static_cast<std::uint64_t>(width); ++x) {
        const std::uint64_t k = mix(key ^ (c << 42 | y << 21 | x)) >> 40;
        out[i++] = static_cast<float>(2.0 * static_cast<double>(k) / 16777216.0 - 1.0);
      }
    }
  }
  return out;
}

Image forward(const Generator& g, const std::vector<float>& z, int noise_height, int noise_width) {
  if (z.size() != static_cast<std::size_t>(g.noise_channels) * noise_height * noise_width) {
    throw Error(ErrorKind::internal, "noise tensor size does not match the generator");
  }
  using Matrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic>;
  using ConstMap = Eigen::Map<const Matrix, 0, Eigen::OuterStride<>>;
  std::vector<float> x = z;
  long h = noise_height, w = noise_width;
  const int k = g.kernel, s = g.stride, p = g.padding;
  Matrix products;
  for (const Layer& layer : g.layers) {
    poll_interrupts();
    const long oh = (h - 1) * s - 2L * p + k, ow = (w - 1) * s - 2L * p + k;
    if (oh <= 0 || ow <= 0) throw_invalid_argument("noise tensor too small for this generator");
    const int cout = layer.out_channels;
    std::vector<float> y(static_cast<std::size_t>(cout) * oh * ow, 0.0f);
    // Transposed convolution as one matrix product per block of input rows: every input pixel's
    // channels times W (cout*k*k x cin) give that pixel's contribution to a k x k window of each
    // output channel, scattered into y with stride s (col2im).
    const long r = static_cast<long>(cout) * k * k;
    const Eigen::Map<const Matrix> weight(layer.weight.data(), r, layer.in_channels);
    const long rows = std::max<long>(1, std::min<long>(h, static_cast<long>(kBlockFloats) / (r * w)));
    products.resize(r, rows * w);
    for (long y0 = 0; y0 < h; y0 += rows) {
      const long n = std::min(rows, h - y0) * w;
      const ConstMap block(x.data() + y0 * w, n, layer.in_channels, Eigen::OuterStride<>(h * w));
      products.leftCols(n).noalias() = weight * block.transpose();
      for (long pix = 0; pix < n; ++pix) {
        const long iy = y0 + pix / w, ix = pix % w;
        const float* col = products.data() + pix * r;
        for (int co = 0; co < cout; ++co) {
          float* plane = y.data() + static_cast<std::size_t>(co) * oh * ow;
          for (int ky = 0; ky < k; ++ky) {
            const long oy = iy * s - p + ky;
            if (oy < 0 || oy >= oh) continue;
            float* row = plane + oy * ow;
            const float* c = col + (static_cast<long>(co) * k + ky) * k;
            for (int kx = 0; kx < k; ++kx) {
              const long ox = ix * s - p + kx;
              if (ox >= 0 && ox < ow) row[ox] += c[kx];
            }
          }
        }
      }
      poll_interrupts();
    }
    const std::size_t plane = static_cast<std::size_t>(oh) * ow;
    for (int co = 0; co < cout; ++co) {
      float* v = y.data() + co * plane;
      const float a = layer.scale[co], b = layer.shift[co];
      if (layer.activation == Activation::relu) {
        for (std::size_t i = 0; i < plane; ++i) v[i] = std::max(0.0f, a * v[i] + b);
      } else {
        for (std::size_t i = 0; i < plane; ++i) v[i] = std::tanh(a * v[i] + b);
      }
    }
    x = std::move(y);
    h = oh;
    w = ow;
  }
  Image image;
  image.width = static_cast<int>(w);
  image.height = static_cast<int>(h);
  image.pixels = std::move(x);
  return image;
}

Image sample(const Generator& g, std::uint64_t seed, int width, int height) {
  if (width < 1 || width > kMaxSide) {
    throw_invalid_argument("width_px must be between 1 and " + std::to_string(kMaxSide),
                           "width_px is " + std::to_string(width) + ".");
  }
  if (height < 1 || height > kMaxSide) {
    throw_invalid_argument("height_px must be between 1 and " + std::to_string(kMaxSide),
                           "height_px is " + std::to_string(height) + ".");
  }
  const int nh = g.noise_side(height), nw = g.noise_side(width);
  long h = nh, w = nw;
  std::size_t largest = static_cast<std::size_t>(g.noise_channels) * nh * nw;
  for (const Layer& layer : g.layers) {
    h = (h - 1) * g.stride - 2L * g.padding + g.kernel;
    w = (w - 1) * g.stride - 2L * g.padding + g.kernel;
    largest = std::max(largest, static_cast<std::size_t>(layer.out_channels) * h * w);
  }
  if (largest > kMaxActivationFloats) {
    throw_invalid_argument("sample too large for this generator",
                           "A " + std::to_string(width) + " x " + std::to_string(height) +
                               " px sample needs an activation of " + std::to_string(largest) +
                               " floats; the limit is " + std::to_string(kMaxActivationFloats) + ".",
                           "Sample smaller tiles.");
  }
  const Image full = forward(g, noise(seed, g.noise_channels, nh, nw), nh, nw);
  Image out;
  out.width = width;
  out.height = height;
  out.pixels.resize(static_cast<std::size_t>(width) * height);
  for (int yy = 0; yy < height; ++yy) {
    std::copy_n(full.pixels.begin() + static_cast<long>(yy) * full.width, width,
                out.pixels.begin() + static_cast<long>(yy) * width);
  }
  return out;
}

std::vector<std::uint8_t> raster_wkb(const Image& image, bool raw, double threshold, double upper_left_x,
                                     double upper_left_y, double pixel_size, std::int32_t srid) {
  if (image.width < 1 || image.height < 1 || image.width > 65535 || image.height > 65535) {
    throw Error(ErrorKind::internal, "raster side out of the WKB range");
  }
  std::vector<std::uint8_t> out;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  out.reserve(64 + pixels * (raw ? 4 : 1));
  // PostGIS raster WKB (raster/doc/RFC2-WellKnownBinaryFormat): header, then one band.
  put<std::uint8_t>(out, 1);  // little-endian
  put<std::uint16_t>(out, 0);  // WKB raster version
  put<std::uint16_t>(out, 1);  // bands
  put<double>(out, pixel_size);
  put<double>(out, -pixel_size);  // rows go south
  put<double>(out, upper_left_x);
  put<double>(out, upper_left_y);
  put<double>(out, 0.0);  // skew x
  put<double>(out, 0.0);  // skew y
  put<std::int32_t>(out, srid);
  put<std::uint16_t>(out, static_cast<std::uint16_t>(image.width));
  put<std::uint16_t>(out, static_cast<std::uint16_t>(image.height));
  if (raw) {
    put<std::uint8_t>(out, 10);  // 32BF, no nodata flag
    put<float>(out, 0.0f);       // nodata value slot (always present in WKB)
    put_bytes(out, image.pixels.data(), pixels * sizeof(float));
  } else {
    put<std::uint8_t>(out, 4);  // 8BUI, no nodata flag
    put<std::uint8_t>(out, 0);
    for (float v : image.pixels) out.push_back(v > threshold ? 1 : 0);
  }
  return out;
}

}  // namespace streetgen::core::gan
