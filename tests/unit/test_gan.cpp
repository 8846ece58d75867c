#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "core/gan/generator.hpp"

using namespace streetgen::core;
using namespace streetgen::core::gan;

namespace {

// Writes the generator file format independently of the parser (the spec of sgan.py
// write_generator), so the tests can build valid and broken files.
struct FileWriter {
  std::vector<std::uint8_t> bytes;
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f32(float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    u32(v);
  }
  void f64(double d) {
    std::uint64_t v;
    std::memcpy(&v, &d, 8);
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void crc() { u32(static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes.data(), bytes.size()))); }
};

struct Spec {
  int noise_channels = 3;
  std::vector<int> widths = {4, 2, 1};  // output channels per layer
  int kernel = 5, stride = 2, padding = 2;
  std::uint32_t version = 1;
  float weight_value = NAN;  // NAN: pseudo-random weights
};

std::vector<std::uint8_t> make_file(const Spec& spec, std::uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  FileWriter w;
  const char magic[8] = {'S', 'G', 'A', 'N', 'G', 'E', 'N', '\0'};
  w.bytes.assign(magic, magic + 8);
  w.u32(spec.version);
  w.u32(static_cast<std::uint32_t>(spec.noise_channels));
  w.u32(static_cast<std::uint32_t>(spec.widths.size()));
  w.u32(static_cast<std::uint32_t>(spec.kernel));
  w.u32(static_cast<std::uint32_t>(spec.stride));
  w.u32(static_cast<std::uint32_t>(spec.padding));
  w.f64(3.0);
  int in = spec.noise_channels;
  for (std::size_t l = 0; l < spec.widths.size(); ++l) {
    const int out = spec.widths[l];
    w.u32(static_cast<std::uint32_t>(in));
    w.u32(static_cast<std::uint32_t>(out));
    w.u32(l + 1 == spec.widths.size() ? 2 : 1);
    for (int i = 0; i < in * out * spec.kernel * spec.kernel; ++i) {
      w.f32(std::isnan(spec.weight_value) ? u(rng) : spec.weight_value);
    }
    for (int i = 0; i < out; ++i) w.f32(1.0f + u(rng));
    for (int i = 0; i < out; ++i) w.f32(u(rng));
    in = out;
  }
  w.crc();
  return w.bytes;
}

// Expects parse_generator to fail with bad_data and a message containing `part`.
void expect_corrupt(const std::vector<std::uint8_t>& file, const std::string& part) {
  try {
    parse_generator(file.data(), file.size());
    ADD_FAILURE() << "parsed a broken file, expected: " << part;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::bad_data) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what() << " / " << e.detail();
  }
}

// The transposed convolution straight from its definition, in double precision.
std::vector<double> reference_forward(const Generator& g, const std::vector<float>& z, int h, int w, int* oh_out,
                                      int* ow_out) {
  std::vector<double> x(z.begin(), z.end());
  int cin = g.noise_channels;
  const int k = g.kernel, s = g.stride, p = g.padding;
  for (const Layer& layer : g.layers) {
    const int oh = (h - 1) * s - 2 * p + k, ow = (w - 1) * s - 2 * p + k, cout = layer.out_channels;
    std::vector<double> y(static_cast<std::size_t>(cout) * oh * ow, 0.0);
    for (int ci = 0; ci < cin; ++ci)
      for (int iy = 0; iy < h; ++iy)
        for (int ix = 0; ix < w; ++ix)
          for (int co = 0; co < cout; ++co)
            for (int ky = 0; ky < k; ++ky)
              for (int kx = 0; kx < k; ++kx) {
                const int oy = iy * s - p + ky, ox = ix * s - p + kx;
                if (oy < 0 || oy >= oh || ox < 0 || ox >= ow) continue;
                y[(static_cast<std::size_t>(co) * oh + oy) * ow + ox] +=
                    x[(static_cast<std::size_t>(ci) * h + iy) * w + ix] *
                    layer.weight[((static_cast<std::size_t>(ci) * cout + co) * k + ky) * k + kx];
              }
    for (int co = 0; co < cout; ++co)
      for (int i = 0; i < oh * ow; ++i) {
        double& v = y[static_cast<std::size_t>(co) * oh * ow + i];
        v = layer.scale[co] * v + layer.shift[co];
        v = layer.activation == Activation::relu ? std::max(0.0, v) : std::tanh(v);
      }
    x = std::move(y);
    h = oh;
    w = ow;
    cin = cout;
  }
  *oh_out = h;
  *ow_out = w;
  return x;
}

}  // namespace

