#include "core/streets/blocks.hpp"

#include <algorithm>
#include <cstdint>
#include <ctime>
#include <memory>
#include <new>
#include <string>

#include "core/error.hpp"
#include "core/interrupts.hpp"

namespace streetgen::core {
namespace {

constexpr double kMinBlockPartArea = 0.01;  // m², as sidewalks' (kMinSidewalkArea): smaller parts are slivers

struct TreeDeleter {
  GEOSContextHandle_t handle;
  void operator()(GEOSSTRtree* tree) const noexcept { GEOSSTRtree_destroy_r(handle, tree); }
};
struct PreparedDeleter {
  GEOSContextHandle_t handle;
  void operator()(const GEOSPreparedGeometry* prepared) const noexcept { GEOSPreparedGeom_destroy_r(handle, prepared); }
};

// What the tree query collects; GEOS calls the callback from C, so it must not throw.
struct Candidates {
  std::vector<std::size_t> indices;
  bool out_of_memory = false;
};
void collect(void* item, void* userdata) {
  auto* c = static_cast<Candidates*>(userdata);
  try {
    c->indices.push_back(reinterpret_cast<std::uintptr_t>(item) - 1);
  } catch (...) {
    c->out_of_memory = true;
  }
}

// CPU seconds, not wall: the figures are for profiling, and must add up on a busy machine too.
double seconds_since(std::clock_t start) { return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC; }

// Adds the CPU seconds of its scope to `sink`, on every way out of it. (std::clock is a system
// call, 1.3 us here: timed per piece, the clips' timing cost 0.5 s of Paris' 30.)
struct ScopeCpuTime {
  explicit ScopeCpuTime(double& s) : sink(s) {}
  ~ScopeCpuTime() { sink += seconds_since(start); }
  double& sink;
  std::clock_t start = std::clock();
};

// A GEOS overlay failed: GEOS's own interrupt is rethrown at once (as canceled); any other error
// is forgotten, and the caller retries on the grid.
void forget_or_rethrow(GeosContext& ctx, const char* operation) {
  if (ctx.last_error().rfind("InterruptedException", 0) == 0) ctx.fail(operation);
  ctx.clear_error();
}

// What is left of a face as its block: the polygons of `rest` of at least kMinBlockPartArea, as a
// MultiPolygon, or nullptr. Smaller parts are the gaps, nanometres wide, that two surfaces leave
// between edges that meet up to rounding (sidewalks lie on the micrometre grid, roadways not):
// on a piece of the Paris graph, 95 % of the blocks' parts were such slivers (1e-20 to 1e-4 m2).
void keep_block(GeosContext& ctx, const GEOSGeometry* rest, GeomPtr& result) {
  std::vector<GeomPtr> polygons;
  append_polygons(ctx, rest, polygons);
  polygons.erase(std::remove_if(polygons.begin(), polygons.end(), [&](const GeomPtr& p) {
                   double a = 0.0;
                   if (GEOSArea_r(ctx.handle(), p.get(), &a) == 0) ctx.fail("area");
                   return a < kMinBlockPartArea;
                 }),
                 polygons.end());
  if (polygons.empty()) {
    result.reset();
  } else {
    result = make_collection(ctx, GEOS_MULTIPOLYGON, polygons);
  }
}

// The floating difference rounded to the grid, then kept as the block. Where two pieces meet up to
// rounding, the difference keeps the nanometre gap between them as part of the block, a channel
// of no width along the street (on Paris in about 6,000 of the 13,140 blocks, up to 256 m long):
// snap rounding closes it. Returns false when the rounding failed (the caller retries on the grid).
bool round_and_keep(GeosContext& ctx, GeomPtr difference, double grid_size, GeomPtr& result, FaceCutStats& stats) {
  std::clock_t start = std::clock();
  GEOSGeometry* rounded = GEOSGeom_setPrecision_r(ctx.handle(), difference.get(), grid_size, 0);
  stats.rounding_seconds += seconds_since(start);
  if (rounded == nullptr) {
    forget_or_rethrow(ctx, "block rounding");
    return false;
  }
  difference.reset(rounded);
  keep_block(ctx, difference.get(), result);
  return true;
}

// The non-empty polygons of `geom`, through collections, as pointers into it (no copies).
void append_polygon_parts(GEOSContextHandle_t h, const GEOSGeometry* geom, std::vector<const GEOSGeometry*>& out) {
  int type = GEOSGeomTypeId_r(h, geom);
  if (type == GEOS_POLYGON) {
    if (GEOSisEmpty_r(h, geom) == 0) out.push_back(geom);
  } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
    int n = GEOSGetNumGeometries_r(h, geom);
    for (int i = 0; i < n; ++i) append_polygon_parts(h, GEOSGetGeometryN_r(h, geom, i), out);
  }
}

// Appends `ring` to `rings`, or frees it when the vector cannot grow.
bool push_or_free(GEOSContextHandle_t h, std::vector<GEOSGeometry*>& rings, GEOSGeometry* ring) noexcept {
  try {
    rings.push_back(ring);
    return true;
  } catch (...) {
    GEOSGeom_destroy_r(h, ring);
    return false;
  }
}

// The face minus its pieces in one pass, by a winding count: a buffer of distance 0 keeps where
// the count of the rings around a point is at least 1, and GEOS counts each ring by its role, not
// its direction (a shell +1, a hole -1). So a polygon whose shell is the face's and whose holes are
// the face's holes and every touching piece's shell keeps the face where no piece lies: no clip,
// no union, no difference (Paris' blocks in the backend: 32.0 s -> 18.1 s of CPU, the same areas
// to 1e-4 m² on every face). The noding and the depths are the buffer's, as in the union the float path makes.
// Returns false, and the float path takes the face, when a touching piece has a hole (it would
// count +1: on Paris a section's hole lying outside its face, one vertex 1e-13 m from a
// junction's, came out as part of the block) or when the buffer fails.
bool wind_face(GeosContext& ctx, const GEOSGeometry* face, const GEOSPreparedGeometry* prepared,
               const std::vector<const GEOSGeometry*>& polygons, const std::vector<std::size_t>& candidates,
               double grid_size, GeomPtr& result, FaceCutStats& stats) {
  GEOSContextHandle_t h = ctx.handle();
  GeomPtr difference(nullptr, GeomDeleter{h});
  {
    ScopeCpuTime winding_time(stats.winding_seconds);
    std::vector<GEOSGeometry*> rings;  // the face's holes and the pieces' shells, owned until the polygon takes them
    auto free_rings = [&] {
      for (GEOSGeometry* ring : rings) GEOSGeom_destroy_r(h, ring);
      rings.clear();
    };
    for (std::size_t i : candidates) {
      const GEOSGeometry* polygon = polygons[i];
      char touches = GEOSPreparedIntersects_r(h, prepared, polygon);
      if (touches == 0) continue;
      if (touches == 2 || GEOSGetNumInteriorRings_r(h, polygon) != 0) {
        free_rings();
        if (touches == 2) forget_or_rethrow(ctx, "block predicate");
        return false;
      }
      GEOSGeometry* ring = GEOSGeom_clone_r(h, GEOSGetExteriorRing_r(h, polygon));
      if (ring == nullptr || !push_or_free(h, rings, ring)) {
        free_rings();
        ctx.fail("clone");
      }
    }
    if (rings.empty()) {
      keep_block(ctx, face, result);
      ++stats.winding_faces;
      return true;
    }
    int face_holes = GEOSGetNumInteriorRings_r(h, face);
    for (int k = 0; k < face_holes; ++k) {
      GEOSGeometry* ring = GEOSGeom_clone_r(h, GEOSGetInteriorRingN_r(h, face, k));
      if (ring == nullptr || !push_or_free(h, rings, ring)) {
        free_rings();
        ctx.fail("clone");
      }
    }
    GEOSGeometry* shell = GEOSGeom_clone_r(h, GEOSGetExteriorRing_r(h, face));
    if (shell == nullptr) {
      free_rings();
      ctx.fail("clone");
    }
    // GEOS owns the rings once it has checked that they are rings, which these are; it can only
    // fail after that for want of memory, so they are not freed here (a leak then, never a
    // double free).
    GEOSGeometry* polygon = GEOSGeom_createPolygon_r(h, shell, rings.data(), static_cast<unsigned>(rings.size()));
    rings.clear();
    if (polygon == nullptr) ctx.fail("block winding polygon");
    GeomPtr wound(polygon, GeomDeleter{h});
    difference.reset(GEOSBuffer_r(h, wound.get(), 0.0, 8));
    if (!difference) {
      forget_or_rethrow(ctx, "block winding");
      return false;
    }
  }
  if (!round_and_keep(ctx, std::move(difference), grid_size, result, stats)) return false;
  ++stats.winding_faces;
  return true;
}

// One face, floating-point or on the grid of `grid_size`: the pieces cut to the face, united,
// and taken from it. Returns false when a float overlay failed (the caller retries on the grid);
// throws when an overlay on the grid fails. (Taking the pieces away one after another, each
// difference clipping the piece to the face's box, was 10 % faster on the small faces of the
// Paris graph but 2.6 times slower on Liechtenstein, whose faces hold hundreds of pieces.)
// In floating point the pieces are united by a buffer of distance 0, which nodes all their rings
// at once (a cascade of overlays nodes each pair it unites: 19 s against 8 s of CPU on Paris), and
// the difference is rounded to the grid (round_and_keep).
bool cut_face(GeosContext& ctx, const GEOSGeometry* face, const GEOSPreparedGeometry* prepared,
              const std::vector<const GEOSGeometry*>& pieces, const std::vector<std::size_t>& candidates, double grid_size,
              bool grid, GeomPtr& result, FaceCutStats& stats) {
  GEOSContextHandle_t h = ctx.handle();
  std::vector<GeomPtr> parts;
  {  // (the clips' time, however the loop ends)
    ScopeCpuTime clip_time(stats.clip_seconds);
    for (std::size_t i : candidates) {
      const GEOSGeometry* piece = pieces[i];
      // (a predicate that throws, on an invalid piece, leaves the question to the overlay)
      char touches = GEOSPreparedIntersects_r(h, prepared, piece);
      if (touches == 0) continue;
      if (touches == 2) forget_or_rethrow(ctx, "block predicate");
      if (touches == 1 && !grid) {
        char inside = GEOSPreparedContainsProperly_r(h, prepared, piece);
        if (inside == 1) {
          append_polygons(ctx, piece, parts);
          continue;
        }
        if (inside == 2) forget_or_rethrow(ctx, "block predicate");
      }
      ++stats.clipped_pairs;
      GEOSGeometry* clipped = grid ? GEOSIntersectionPrec_r(h, piece, face, grid_size) : GEOSIntersection_r(h, piece, face);
      if (clipped == nullptr) {
        if (grid) ctx.fail("block overlay (intersection on the grid)");
        forget_or_rethrow(ctx, "block overlay (intersection)");
        return false;
      }
      GeomPtr owned(clipped, GeomDeleter{h});
      append_polygons(ctx, owned.get(), parts);
    }
  }
  if (parts.empty()) {
    keep_block(ctx, face, result);
    return true;
  }
  GeomPtr collection = make_collection(ctx, GEOS_GEOMETRYCOLLECTION, parts);
  std::clock_t start = std::clock();
  GEOSGeometry* u = grid ? GEOSUnaryUnionPrec_r(h, collection.get(), grid_size) : GEOSBuffer_r(h, collection.get(), 0.0, 8);
  stats.union_seconds += seconds_since(start);
  if (u == nullptr) {
    if (grid) ctx.fail("block overlay (union on the grid)");
    forget_or_rethrow(ctx, "block overlay (union)");
    return false;
  }
  GeomPtr united(u, GeomDeleter{h});
  start = std::clock();
  GEOSGeometry* d = grid ? GEOSDifferencePrec_r(h, face, united.get(), grid_size) : GEOSDifference_r(h, face, united.get());
  stats.difference_seconds += seconds_since(start);
  if (d == nullptr) {
    if (grid) ctx.fail("block overlay (difference on the grid)");
    forget_or_rethrow(ctx, "block overlay (difference)");
    return false;
  }
  GeomPtr difference(d, GeomDeleter{h});
  if (!grid) return round_and_keep(ctx, std::move(difference), grid_size, result, stats);
  keep_block(ctx, difference.get(), result);
  return true;
}

struct IndexTree {  // an STRtree of geometries by index (items are index + 1: GEOS may treat a null item as none)
  IndexTree(GeosContext& ctx) : tree(GEOSSTRtree_create_r(ctx.handle(), 10), TreeDeleter{ctx.handle()}) {
    if (!tree) ctx.fail("STRtree creation");
  }
  void insert(GeosContext& ctx, const GEOSGeometry* g, std::size_t i) {
    GEOSSTRtree_insert_r(ctx.handle(), tree.get(), g, reinterpret_cast<void*>(static_cast<std::uintptr_t>(i + 1)));
  }
  // The indices whose boxes meet g's, sorted.
  const std::vector<std::size_t>& query(GeosContext& ctx, const GEOSGeometry* g) {
    found.indices.clear();
    GEOSSTRtree_query_r(ctx.handle(), tree.get(), g, &collect, &found);
    if (found.out_of_memory) throw std::bad_alloc();
    std::sort(found.indices.begin(), found.indices.end());
    return found.indices;
  }
  std::unique_ptr<GEOSSTRtree, TreeDeleter> tree;
  Candidates found;
};

}  // namespace

