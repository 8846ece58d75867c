// Topology from fuzzy road axes (StreetGen step 1): axis endpoints within the snap tolerance
// become one node; axes are split where another axis of the same layer crosses or touches
// them (shared OSM nodes, T-junctions digitised a little short or long); bridges and tunnels
// only connect through their endpoints.
#pragma once
#include "core/no_postgres.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct TopologyAxis {
  std::int64_t id = 0;
  Polyline line;
  int layer = 0;
};

struct TopologyNode {
  std::int64_t id = 0;  // stable: derived from position (mm) and layer
  Point position;
  int layer = 0;
  std::vector<std::int64_t> axis_ids;  // every axis with a point in the node (sorted), duplicates too
};

struct TopologyEdge {
  std::size_t axis_index = 0;  // into the input vector
  std::int64_t axis_id = 0;
  // Where the part starts along its axis, in millimetres of abscissa: its key. Unlike an
  // ordinal it does not change when the axis is split somewhere else, so a change stays local.
  std::int64_t part = 0;
  std::size_t from_node = 0;   // indices into Topology::nodes
  std::size_t to_node = 0;
  Polyline line;               // from_node's position ... to_node's position
  bool duplicate = false;      // same nodes and same course as an earlier edge: no surface
};

struct TopologyIssue {
  std::int64_t axis_id;
  std::string kind;  // degenerate_axis, duplicate_axis, loop_dropped, overlap_kept
  std::string detail;
  std::optional<std::int64_t> part;  // the part concerned, when it is about one part
  // The node it happens at, when the part it concerns has no section (a dropped loop, a
  // duplicate): what an incremental refresh scopes it by, since no section carries it.
  std::optional<std::int64_t> node_id = std::nullopt;
};

struct Topology {
  std::vector<TopologyNode> nodes;
  std::vector<TopologyEdge> edges;
  std::vector<TopologyIssue> issues;
};

Topology build_topology(const std::vector<TopologyAxis>& axes, double snap_tolerance);

// The stable node id: a 63-bit hash of the position rounded to the millimetre and the layer.
std::int64_t node_id_for(Point position, int layer);

}  // namespace streetgen::core
