// Example-based growth of a road network (Yu & Steed, "Example-based Road Network Synthesis"):
// from unfinished nodes, find example nodes whose incident edge angles match under a rotation
// (node matching), choose the one whose surroundings look most like the output's surroundings
// (neighbourhood matching by a weighted line-segment Hausdorff distance), copy its incident edges
// as proposals and adapt them to local constraints (legal region, obstacles, snapping, no
// crossing, dead ends stay dead ends).
//
// The example is read as the paper's planar graph: every polyline is cut at its vertices into
// straight segments, so nodes are junctions, dead ends and shape points. Output edges are
// straight segments between output nodes in the same way.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geos_context.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct ExampleEdge {
  Polyline line;
  std::string road_class;  // levels: with match_levels, only edges of one class match each other
  std::int64_t id = 0;     // the example row it came from (traceability: GrownEdge::example_id)
};

struct GrowParams {
  double epsilon = 30.0;       // degrees: largest angle between a matched pair of incident edges
  double radius = 0.0;         // metres: neighbourhood radius r; 0: 3 x mean example segment length
  bool rotation = true;        // false: θ = 0 (grids keep their orientation)
  std::uint64_t seed = 0;      // the only source of randomness
  std::size_t max_edges = 10000;
  bool match_levels = true;    // match incident edges of the same road class only
  double snap = 0.0;           // metres: snap distance for free ends; 0: 0.45 x mean example segment length
  double min_angle = 20.0;     // degrees: smallest angle between two edges at a node
  std::size_t candidates = 16; // node matches compared by neighbourhood matching per step
};

struct GrowInput {
  std::vector<ExampleEdge> example;
  const GEOSGeometry* region = nullptr;  // Polygon or MultiPolygon, valid, non-empty
  std::vector<const GEOSGeometry*> obstacles;  // polygonal; may be empty
  std::vector<Point> seeds;              // start nodes; inside the region, outside obstacles, or on
                                         // a node of `existing` (then the region may just touch it)
  std::vector<Polyline> existing;        // a network to extend: respected and joined, never emitted
};

struct GrownEdge {
  std::int64_t id = 0;
  std::int64_t from_node = 0;
  std::int64_t to_node = 0;
  std::string road_class;
  std::int64_t example_id = 0;
  Point a, b;
};

struct GrowStats {
  std::size_t steps = 0;           // unfinished nodes processed
  std::size_t unmatched = 0;       // steps where no example node matched
  std::size_t proposals = 0;
  std::size_t accepted = 0;
  std::size_t snapped = 0;         // proposals ending on an existing node or edge
  std::size_t clipped = 0;         // proposals shortened by the region or an obstacle
  std::size_t rejected = 0;
  std::size_t restarts = 0;        // growths that died within their first 20 edges and began again
  double radius = 0.0;             // the r and snap distance used
  double snap = 0.0;
};

struct GrowResult {
  std::vector<GrownEdge> edges;
  GrowStats stats;
};

// Throws invalid_argument for an example without two distinct nodes, a region that is empty,
// invalid or not polygonal, obstacles that are not polygonal, no seed, a seed outside the region
// or inside an obstacle, and parameters out of range. Polls interrupts once per step.
GrowResult grow_example(GeosContext& geos, const GrowInput& input, const GrowParams& params);

}  // namespace streetgen::core
