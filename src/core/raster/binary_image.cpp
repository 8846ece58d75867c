#include "core/raster/binary_image.hpp"

#include <algorithm>

#include "core/interrupts.hpp"

namespace streetgen::core {

std::size_t BinaryImage::count() const {
  std::size_t n = 0;
  for (std::uint8_t p : pixels) n += p != 0;
  return n;
}

namespace {

// `steps` cross steps on a padded copy (a frame, so no bounds checks), ping-ponging between two
// buffers: each step reads the previous one only, as the definition says. Erosion keeps a road
// pixel whose 4-neighbours are all road; dilation sets a pixel with a road 4-neighbour. For
// erosion the frame is road, so a road leaving the raster is not eaten at the raster's edge (as
// scipy/scikit-image's binary_erosion does); for dilation it is background.
void cross_steps(BinaryImage& image, int steps, bool erosion) {
  if (steps <= 0 || image.pixels.empty()) return;
  const int w = image.width + 2, h = image.height + 2;
  std::vector<std::uint8_t> a(static_cast<std::size_t>(w) * h, erosion ? 1 : 0);
  for (int r = 0; r < image.height; ++r) {
    std::copy(image.pixels.begin() + static_cast<std::size_t>(r) * image.width,
              image.pixels.begin() + static_cast<std::size_t>(r + 1) * image.width, a.begin() + (r + 1) * w + 1);
  }
  std::vector<std::uint8_t> b = a;  // frame cells are never written
  for (int step = 0; step < steps; ++step) {
    poll_interrupts();
    for (int r = 1; r < h - 1; ++r) {
      const int row = r * w;
      for (int i = row + 1; i < row + w - 1; ++i) {
        const int n = a[i - w] + a[i + w] + a[i - 1] + a[i + 1];
        b[i] = erosion ? (a[i] && n == 4) : (a[i] || n > 0);
      }
    }
    a.swap(b);
  }
  for (int r = 0; r < image.height; ++r) {
    std::copy(a.begin() + (r + 1) * w + 1, a.begin() + (r + 1) * w + 1 + image.width,
              image.pixels.begin() + static_cast<std::size_t>(r) * image.width);
  }
}

}  // namespace

void erode(BinaryImage& image, int steps) { cross_steps(image, steps, true); }

void dilate(BinaryImage& image, int steps) { cross_steps(image, steps, false); }

namespace {

// Zhang-Suen's deletion test depends only on the 8 neighbours, so it is tabulated once per
// sub-iteration: bit k of the index is neighbour P(k+2), clockwise from north.
struct ThinningTables {
  bool remove[2][256];
  ThinningTables() {
    for (int m = 0; m < 256; ++m) {
      int p[8];
      for (int k = 0; k < 8; ++k) p[k] = (m >> k) & 1;
      int b = 0, a = 0;
      for (int k = 0; k < 8; ++k) {
        b += p[k];
        a += p[k] == 0 && p[(k + 1) % 8] == 1;
      }
      bool shape = b >= 2 && b <= 6 && a == 1;
      // First sub-iteration: P2*P4*P6 = 0 and P4*P6*P8 = 0; second: P2*P4*P8 = 0 and P2*P6*P8 = 0.
      remove[0][m] = shape && p[0] * p[2] * p[4] == 0 && p[2] * p[4] * p[6] == 0;
      remove[1][m] = shape && p[0] * p[2] * p[6] == 0 && p[0] * p[4] * p[6] == 0;
    }
  }
};

}  // namespace

void zhang_suen_thin(BinaryImage& image) {
  static const ThinningTables tables;
  // A padded copy (one background pixel all round) so that neighbours need no bounds checks.
  const int w = image.width + 2, h = image.height + 2;
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h, 0);
  for (int r = 0; r < image.height; ++r) {
    std::copy(image.pixels.begin() + static_cast<std::size_t>(r) * image.width,
              image.pixels.begin() + static_cast<std::size_t>(r + 1) * image.width, px.begin() + (r + 1) * w + 1);
  }
  const int offset[8] = {-w, -w + 1, 1, w + 1, w, w - 1, -1, -w - 1};
  auto pattern = [&](int i) {
    int m = 0;
    for (int k = 0; k < 8; ++k) m |= (px[i + offset[k]] != 0) << k;
    return m;
  };
  // Only pixels with a background neighbour can go (the test needs at most 6 road neighbours),
  // so each pass visits that border list, which grows by the neighbours of what was removed,
  // instead of every road pixel: most of a wide road is tested only once it is reached.
  std::vector<int> border;
  std::vector<std::uint8_t> listed(px.size(), 0);
  for (int i = w; i < w * (h - 1); ++i) {
    if (px[i] && pattern(i) != 255) {
      border.push_back(i);
      listed[i] = 1;
    }
  }
  std::vector<int> remove;
  bool changed = true;
  while (changed) {
    changed = false;
    for (int sub = 0; sub < 2; ++sub) {
      poll_interrupts();
      remove.clear();
      for (int i : border) {
        if (tables.remove[sub][pattern(i)]) remove.push_back(i);
      }
      if (remove.empty()) continue;
      changed = true;
      for (int i : remove) px[i] = 0;
      std::size_t kept = 0;
      for (int i : border) {
        if (px[i]) border[kept++] = i;
      }
      border.resize(kept);
      for (int i : remove) {
        for (int k = 0; k < 8; ++k) {
          int j = i + offset[k];
          if (px[j] && !listed[j]) {
            listed[j] = 1;
            border.push_back(j);
          }
        }
      }
    }
  }
  for (int r = 0; r < image.height; ++r) {
    std::copy(px.begin() + (r + 1) * w + 1, px.begin() + (r + 1) * w + 1 + image.width,
              image.pixels.begin() + static_cast<std::size_t>(r) * image.width);
  }
}

}  // namespace streetgen::core
