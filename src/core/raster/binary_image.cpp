#include "core/raster/binary_image.hpp"

#include "core/interrupts.hpp"

namespace streetgen::core {

std::size_t BinaryImage::count() const {
  std::size_t n = 0;
  for (std::uint8_t p : pixels) n += p != 0;
  return n;
}

namespace {

// One cross step: erosion keeps a road pixel whose 4-neighbours are all road; dilation sets a
// pixel with a road 4-neighbour. Reads a copy so the step is parallel, as the definition says.
void cross_step(BinaryImage& image, bool erosion) {
  const BinaryImage in = image;
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      std::uint8_t self = in.at(r, c);
      if (erosion ? self == 0 : self != 0) continue;
      int n = in.at(r - 1, c) + in.at(r + 1, c) + in.at(r, c - 1) + in.at(r, c + 1);
      image.set(r, c, erosion ? n == 4 : n > 0);
    }
  }
}

}  // namespace

void erode(BinaryImage& image, int steps) {
  for (int i = 0; i < steps; ++i) {
    poll_interrupts();
    cross_step(image, true);
  }
}

void dilate(BinaryImage& image, int steps) {
  for (int i = 0; i < steps; ++i) {
    poll_interrupts();
    cross_step(image, false);
  }
}

void zhang_suen_thin(BinaryImage& image) {
  // Only road pixels can change, so each pass visits the list of the remaining ones instead of
  // the whole image (roads cover a fraction of it and the list shrinks every pass).
  std::vector<int> live;
  for (int i = 0; i < static_cast<int>(image.pixels.size()); ++i) {
    if (image.pixels[i] != 0) live.push_back(i);
  }
  std::vector<int> remove;
  bool changed = true;
  while (changed) {
    changed = false;
    for (int sub = 0; sub < 2; ++sub) {
      poll_interrupts();
      remove.clear();
      for (int i : live) {
        int r = i / image.width, c = i % image.width;
        // Neighbours P2..P9 clockwise from north.
        int p[8] = {image.at(r - 1, c), image.at(r - 1, c + 1), image.at(r, c + 1), image.at(r + 1, c + 1),
                    image.at(r + 1, c), image.at(r + 1, c - 1), image.at(r, c - 1), image.at(r - 1, c - 1)};
        int b = 0, a = 0;
        for (int k = 0; k < 8; ++k) {
          b += p[k];
          a += p[k] == 0 && p[(k + 1) % 8] == 1;
        }
        if (b < 2 || b > 6 || a != 1) continue;
        // First sub-iteration: P2*P4*P6 = 0 and P4*P6*P8 = 0; second: P2*P4*P8 = 0 and P2*P6*P8 = 0.
        bool ok = sub == 0 ? (p[0] * p[2] * p[4] == 0 && p[2] * p[4] * p[6] == 0)
                           : (p[0] * p[2] * p[6] == 0 && p[0] * p[4] * p[6] == 0);
        if (ok) remove.push_back(i);
      }
      for (int i : remove) image.pixels[i] = 0;
      if (!remove.empty()) {
        changed = true;
        std::size_t kept = 0;
        for (int i : live) {
          if (image.pixels[i] != 0) live[kept++] = i;
        }
        live.resize(kept);
      }
    }
  }
}

}  // namespace streetgen::core
