#include "core/streets/blocks.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <memory>
#include <new>
#include <string>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "core/interrupts.hpp"
#include "core/streets/box_pairs.hpp"

namespace streetgen::core {
namespace {

constexpr double kMinBlockPartArea = 0.01;  // m², as sidewalks' (kMinSidewalkArea): smaller parts are slivers

struct PreparedDeleter {
  GEOSContextHandle_t handle;
  void operator()(const GEOSPreparedGeometry* prepared) const noexcept { GEOSPreparedGeom_destroy_r(handle, prepared); }
};


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



// See wkb_polygon_boxes.
class WkbBoxReader {
 public:
  WkbBoxReader(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}
  bool read(std::vector<Box>& boxes) { return geometry(boxes, 0) && p_ == end_; }

 private:
  bool geometry(std::vector<Box>& boxes, int depth) {
    if (depth > 32 || end_ - p_ < 5) return false;
    little_ = *p_++ == 1;
    std::uint32_t type = 0;
    if (!u32(type)) return false;
    bool z = (type & 0x80000000u) != 0, m = (type & 0x40000000u) != 0;
    bool srid = (type & 0x20000000u) != 0;
    type &= 0x0fffffffu;
    if (type >= 1000 && type < 4000) {  // ISO: 1000s Z, 2000s M, 3000s ZM
      z = z || type / 1000 != 2;
      m = m || type / 1000 != 1;
      type %= 1000;
    }
    std::size_t dims = 2 + (z ? 1 : 0) + (m ? 1 : 0);
    std::uint32_t n = 0;
    if (srid && !u32(n)) return false;
    switch (type) {
      case 1:  // point
        return skip(dims);
      case 2:  // line string
        return u32(n) && skip(std::size_t{n} * dims);
      case 3:  // polygon
        return polygon(boxes, dims);
      case 4:  // multi point, multi line string, multi polygon, collection: each part with its own header
      case 5:
      case 6:
      case 7:
        if (!u32(n)) return false;
        for (std::uint32_t i = 0; i < n; ++i) {
          if (!geometry(boxes, depth + 1)) return false;
        }
        return true;
      default:
        return false;
    }
  }
  bool polygon(std::vector<Box>& boxes, std::size_t dims) {
    std::uint32_t rings = 0;
    if (!u32(rings)) return false;
    for (std::uint32_t r = 0; r < rings; ++r) {
      std::uint32_t points = 0;
      if (!u32(points)) return false;
      if (r > 0 || points == 0) {
        if (!skip(std::size_t{points} * dims)) return false;
        continue;
      }
      Box b{};
      for (std::uint32_t i = 0; i < points; ++i) {
        double x = 0, y = 0;
        if (!f64(x) || !f64(y) || !skip(dims - 2)) return false;
        if (i == 0) {
          b = {x, y, x, y};
        } else {
          b = {std::min(b.xmin, x), std::min(b.ymin, y), std::max(b.xmax, x), std::max(b.ymax, y)};
        }
      }
      boxes.push_back(b);
    }
    return true;
  }
  bool u32(std::uint32_t& v) {
    if (end_ - p_ < 4) return false;
    std::uint8_t b[4];
    std::memcpy(b, p_, 4);
    if (!little_) std::reverse(b, b + 4);
    v = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 | static_cast<std::uint32_t>(b[2]) << 16 |
        static_cast<std::uint32_t>(b[3]) << 24;
    p_ += 4;
    return true;
  }
  bool f64(double& v) {
    if (end_ - p_ < 8) return false;
    std::uint8_t b[8];
    std::memcpy(b, p_, 8);
    if (little_ != host_little()) std::reverse(b, b + 8);
    std::memcpy(&v, b, 8);
    p_ += 8;
    return true;
  }
  bool skip(std::size_t doubles) {
    if (static_cast<std::size_t>(end_ - p_) / 8 < doubles) return false;
    p_ += doubles * 8;
    return true;
  }
  static bool host_little() {
    const std::uint16_t one = 1;
    std::uint8_t first = 0;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  bool little_ = true;
};

// The pieces, as polygons numbered in input order (a piece's parts in turn), each piece held as
// a GEOS geometry only while the faces that need it are cut.
class PieceStore {
 public:
  // Pieces given as GEOS geometries: all held by the caller.
  PieceStore(GeosContext& ctx, const std::vector<const GEOSGeometry*>& pieces) : ctx_(ctx) {
    for (const GEOSGeometry* piece : pieces) add(piece);
    polygons_ = parts_;  // (every piece is there from the start)
    held_at_most_ = pieces.size();
  }
  // Pieces given as EWKB: the boxes of each piece's polygons read from its bytes
  // (wkb_polygon_boxes), the piece read into GEOS when a face first needs it.
  PieceStore(GeosContext& ctx, const std::vector<WkbView>& pieces) : ctx_(ctx), wkb_(&pieces) {
    for (const WkbView& piece : pieces) {
      if (piece.data == nullptr) {
        add(nullptr);
        continue;
      }
      std::vector<Box> boxes;
      if (wkb_polygon_boxes(piece, boxes)) {
        add_boxes(boxes);
        continue;
      }
      GeomPtr g = read_ewkb(ctx_, piece.data, piece.size, "piece").geom;
      add(g.get());
    }
    std::vector<const GEOSGeometry*>().swap(parts_);  // (pointers into the geometries just freed)
    polygons_.assign(boxes_.size(), nullptr);
    held_.resize(pieces.size());
  }

