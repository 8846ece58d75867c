// The street graph that every network metric reads, built once from edge polylines: endpoints
// within the node tolerance become one node (separately mapped carriageways and near-duplicate
// junctions would otherwise count twice), exact duplicates are dropped (OSMnx's undirected graph
// keeps one edge of a two-way street), and optionally the engine's topology splits crossings and
// degree-2 nodes are merged away (OSMnx's simplification).
#pragma once
#include <cstddef>
#include <vector>

#include "core/no_postgres.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct NetworkGraphOptions {
  double node_tolerance = 0.0;      // metres; 0: endpoints merge only when equal
  bool split_at_crossings = false;  // the surface engine's topology: split where lines cross or touch
  bool simplify = false;            // merge chains through degree-2 nodes into one edge
};

struct NetworkEdge {
  std::size_t a = 0;  // node indices; a == b for a self-loop
  std::size_t b = 0;
  Polyline line;  // starts at node a's position, ends at node b's
  double length = 0.0;
};

struct NetworkGraph {
  std::vector<Point> nodes;
  std::vector<NetworkEdge> edges;
  std::vector<int> degree;          // undirected; a self-loop counts twice (OSMnx's street_count)
  std::size_t duplicate_edges = 0;  // dropped: same nodes and same course as an earlier edge
  std::size_t collapsed_edges = 0;  // dropped: both ends in one node and no longer than 2 x tolerance
  std::size_t merged_nodes = 0;     // degree-2 nodes removed by simplify
};

// Throws invalid_argument for a negative or non-finite tolerance. Lines with fewer than two
// distinct points count as collapsed. `layers` (empty, or one per line) only matter with
// split_at_crossings: lines on different layers (bridges, tunnels) meet only at their ends.
NetworkGraph build_network_graph(const std::vector<Polyline>& lines, const NetworkGraphOptions& options,
                                 const std::vector<int>& layers = {});

}  // namespace streetgen::core