TEST(Gan, ParsesAValidFile) {
  const auto file = make_file({});
  const Generator g = parse_generator(file.data(), file.size());
  EXPECT_EQ(g.noise_channels, 3);
  ASSERT_EQ(g.layers.size(), 3u);
  EXPECT_EQ(g.layers[0].in_channels, 3);
  EXPECT_EQ(g.layers[2].out_channels, 1);
  EXPECT_EQ(g.layers[2].activation, Activation::tanh);
  EXPECT_DOUBLE_EQ(g.metres_per_pixel, 3.0);
  EXPECT_EQ(g.parameter_count(), (3u * 4 + 4 * 2 + 2 * 1) * 25 + 2 * (4 + 2 + 1));
  // 2n - 1 per layer: the paper's 25 x 25 noise gives 769 px with five layers; here three.
  EXPECT_EQ(g.output_side(25), 193);
  EXPECT_EQ(g.noise_side(193), 25);
  EXPECT_EQ(g.noise_side(194), 26);
  EXPECT_EQ(g.noise_side(1), 1);
}

TEST(Gan, EveryTruncationIsRejected) {
  const auto file = make_file({});
  for (std::size_t n = 0; n < file.size(); ++n) {
    std::vector<std::uint8_t> cut(file.begin(), file.begin() + static_cast<long>(n));
    expect_corrupt(cut, "truncated");
  }
}

TEST(Gan, RejectsBrokenFiles) {
  auto file = make_file({});
  auto bad = file;
  bad[0] = 'X';
  expect_corrupt(bad, "not a streetgen generator file");
  Spec v2;
  v2.version = 2;
  expect_corrupt(make_file(v2), "unsupported format version");
  bad = file;
  bad.push_back(0);
  expect_corrupt(bad, "trailing bytes");
  bad = file;
  bad[100] ^= 0x01;  // a weight bit flips
  expect_corrupt(bad, "CRC-32 mismatch");
  Spec two_channels;
  two_channels.widths = {4, 2};
  expect_corrupt(make_file(two_channels), "inconsistent layer shapes");
  Spec odd_stride;
  odd_stride.stride = 1;
  expect_corrupt(make_file(odd_stride), "invalid stride");
  Spec infinite_weights;
  infinite_weights.widths = {1};
  infinite_weights.weight_value = std::numeric_limits<float>::infinity();
  expect_corrupt(make_file(infinite_weights), "non-finite");
  // Layer 2 claims 5 input channels but layer 1 gives 4: rewrite its header word in place.
  bad = file;
  const std::size_t layer2 = 8 + 24 + 8 + 12 + 4 * (3 * 4 * 25 + 4 + 4);
  ASSERT_EQ(bad[layer2], 4);
  bad[layer2] = 5;
  expect_corrupt(bad, "inconsistent layer shapes");
}

TEST(Gan, NoiseMatchesThePythonDefinition) {
  // Values printed by tools/sgan/sgan.py noise(); the SQL sampler and the trainer's export agree
  // through this definition.
  const auto z = noise(42, 3, 4, 5);
  EXPECT_FLOAT_EQ(z[0], -0.31341624f);
  EXPECT_FLOAT_EQ(z[(2 * 4 + 3) * 5 + 4], 0.23163188f);
  EXPECT_FLOAT_EQ(z[(1 * 4 + 2) * 5 + 3], 0.9582789f);
  const auto negative = noise(static_cast<std::uint64_t>(std::int64_t{-7}), 1, 1, 2);
  EXPECT_FLOAT_EQ(negative[0], -0.83368635f);
  EXPECT_FLOAT_EQ(negative[1], 0.99567354f);
  // An element depends on its position only: a bigger tensor extends a smaller one.
  const auto big = noise(42, 3, 9, 11);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) EXPECT_EQ(z[(c * 4 + y) * 5 + x], big[(c * 9 + y) * 11 + x]);
  double sum = 0;
  for (float v : big) {
    ASSERT_GE(v, -1.0f);
    ASSERT_LT(v, 1.0f);
    sum += v;
  }
  EXPECT_LT(std::abs(sum / static_cast<double>(big.size())), 0.1);
  EXPECT_NE(noise(43, 3, 4, 5), z);
}