  const std::vector<Box>& boxes() const { return boxes_; }
  std::size_t held_at_most() const { return held_at_most_; }
  std::size_t piece_count() const { return first_part_.size(); }
  std::size_t piece_of(std::size_t polygon) const { return piece_of_[polygon]; }
  // Every polygon by its number; a piece's are null until need() reads it.
  const std::vector<const GEOSGeometry*>& polygons() const { return polygons_; }

  void need(std::size_t piece) {
    if (wkb_ == nullptr || held_[piece]) return;
    const WkbView& v = (*wkb_)[piece];
    held_[piece] = read_ewkb(ctx_, v.data, v.size, "piece").geom;
    held_at_most_ = std::max(held_at_most_, ++held_count_);
    std::vector<const GEOSGeometry*> parts;
    append_polygon_parts(ctx_.handle(), held_[piece].get(), parts);
    if (parts.size() != part_count_[piece]) ctx_.fail("piece read again");  // (cannot happen: the same bytes)
    std::copy(parts.begin(), parts.end(), polygons_.begin() + static_cast<std::ptrdiff_t>(first_part_[piece]));
  }
  void release(std::size_t piece) {
    if (wkb_ == nullptr || !held_[piece]) return;
    std::fill_n(polygons_.begin() + static_cast<std::ptrdiff_t>(first_part_[piece]), part_count_[piece], nullptr);
    held_[piece].reset();
    --held_count_;
  }

 private:
  void add(const GEOSGeometry* piece) {
    std::size_t first = parts_.size();
    if (piece != nullptr) append_polygon_parts(ctx_.handle(), piece, parts_);
    first_part_.push_back(first);
    part_count_.push_back(parts_.size() - first);
    boxes_.resize(parts_.size());
    for (std::size_t k = first; k < parts_.size(); ++k) {
      Box& b = boxes_[k];
      if (GEOSGeom_getXMin_r(ctx_.handle(), parts_[k], &b.xmin) == 0 || GEOSGeom_getYMin_r(ctx_.handle(), parts_[k], &b.ymin) == 0 ||
          GEOSGeom_getXMax_r(ctx_.handle(), parts_[k], &b.xmax) == 0 || GEOSGeom_getYMax_r(ctx_.handle(), parts_[k], &b.ymax) == 0) {
        ctx_.fail("envelope");
      }
      piece_of_.push_back(first_part_.size() - 1);
    }
  }

  // A piece's polygons by their boxes alone (read from its bytes: held as none).
  void add_boxes(const std::vector<Box>& boxes) {
    first_part_.push_back(boxes_.size());
    part_count_.push_back(boxes.size());
    for (const Box& b : boxes) {
      boxes_.push_back(b);
      parts_.push_back(nullptr);
      piece_of_.push_back(first_part_.size() - 1);
    }
  }

