// Example patches (Nishida, Garcia-Dorado & Aliaga, "Example-Driven Procedural Urban Roads", 2016,
// section 4.1) with semantic tags (Teng & Bidarra, "A semantic approach to patch-based procedural
// generation of urban road networks", 2017, Table 1).
//
// The example is read as a street graph: polylines are noded at shared vertices and degree-2
// chains are merged, so nodes are junctions and dead ends and edges are whole streets between
// them. Interesting structures are detected first (roundabouts: the example's roundabout flag,
// or a small compact face of the graph, found by GEOS polygonize; tightly clustered junctions: a
// nearest-neighbour search), then every structure and every remaining junction is expanded into
// a patch by short-edge growth (an edge shorter than `short_edge` pulls its far node in). An
// edge between two patches is a connector of both (oriented from each patch outwards); an edge
// to a dead end is a dead-end edge.
#pragma once
#include "core/no_postgres.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "core/geos_context.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

struct PatchInputEdge {
  Polyline line;
  std::string road_class;  // OSM highway class or the example files' type (avenue, street, ...)
  std::int64_t id = 0;
  bool roundabout = false;  // the example says this edge is part of a roundabout
};

struct PatchParams {
  double short_edge = 0.0;        // metres; 0: 0.4 x the median street length
  double cluster_distance = 0.0;  // metres; 0: short_edge. Junctions this close form a cluster (>= 3 of them)
  bool detect_circles = true;     // small compact faces of the graph are roundabouts / plazas
  double circle_min_diameter = 8.0;
  double circle_max_diameter = 120.0;
  double circle_compactness = 0.8;  // 4 pi area / perimeter^2 of the face, 1 for a circle
  double crop_margin = 0.0;         // metres; 0: off. A dead end this close to the example's convex
                                    // hull is a street the crop cut: a connector tagged cut
  bool levels = true;               // arterial patches (tag arterial) from the main streets' graph, then
                                    // local patches around the junctions where local streets meet
};

// isolated: a street of the example with no junction at either end (a component without one): in
// no patch, its own patch (tag isolated) that grow_patches never places but counts in the
// example's dead-end share.
enum class PatchEdgeRole { inner, connector, dead_end, isolated };
const char* role_name(PatchEdgeRole role);

struct PatchEdge {
  Polyline line;  // connectors run from the patch outwards, dead-end edges towards the dead end
  PatchEdgeRole role = PatchEdgeRole::inner;
  std::string road_class;
  std::int64_t example_id = 0;
  std::vector<std::string> tags;        // main|local, connector, dead-end, snappable, curved|straight, roundabout
  std::vector<std::string> start_tags;  // vertex tags: intersection, connectable, dead-end
  std::vector<std::string> end_tags;
};

struct Patch {
  std::int64_t id = 0;
  std::vector<PatchEdge> edges;
  std::vector<std::string> tags;  // roundabout, cluster, loop, cul-de-sac, curved|straight, terminal, initial, main, local
  int max_uses = 0;               // 0: unlimited
};

struct PatchExtraction {
  std::vector<Patch> patches;
  double short_edge = 0.0;  // the threshold used
  std::size_t streets = 0;  // edges of the street graph
  std::size_t junctions = 0;
  std::size_t arterial_patches = 0;  // levels: the first ones are the arterial level's
};

// OSM's arterial classes (Nishida's Table 1, plus motorway and trunk) and the example files'
// avenue / highway / boulevard are main streets; everything else is local.
bool is_main_class(const std::string& road_class);

// Throws invalid_argument for an example without a street, and parameters out of range.
// Deterministic: the same edges in the same order give the same patches.
PatchExtraction extract_patches(GeosContext& geos, const std::vector<PatchInputEdge>& example,
                                const PatchParams& params);

// Nishida's statistical features of a set of streets (section 4.2): mean and standard deviation
// of the length and of the curvature (eq. 1: the turning of the unit directions per metre).
struct StreetStatistics {
  double length_mean = 0.0, length_sd = 0.0;
  double curvature_mean = 0.0, curvature_sd = 0.0;
};
StreetStatistics street_statistics(const std::vector<const Polyline*>& streets);
double curvature(const Polyline& line);
// The curvature (radians per metre) of the circular arc with the line's length and chord: how much
// the street bends as a whole. Unlike curvature(), a straight street digitised with small zigzags
// (whose turns add up) has about none.
double arc_curvature(const Polyline& line);

}  // namespace streetgen::core
