// Road raster -> street graph, StreetGAN's post-processing (Hartmann et al. 2017, section 4.4):
// threshold, erosion, dilation, Zhang-Suen thinning, a graph from the skeleton's 8-neighbourhood,
// removal of tiny artefact blocks, gap closing (not in the paper: a generator's roads break off),
// dead-end pruning, chain smoothing and Douglas-Peucker simplification. Edges come out in the
// raster's CRS, ready for a model's axis table.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geos_context.hpp"
#include "core/raster/binary_image.hpp"
#include "core/raster/wkb_raster.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct RasterNetworkParams {
  int erode = 1;                     // erosion steps (paper: 1)
  int dilate = 5;                    // dilation steps after the erosion (paper: 5)
  double min_block_area = 100.0;     // m²: faces smaller than this lose their longest edge
  double max_gap = 60.0;             // m: a dead end is joined to a road at most this far ahead (0: never)
  double gap_angle = 30.0;           // degrees: how far the join may turn from the dead end's direction
  double min_dead_end_length = 25.0; // m: shorter dead-end chains are removed (paper: 25 m)
  int smooth_iterations = 5;         // steps of (1/4, 1/2, 1/4) averaging (paper: 5)
  double simplify_tolerance = 3.0;   // m, Douglas-Peucker (paper: 3 m); 0 keeps every vertex
};

struct RasterEdge {
  std::int64_t id = 0;
  std::int64_t from_node = 0;
  std::int64_t to_node = 0;
  Polyline line;  // world coordinates; starts at from_node, ends at to_node
};

struct RasterNetworkStats {
  std::size_t road_pixels = 0;       // after threshold
  std::size_t cleaned_pixels = 0;    // after erosion and dilation
  std::size_t skeleton_pixels = 0;
  std::size_t raw_edges = 0;         // chains of the skeleton graph
  std::size_t small_faces = 0;       // artefact blocks removed
  std::size_t gaps_closed = 0;       // dead ends joined to the road ahead of them
  std::size_t dead_ends_pruned = 0;
  std::size_t junctions_merged = 0;  // short links between two junctions contracted
};

struct RasterNetwork {
  std::vector<RasterEdge> edges;
  std::size_t node_count = 0;
  RasterNetworkStats stats;
};

// Throws invalid_argument for negative parameters and for a mask without background (an
// all-road raster has no streets to find: usually a wrong threshold).
RasterNetwork raster_to_network(GeosContext& geos, const RoadRaster& raster, const RasterNetworkParams& params);

// The graph steps alone: `skeleton` is the thinned mask, `cleaned` the mask before thinning (its
// road width decides which junction links are contracted and where dead ends stop).
RasterNetwork skeleton_to_network(GeosContext& geos, const BinaryImage& skeleton, const BinaryImage& cleaned,
                                  const GeoTransform& transform, const RasterNetworkParams& params);

}  // namespace streetgen::core
