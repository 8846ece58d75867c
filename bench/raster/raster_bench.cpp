// Core time of raster -> graph on one core, per phase, on a WKB raster file (ST_AsBinary of a
// road raster): read + threshold, erosion and dilation, Zhang-Suen thinning, graph and
// post-processing. Prints one JSON object of medians in seconds (bench/raster/run.sh reads it).
//
//   streetgen_raster_bench FILE [RUNS] [THRESHOLD]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/raster/binary_image.hpp"
#include "core/raster/raster_to_network.hpp"
#include "core/raster/wkb_raster.hpp"

using namespace streetgen::core;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE [RUNS] [THRESHOLD]\n", argv[0]);
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  const double threshold = argc > 3 ? std::stod(argv[3]) : 0.5;
  try {
    GeosContext geos;
    RasterNetworkParams params;
    std::vector<double> t_read, t_morph, t_thin, t_graph, t_total;
    RasterNetwork net, whole;
    for (int r = 0; r < runs; ++r) {
      auto t0 = Clock::now();
      RoadRaster raster = read_wkb_raster(bytes.data(), bytes.size(), threshold);
      t_read.push_back(seconds_since(t0));
      auto t1 = Clock::now();
      BinaryImage image = raster.mask;
      erode(image, params.erode);
      dilate(image, params.dilate);
      t_morph.push_back(seconds_since(t1));
      const BinaryImage cleaned = image;
      auto t2 = Clock::now();
      zhang_suen_thin(image);
      t_thin.push_back(seconds_since(t2));
      auto t3 = Clock::now();
      net = skeleton_to_network(geos, image, cleaned, raster.transform, params);
      t_graph.push_back(seconds_since(t3));
      // The same work through the one entry point the SQL function calls.
      auto t4 = Clock::now();
      whole = raster_to_network(geos, read_wkb_raster(bytes.data(), bytes.size(), threshold), params);
      t_total.push_back(seconds_since(t4));
      if (whole.edges.size() != net.edges.size()) throw std::runtime_error("phases and entry point disagree");
    }
    std::printf(
        "{\"read\": %.6f, \"morphology\": %.6f, \"thinning\": %.6f, \"graph\": %.6f, \"total\": %.6f, "
        "\"edges\": %zu, \"nodes\": %zu, \"skeleton_pixels\": %zu, \"raw_edges\": %zu, \"small_faces\": %zu, "
        "\"dead_ends_pruned\": %zu, \"junctions_merged\": %zu, \"road_pixels\": %zu, \"cleaned_pixels\": %zu}\n",
        median(t_read), median(t_morph), median(t_thin), median(t_graph), median(t_total), net.edges.size(),
        net.node_count, net.stats.skeleton_pixels, net.stats.raw_edges, net.stats.small_faces,
        net.stats.dead_ends_pruned, net.stats.junctions_merged, whole.stats.road_pixels, whole.stats.cleaned_pixels);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "raster bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