  GeosContext& ctx_;
  const std::vector<WkbView>* wkb_ = nullptr;
  std::vector<const GEOSGeometry*> parts_;     // while adding
  std::vector<const GEOSGeometry*> polygons_;
  std::vector<Box> boxes_;                     // per polygon
  std::vector<std::size_t> piece_of_;          // per polygon
  std::vector<std::size_t> first_part_, part_count_;  // per piece
  std::vector<GeomPtr> held_;                  // per piece (EWKB pieces only)
  std::size_t held_count_ = 0, held_at_most_ = 0;
};

}  // namespace

bool wkb_polygon_boxes(const WkbView& wkb, std::vector<Box>& boxes) {
  boxes.clear();
  if (wkb.data == nullptr) return false;
  return WkbBoxReader(wkb.data, wkb.size).read(boxes);
}

namespace {

// Cuts the faces (see faces_minus_pieces) with the pieces of `store`, along a Hilbert curve
// through the faces' boxes.
void cut_faces(GeosContext& ctx, std::size_t face_count, const std::function<GeomPtr(std::size_t)>& face_at,
               PieceStore& store, double grid_size, const std::function<void(std::size_t, GeomPtr)>& emit,
               FaceCutStats& s) {
  if (!(grid_size > 0)) throw_invalid_argument("grid size must be positive");
  GEOSContextHandle_t h = ctx.handle();
  std::clock_t call_start = std::clock();
  // Each face's polygons by box (faces first, then polygons, in one box sweep), in the order of
  // the input: the same pieces always unite in the same order.
  std::vector<Box> boxes;
  std::vector<std::size_t> face_of_box;
  std::vector<bool> present(face_count, false);
  for (std::size_t f = 0; f < face_count; ++f) {
    poll_interrupts();
    GeomPtr face = face_at(f);
    if (!face) continue;
    present[f] = true;
    ++s.faces;
    if (GEOSisEmpty_r(h, face.get()) != 0) continue;
    Box b;
    if (GEOSGeom_getXMin_r(h, face.get(), &b.xmin) == 0 || GEOSGeom_getYMin_r(h, face.get(), &b.ymin) == 0 ||
        GEOSGeom_getXMax_r(h, face.get(), &b.xmax) == 0 || GEOSGeom_getYMax_r(h, face.get(), &b.ymax) == 0) {
      ctx.fail("envelope");
    }
    boxes.push_back(b);
    face_of_box.push_back(f);
  }
  const std::size_t face_boxes = boxes.size();
  std::vector<std::size_t> order;  // the faces, along the curve
  for (std::size_t k : hilbert_order(boxes)) order.push_back(face_of_box[k]);
  boxes.insert(boxes.end(), store.boxes().begin(), store.boxes().end());
  std::vector<std::vector<std::size_t>> candidates(face_count);
  for_each_overlapping_pair(boxes, [&](std::size_t i, std::size_t j) {
    if (i < face_boxes && j >= face_boxes) candidates[face_of_box[i]].push_back(j - face_boxes);
  });
  std::vector<Box>().swap(boxes);
  // A piece is held from the first face that needs it until its last is cut.
  std::vector<std::size_t> uses(store.piece_count(), 0);
  for (auto& c : candidates) {
    std::sort(c.begin(), c.end());
    s.candidate_pairs += c.size();
    for (std::size_t polygon : c) ++uses[store.piece_of(polygon)];
  }
  // (empty faces, which have no box, come last: nothing is cut from them)
  std::vector<bool> ordered(face_count, false);
  for (std::size_t f : order) ordered[f] = true;
  for (std::size_t f = 0; f < face_count; ++f) {
    if (present[f] && !ordered[f]) order.push_back(f);
  }
  std::vector<bool> emitted(face_count, false);
  for (std::size_t f : order) {
    poll_interrupts();
    GeomPtr face = face_at(f);
    GeomPtr cut(nullptr, GeomDeleter{h});
    for (std::size_t polygon : candidates[f]) store.need(store.piece_of(polygon));
    std::unique_ptr<const GEOSPreparedGeometry, PreparedDeleter> prepared(GEOSPrepare_r(h, face.get()), PreparedDeleter{h});
    if (!prepared) ctx.fail("prepared geometry");
    const std::vector<const GEOSGeometry*>& polygons = store.polygons();
    if (!wind_face(ctx, face.get(), prepared.get(), polygons, candidates[f], grid_size, cut, s) &&
        !cut_face(ctx, face.get(), prepared.get(), polygons, candidates[f], grid_size, false, cut, s)) {
      ++s.grid_faces;
      cut_face(ctx, face.get(), prepared.get(), polygons, candidates[f], grid_size, true, cut, s);
    }
    prepared.reset();
    face.reset();
    for (std::size_t polygon : candidates[f]) {
      std::size_t piece = store.piece_of(polygon);
      if (--uses[piece] == 0) store.release(piece);
    }
    std::vector<std::size_t>().swap(candidates[f]);
    emitted[f] = true;
    emit(f, std::move(cut));
  }
  for (std::size_t f = 0; f < face_count; ++f) {  // no face: a null cut
    if (!emitted[f]) emit(f, GeomPtr(nullptr, GeomDeleter{h}));
  }
  s.pieces = store.piece_count();
  s.pieces_held_at_most = store.held_at_most();
  s.total_seconds += seconds_since(call_start);
}

}  // namespace

std::vector<GeomPtr> faces_minus_pieces(GeosContext& ctx, const std::vector<const GEOSGeometry*>& faces,
                                        const std::vector<const GEOSGeometry*>& pieces, double grid_size,
                                        FaceCutStats* stats) {
  FaceCutStats local;
  PieceStore store(ctx, pieces);
  std::vector<GeomPtr> out;
  for (std::size_t f = 0; f < faces.size(); ++f) out.emplace_back(nullptr, GeomDeleter{ctx.handle()});
  // (the caller keeps its faces: each is lent as a clone)
  auto face_at = [&](std::size_t f) {
    if (faces[f] == nullptr) return GeomPtr(nullptr, GeomDeleter{ctx.handle()});
    return own(ctx, GEOSGeom_clone_r(ctx.handle(), faces[f]), "clone");
  };
  cut_faces(ctx, faces.size(), face_at, store, grid_size, [&](std::size_t f, GeomPtr cut) { out[f] = std::move(cut); },
            stats != nullptr ? *stats : local);
  return out;
}

void faces_minus_pieces(GeosContext& ctx, std::size_t face_count, const std::function<GeomPtr(std::size_t)>& face_at,
                        const std::vector<WkbView>& pieces, double grid_size,
                        const std::function<void(std::size_t, GeomPtr)>& emit, FaceCutStats* stats) {
  if (!(grid_size > 0)) throw_invalid_argument("grid size must be positive");
  FaceCutStats local;
  PieceStore store(ctx, pieces);
  cut_faces(ctx, face_count, face_at, store, grid_size, emit, stats != nullptr ? *stats : local);
}

}  // namespace streetgen::core
