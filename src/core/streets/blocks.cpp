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

// One face, floating-point or on the grid of `grid_size`: the pieces cut to the face, united,
// and taken from it. Returns false when a float overlay failed (the caller retries on the grid);
// throws when an overlay on the grid fails. (Taking the pieces away one after another, each
// difference clipping the piece to the face's box, was 10 % faster on the small faces of the
// Paris graph but 2.6 times slower on Liechtenstein, whose faces hold hundreds of pieces.)
// In floating point the pieces are united by a buffer of distance 0, which nodes all their rings
// at once (a cascade of overlays nodes each pair it unites: 19 s against 8 s of CPU on Paris), and
// the difference is rounded to the grid: where two pieces meet up to rounding, the difference
// kept the nanometre gap between them as part of the block, a channel of no width along the
// street (on Paris in about 6,000 of the 13,140 blocks, up to 256 m long).
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
  if (!grid) {
    start = std::clock();
    GEOSGeometry* rounded = GEOSGeom_setPrecision_r(h, difference.get(), grid_size, 0);
    stats.rounding_seconds += seconds_since(start);
    if (rounded == nullptr) {
      forget_or_rethrow(ctx, "block rounding");
      return false;
    }
    difference.reset(rounded);
  }
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
  if (!(grid_size > 0)) throw_invalid_argument("grid size must be positive");
  GEOSContextHandle_t h = ctx.handle();
  FaceCutStats local;
  FaceCutStats& s = stats != nullptr ? *stats : local;
  std::clock_t call_start = std::clock();
  std::vector<GeomPtr> out;
  for (std::size_t f = 0; f < faces.size(); ++f) out.emplace_back(nullptr, GeomDeleter{h});

  IndexTree tree(ctx);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (pieces[i] != nullptr && GEOSisEmpty_r(h, pieces[i]) == 0) tree.insert(ctx, pieces[i], i);
  }
  // Each face's pieces by box, in the order of the input (not of the tree: the same pieces
  // always unite in the same order).
  std::vector<std::vector<std::size_t>> candidates(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f] == nullptr) continue;
    ++s.faces;
    if (GEOSisEmpty_r(h, faces[f]) == 0) candidates[f] = tree.query(ctx, faces[f]);
    s.candidate_pairs += candidates[f].size();
  }

  for (std::size_t f = 0; f < faces.size(); ++f) {
    poll_interrupts();
    if (faces[f] == nullptr) continue;
    const GEOSGeometry* face = faces[f];
    std::unique_ptr<const GEOSPreparedGeometry, PreparedDeleter> prepared(GEOSPrepare_r(h, face), PreparedDeleter{h});
    if (!prepared) ctx.fail("prepared geometry");
    if (!cut_face(ctx, face, prepared.get(), pieces, candidates[f], grid_size, false, out[f], s)) {
      ++s.grid_faces;
      cut_face(ctx, face, prepared.get(), pieces, candidates[f], grid_size, true, out[f], s);
    }
  }
  s.total_seconds += seconds_since(call_start);
  return out;
}

}  // namespace streetgen::core