TEST(Gan, ForwardMatchesTheDefinition) {
  // 16 output channels on a 120 x 120 input make the first layer's products larger than one
  // block, so the row blocking is exercised too.
  Spec spec;
  spec.noise_channels = 2;
  spec.widths = {16, 1};
  const auto file = make_file(spec);
  const Generator g = parse_generator(file.data(), file.size());
  const int h = 120, w = 117;
  const auto z = noise(5, 2, h, w);
  const Image image = forward(g, z, h, w);
  int oh = 0, ow = 0;
  const auto expected = reference_forward(g, z, h, w, &oh, &ow);
  ASSERT_EQ(image.height, oh);
  ASSERT_EQ(image.width, ow);
  double worst = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) worst = std::max(worst, std::abs(expected[i] - image.pixels[i]));
  EXPECT_LT(worst, 1e-5);
  // Stride 3, kernel 4, padding 1: the arithmetic is not tied to the shipped shape.
  Spec other;
  other.kernel = 4;
  other.stride = 3;
  other.padding = 1;
  const auto file2 = make_file(other);
  const Generator g2 = parse_generator(file2.data(), file2.size());
  const auto z2 = noise(9, 3, 6, 7);
  const Image image2 = forward(g2, z2, 6, 7);
  const auto expected2 = reference_forward(g2, z2, 6, 7, &oh, &ow);
  ASSERT_EQ(image2.height, oh);
  ASSERT_EQ(image2.width, ow);
  worst = 0;
  for (std::size_t i = 0; i < expected2.size(); ++i) worst = std::max(worst, std::abs(expected2[i] - image2.pixels[i]));
  EXPECT_LT(worst, 1e-5);
}

TEST(Gan, SampleSizesSeedsAndLimits) {
  const auto file = make_file({});
  const Generator g = parse_generator(file.data(), file.size());
  const Image a = sample(g, 1, 50, 31);
  EXPECT_EQ(a.width, 50);
  EXPECT_EQ(a.height, 31);
  EXPECT_EQ(a.pixels.size(), 50u * 31u);
  EXPECT_EQ(sample(g, 1, 50, 31).pixels, a.pixels);
  EXPECT_NE(sample(g, 2, 50, 31).pixels, a.pixels);
  // A larger sample of the same seed extends a smaller one away from its right/bottom border
  // (there the smaller one lacks the noise beyond its edge).
  const Image big = sample(g, 1, 120, 90);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 35; ++x) EXPECT_EQ(a.pixels[y * 50 + x], big.pixels[y * 120 + x]) << x << "," << y;
  EXPECT_EQ(sample(g, 1, 1, 1).pixels.size(), 1u);
  for (auto [w, h] : {std::pair{0, 10}, {10, 0}, {-5, 10}, {kMaxSide + 1, 10}, {10, kMaxSide + 1}}) {
    try {
      sample(g, 1, w, h);
      ADD_FAILURE() << w << " x " << h << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
      EXPECT_NE(std::string(e.what()).find(w < 1 || w > kMaxSide ? "width_px" : "height_px"), std::string::npos);
    }
  }
}

TEST(Gan, RasterWkb) {
  Image image;
  image.width = 3;
  image.height = 2;
  image.pixels = {-0.5f, 0.25f, 0.0f, 1.0f, -1.0f, 0.01f};
  const auto wkb = raster_wkb(image, false, 0.0, 10.0, 20.0, 3.0, 3857);
  ASSERT_EQ(wkb.size(), 1u + 2 + 2 + 6 * 8 + 4 + 2 + 2 + 1 + 1 + 6);
  EXPECT_EQ(wkb[0], 1);
  double scale_y;
  std::memcpy(&scale_y, wkb.data() + 5 + 8, 8);
  EXPECT_EQ(scale_y, -3.0);
  std::int32_t srid;
  std::memcpy(&srid, wkb.data() + 5 + 48, 4);
  EXPECT_EQ(srid, 3857);
  EXPECT_EQ(wkb[61], 4);  // 8BUI
  EXPECT_EQ(std::vector<std::uint8_t>(wkb.end() - 6, wkb.end()), (std::vector<std::uint8_t>{0, 1, 0, 1, 0, 1}));
  const auto raw = raster_wkb(image, true, 0.0, 0.0, 0.0, 3.0, 0);
  EXPECT_EQ(raw[61], 10);  // 32BF
  float last;
  std::memcpy(&last, raw.data() + raw.size() - 4, 4);
  EXPECT_EQ(last, 0.01f);
}