std::vector<GeomPtr> faces_minus_pieces(GeosContext& ctx, const std::vector<const GEOSGeometry*>& faces,
                                        const std::vector<const GEOSGeometry*>& pieces, double grid_size,
                                        FaceCutStats* stats) {
  std::vector<GeomPtr> out;
  for (std::size_t f = 0; f < faces.size(); ++f) out.emplace_back(nullptr, GeomDeleter{ctx.handle()});
  // (the caller keeps its faces: each lent as a clone would be copied for nothing)
  auto face_at = [&](std::size_t f) {
    if (faces[f] == nullptr) return GeomPtr(nullptr, GeomDeleter{ctx.handle()});
    return own(ctx, GEOSGeom_clone_r(ctx.handle(), faces[f]), "clone");
  };
  faces_minus_pieces(ctx, faces.size(), face_at, pieces, grid_size, [&](std::size_t f, GeomPtr cut) { out[f] = std::move(cut); },
                     stats);
  return out;
}

void faces_minus_pieces(GeosContext& ctx, std::size_t face_count, const std::function<GeomPtr(std::size_t)>& face_at,
                        const std::vector<const GEOSGeometry*>& pieces, double grid_size,
                        const std::function<void(std::size_t, GeomPtr)>& emit, FaceCutStats* stats) {
  if (!(grid_size > 0)) throw_invalid_argument("grid size must be positive");
  GEOSContextHandle_t h = ctx.handle();
  FaceCutStats local;
  FaceCutStats& s = stats != nullptr ? *stats : local;
  std::clock_t call_start = std::clock();

  // Every polygon of the pieces is its own item: a junction's sidewalk is one MultiPolygon with a
  // part at each corner, each part in one face, and whole it met every face around its junction
  // (on Paris a third of the pieces the old clip cut were such parts lying inside their face).
  std::vector<const GEOSGeometry*> polygons;
  for (const GEOSGeometry* piece : pieces) {
    if (piece != nullptr) append_polygon_parts(h, piece, polygons);
  }
  IndexTree tree(ctx);
  for (std::size_t i = 0; i < polygons.size(); ++i) tree.insert(ctx, polygons[i], i);

  for (std::size_t f = 0; f < face_count; ++f) {
    poll_interrupts();
    GeomPtr face = face_at(f);
    GeomPtr cut(nullptr, GeomDeleter{h});
    if (face) {
      ++s.faces;
      // The face's polygons by box, in the order of the input (not of the tree: the same pieces
      // always unite in the same order).
      std::vector<std::size_t> candidates;
      if (GEOSisEmpty_r(h, face.get()) == 0) candidates = tree.query(ctx, face.get());
      s.candidate_pairs += candidates.size();
      std::unique_ptr<const GEOSPreparedGeometry, PreparedDeleter> prepared(GEOSPrepare_r(h, face.get()), PreparedDeleter{h});
      if (!prepared) ctx.fail("prepared geometry");
      if (!wind_face(ctx, face.get(), prepared.get(), polygons, candidates, grid_size, cut, s) &&
          !cut_face(ctx, face.get(), prepared.get(), polygons, candidates, grid_size, false, cut, s)) {
        ++s.grid_faces;
        cut_face(ctx, face.get(), prepared.get(), polygons, candidates, grid_size, true, cut, s);
      }
    }
    emit(f, std::move(cut));
  }
  s.total_seconds += seconds_since(call_start);
}

}  // namespace streetgen::core
