// City blocks (issue 5): each bounded face of the ground-level axis network minus the street
// surfaces and sidewalks on it. The faces themselves come from PostGIS (ST_Polygonize of the
// sections' centre lines, sql/62-blocks.sql); this is the per-face overlay, which in SQL was one
// ST_Intersection per (face, piece) pair, each converting the face to GEOS again: most of a full
// run's block time on real cities.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/geos_context.hpp"
#include "core/streets/box_pairs.hpp"

namespace streetgen::core {

struct FaceCutStats {
  std::size_t faces = 0;
  std::size_t candidate_pairs = 0;  // (face, piece) pairs whose boxes overlap
  std::size_t clipped_pairs = 0;    // pairs that needed an overlay (the piece crosses the face's boundary)
  std::size_t winding_faces = 0;    // faces done in one pass by a winding count (the others are clipped and united)
  std::size_t grid_faces = 0;       // faces that fell back to the micrometre grid
  std::size_t pieces = 0;
  std::size_t pieces_held_at_most = 0;  // as GEOS geometries at once (EWKB pieces; given as geometries: all of them)
  // CPU seconds
  double winding_seconds = 0;       // in the winding passes, with the predicates that pick the pieces
  double clip_seconds = 0;          // in the pieces' intersections with the faces, with the predicates that pick them
  double union_seconds = 0;
  double difference_seconds = 0;
  double rounding_seconds = 0;      // the floating differences rounded to the grid
  double total_seconds = 0;         // the whole call (the index, the predicates, the retries too)
};

// Serialised geometry held by the caller (EWKB or WKB).
struct WkbView {
  const std::uint8_t* data = nullptr;  // null: no piece
  std::size_t size = 0;
};

// The boxes of the polygons of an (E)WKB geometry, in the order the overlay numbers them (a
// collection's or multipolygon's parts in turn, nested ones too; a polygon's box is its shell's,
// as in GEOS; empty polygons skipped), read straight from the bytes: the boxes are all the
// overlay needs of the pieces up front, and reading every piece into GEOS only for them was a
// whole parse more. False when the bytes hold anything it does not know or are cut short (the
// caller then reads the geometry with GEOS, which reports bad bytes). Hand-written: GEOS and
// PostGIS give a geometry's box, not its parts', without building the geometry.
bool wkb_polygon_boxes(const WkbView& wkb, std::vector<Box>& boxes);

// For each face: the face minus the union of the polygons of `pieces`, as a MultiPolygon of the
// parts of at least 0.01 m² (smaller ones are slivers between surfaces that meet up to
// rounding), or nullptr when nothing is left. Each face goes the first way that works:
// 1. one buffer of distance 0 over a winding count (the face +1, each touching piece -1), in
//    floating point, rounded to the grid of `grid_size`; not for a face that a piece with a hole
//    touches;
// 2. the pieces clipped to the face (one inside the face's interior taken as is), united, and
//    taken from it, in floating point, rounded to the grid: the operations of the SQL it replaced
//    (ST_Intersection, a union, ST_Difference);
// 3. the same with OverlayNG on the grid, which never fails (GEOS throws on nearly coincident
//    edges on a few real faces).
// A piece whose box misses the face, or that does not touch it, adds nothing. A null face gives
// a null result. Polls interrupts between faces.
std::vector<GeomPtr> faces_minus_pieces(GeosContext& ctx, const std::vector<const GEOSGeometry*>& faces,
                                        const std::vector<const GEOSGeometry*>& pieces, double grid_size,
                                        FaceCutStats* stats = nullptr);

// The same, a face at a time and the pieces as EWKB: face_at(f) gives face f (null: none; called
// twice, once for its box), emit(f, cut) takes its cut as soon as it is made, and a piece is read
// into GEOS before the first face that needs it and freed after the last. The faces go along a
// Hilbert curve (a face's cut does not depend on the order), so only the faces' and pieces'
// round the curve's front are held, not a city's.
void faces_minus_pieces(GeosContext& ctx, std::size_t face_count, const std::function<GeomPtr(std::size_t)>& face_at,
                        const std::vector<WkbView>& pieces, double grid_size,
                        const std::function<void(std::size_t, GeomPtr)>& emit, FaceCutStats* stats = nullptr);

}  // namespace streetgen::core
