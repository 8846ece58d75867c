// Binary road masks and the pixel operations of StreetGAN's post-processing (Hartmann et al.,
// section 4.4): erosion and dilation with a 3 x 3 cross, and Zhang-Suen thinning.
//
// Hand-written on purpose: OpenCV has all three (cv::erode/dilate, cv::ximgproc::thinning in
// libopencv-contrib-dev), but on Debian 12 that package pulls 95 packages (VTK, Qt, codecs) into
// every backend that loads streetgen, and it would run on a cv::Mat copy of the mask. The three
// operations are about 100 lines here, work in place on the mask we already hold, and are
// checked by the unit tests against hand-computed results.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streetgen::core {

// Row-major, row 0 first; 1 = road, 0 = background. Pixels outside the image are background.
// Pixel indices are int throughout src/core/raster: read_wkb_raster refuses more than 1e8 pixels.
struct BinaryImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;

  BinaryImage() = default;
  BinaryImage(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, 0) {}
  std::uint8_t at(int row, int col) const {
    if (row < 0 || col < 0 || row >= height || col >= width) return 0;
    return pixels[static_cast<std::size_t>(row) * width + col];
  }
  void set(int row, int col, std::uint8_t v) { pixels[static_cast<std::size_t>(row) * width + col] = v; }
  std::size_t count() const;
};

// `steps` erosions (a pixel stays only if its four 4-neighbours are road; outside the raster
// counts as road here, so roads are not eaten where they leave it) or dilations (a pixel becomes
// road if one of its 4-neighbours is), the paper's 3 x 3 cross structuring element.
void erode(BinaryImage& image, int steps);
void dilate(BinaryImage& image, int steps);

// Zhang & Suen (1984), "A fast parallel algorithm for thinning digital patterns", both
// sub-iterations until nothing changes. Polls interrupts between passes.
void zhang_suen_thin(BinaryImage& image);

}  // namespace streetgen::core
