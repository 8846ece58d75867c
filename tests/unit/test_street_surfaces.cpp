#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <tuple>

#include "core/error.hpp"
#include "core/streets/arc_centre.hpp"
#include "core/streets/box_pairs.hpp"
#include "core/streets/street_surfaces.hpp"

using namespace streetgen::core;

namespace {
constexpr double kPi = 3.14159265358979323846;

double area(GeosContext& ctx, const GEOSGeometry* g) {
  double a = 0;
  GEOSArea_r(ctx.handle(), g, &a);
  return a;
}

double overlap_area(GeosContext& ctx, const GEOSGeometry* a, const GEOSGeometry* b) {
  GeomPtr i = own(ctx, GEOSIntersection_r(ctx.handle(), a, b), "intersection");
  return area(ctx, i.get());
}

SurfaceAxis axis(std::int64_t id, Polyline line, double width, double speed) {
  SurfaceAxis a;
  a.id = id;
  a.line = std::move(line);
  a.roadway_width = width;
  a.speed_kmh = speed;
  return a;
}

// Every output valid; no two surfaces overlap (beyond rounding).
void expect_valid_and_disjoint(GeosContext& ctx, const SurfaceResult& r) {
  std::vector<const GEOSGeometry*> all;
  for (const auto& s : r.sections) {
    if (s.surface) all.push_back(s.surface.get());
  }
  for (const auto& i : r.intersections) {
    ASSERT_TRUE(i.surface) << "missing intersection surface";
    all.push_back(i.surface.get());
  }
  for (const GEOSGeometry* g : all) EXPECT_EQ(GEOSisValid_r(ctx.handle(), g), 1);
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = i + 1; j < all.size(); ++j) EXPECT_LT(overlap_area(ctx, all[i], all[j]), 1e-6) << i << " " << j;
  }
}
}  // namespace

TEST(RadiusRule, MatchesThePapersRadiiForCitySpeeds) {
  SurfaceSettings s;
  EXPECT_NEAR(radius_for_speed(s, 30), 2.8, 0.1);
  EXPECT_NEAR(radius_for_speed(s, 40), 5.0, 0.1);
  EXPECT_NEAR(radius_for_speed(s, 50), 7.9, 0.1);
  EXPECT_DOUBLE_EQ(radius_for_speed(s, 2), s.min_radius);
  EXPECT_DOUBLE_EQ(radius_for_speed(s, 300), s.max_radius);
}

TEST(ArcCentre, RightAngleAndPolylines) {
  auto c = arc_centre({{0, 0}, {50, 0}}, 5, {{0, 0}, {0, 50}}, 4);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->x, 4, 1e-9);
  EXPECT_NEAR(c->y, 5, 1e-9);
  // 180 degrees: parallel offsets, no centre.
  EXPECT_FALSE(arc_centre({{0, 0}, {50, 0}}, 5, {{0, 0}, {-50, 0}}, 5));
  // A reflex corner (swept the long way round) has none either.
  EXPECT_FALSE(arc_centre({{0, 0}, {0, 50}}, 5, {{0, 0}, {50, 0}}, 5));
  // Polyline: the centre found on the second segment is at the right distance from both.
  Polyline a{{0, 0}, {4, 0}, {30, 15}};
  Polyline b{{0, 0}, {-5, 40}};
  auto p = arc_centre(a, 6, b, 6);
  ASSERT_TRUE(p);
  EXPECT_NEAR(project(a, *p).distance, 6, 1e-7);
  EXPECT_NEAR(project(b, *p).distance, 6, 1e-7);
}

TEST(ArcCentre, FastAndExactPassesAgree) {
  // Polylines with bends on both sides, several radii: where the fast pass finds a centre the
  // exact pass finds the same one.
  Polyline a{{0, 0}, {12, 1}, {25, 9}, {40, 30}};
  Polyline b{{0, 0}, {-3, 14}, {2, 30}, {-6, 50}};
  int found = 0;
  for (double r : {0.0, 0.5, 2.0, 5.0, 9.0, 15.0}) {
    auto fast = arc_centre_fast(a, 4 + r, b, 3 + r);
    auto exact = arc_centre_exact(a, 4 + r, b, 3 + r);
    ASSERT_EQ(fast.has_value(), exact.has_value()) << r;
    if (fast) {
      ++found;
      EXPECT_NEAR(fast->x, exact->x, 1e-7) << r;
      EXPECT_NEAR(fast->y, exact->y, 1e-7) << r;
    }
  }
  EXPECT_GE(found, 4);
}

TEST(StreetSurfaces, CrossJunctionHasFourArcsAndTheExpectedArea) {
  GeosContext ctx;
  SurfaceSettings s;
  std::vector<SurfaceAxis> axes{axis(1, {{-50, 0}, {50, 0}}, 10, 50), axis(2, {{0, -50}, {0, 50}}, 10, 50)};
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  double radius = radius_for_speed(s, 50);
  ASSERT_EQ(r.intersections.size(), 1u);
  ASSERT_EQ(r.corners.size(), 4u);
  for (const auto& c : r.corners) {
    EXPECT_EQ(c.status, "ok");
    EXPECT_NEAR(c.radius, radius, 1e-9);
    ASSERT_TRUE(c.centre);
    EXPECT_NEAR(std::abs(c.centre->x), 5 + radius, 1e-7);
    EXPECT_NEAR(std::abs(c.centre->y), 5 + radius, 1e-7);
    EXPECT_NEAR(distance(c.arc[1], *c.centre), radius, 1e-7);
  }
  // Square of side 10 + 2r minus four r x r corner squares, plus what of them lies outside the arcs
  // (r^2 minus the quarter disc, segmentised with 8 chords per quarter circle).
  double quarter = 8 * radius * radius / 2 * std::sin(kPi / 16);
  double expected = std::pow(10 + 2 * radius, 2) - 4 * quarter;
  EXPECT_NEAR(area(ctx, r.intersections[0].surface.get()), expected, 1e-6);
  ASSERT_EQ(r.sections.size(), 4u);
  for (const auto& sec : r.sections) {
    EXPECT_EQ(sec.status, "ok");
    EXPECT_NEAR(area(ctx, sec.surface.get()), 10 * (50 - 5 - radius), 1e-6);
  }
  expect_valid_and_disjoint(ctx, r);
}

TEST(StreetSurfaces, ShortAxisShrinksTheRadius) {
  GeosContext ctx;
  SurfaceSettings s;
  // A 12 m stub between two junctions cannot hold 7.9 m arcs at both ends.
  std::vector<SurfaceAxis> axes{axis(1, {{-60, 0}, {0, 0}}, 8, 50), axis(2, {{0, 0}, {12, 0}}, 8, 50),
                                axis(3, {{12, 0}, {60, 0}}, 8, 50), axis(4, {{0, 0}, {0, 60}}, 8, 50),
                                axis(5, {{12, 0}, {12, -60}}, 8, 50)};
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  int reduced = 0;
  for (const auto& c : r.corners) {
    if (c.status == "radius_reduced") {
      ++reduced;
      EXPECT_LT(c.radius, c.radius_wanted);
    }
  }
  EXPECT_GT(reduced, 0);
  expect_valid_and_disjoint(ctx, r);
}

TEST(StreetSurfaces, AcuteAngleFallsBackAndStaysValid) {
  GeosContext ctx;
  SurfaceSettings s;
  std::vector<SurfaceAxis> axes{axis(1, {{0, 0}, {80, 0}}, 8, 50), axis(2, {{0, 0}, {80, 6}}, 8, 50),
                                axis(3, {{0, 0}, {-80, 0}}, 8, 50)};
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  ASSERT_EQ(r.intersections.size(), 1u);
  bool fallback = std::any_of(r.corners.begin(), r.corners.end(), [](const CornerResult& c) {
    return c.status == "min_radius" || c.status == "sharp" || c.status == "radius_reduced" || c.status == "clamped" ||
           c.status == "no_corner";
  });
  EXPECT_TRUE(fallback);
  expect_valid_and_disjoint(ctx, r);
}

// Two carriageways 8 m apart, 10 m wide (their sections split the overlap along the midline),
// each with a branch leaving at 6°, one eastwards, one westwards, from the same abscissa: each
// junction reaches over the other carriageway and the other junction. Junctions give way to the
// sections and split what they share: nothing overlaps, and each keeps its node.
TEST(StreetSurfaces, JunctionsPackedTogetherDoNotOverlap) {
  GeosContext ctx;
  SurfaceSettings s;
  std::vector<SurfaceAxis> axes{axis(1, {{-100, 0}, {100, 0}}, 10, 50), axis(2, {{-100, 8}, {100, 8}}, 10, 50),
                                axis(3, {{0, 0}, {100, -10}}, 8, 50), axis(4, {{0, 8}, {-100, 18}}, 8, 50)};
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  ASSERT_EQ(r.intersections.size(), 2u);
  for (const auto& i : r.intersections) {
    EXPECT_EQ(i.status, "narrowed") << i.node_id;
    EXPECT_EQ(GEOSGeomTypeId_r(ctx.handle(), i.surface.get()), GEOS_POLYGON);
  }
  for (Point node : {Point{0, 0}, Point{0, 8}}) {
    GeomPtr p = own(ctx, GEOSGeom_createPointFromXY_r(ctx.handle(), node.x, node.y), "point");
    int holders = 0;
    for (const auto& i : r.intersections) holders += GEOSIntersects_r(ctx.handle(), i.surface.get(), p.get());
    EXPECT_GE(holders, 1) << node.y;
  }
  expect_valid_and_disjoint(ctx, r);
}

TEST(StreetSurfaces, WidthChangeAtADegreeTwoNodeIsALinearTransition) {
  GeosContext ctx;
  SurfaceSettings s;
  std::vector<SurfaceAxis> axes{axis(1, {{-50, 0}, {0, 0}}, 6, 50), axis(2, {{0, 0}, {50, 0}}, 10, 50)};
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  ASSERT_EQ(r.intersections.size(), 1u);
  EXPECT_EQ(r.intersections[0].status, "transition");
  // Length max(5, 5 m per m of change = 20 m): a trapezoid 20 m long from 6 to 10 m wide.
  EXPECT_NEAR(area(ctx, r.intersections[0].surface.get()), 20 * 8, 1e-6);
  for (const auto& c : r.corners) EXPECT_EQ(c.status, "transition");
  expect_valid_and_disjoint(ctx, r);
}

TEST(StreetSurfaces, OverridesWin) {
  GeosContext ctx;
  SurfaceSettings s;
  std::vector<SurfaceAxis> axes{axis(1, {{-50, 0}, {50, 0}}, 10, 50), axis(2, {{0, 0}, {0, 50}}, 10, 50)};
  axes[1].radius_override = 2.0;
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  for (const auto& c : r.corners) {
    if (c.status == "ok") {
      EXPECT_NEAR(c.radius, 2.0, 1e-9);
    }
  }
  // A per-corner override beats the axis one.
  const CornerResult* first = nullptr;
  for (const auto& c : r.corners) {
    if (c.status == "ok") first = &c;
  }
  ASSERT_NE(first, nullptr);
  CornerOverride o{first->node_id, first->a, first->b, 4.5};
  SurfaceResult r2 = street_surfaces(ctx, axes, {o}, s);
  int overridden = 0;
  for (const auto& c : r2.corners) {
    if (c.a == o.a && c.b == o.b) {
      EXPECT_NEAR(c.radius, 4.5, 1e-9);
      ++overridden;
    }
  }
  EXPECT_EQ(overridden, 1);
}

TEST(StreetSurfaces, BadInputIsRefusedWithTheAxisId) {
  GeosContext ctx;
  SurfaceSettings s;
  for (double w : {0.0, -1.0, std::nan("")}) {
    try {
      street_surfaces(ctx, {axis(42, {{0, 0}, {10, 0}}, w, 30)}, {}, s);
      FAIL() << "width " << w << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_argument);
      EXPECT_NE(std::string(e.what()).find("42"), std::string::npos);
    }
  }
  EXPECT_THROW(street_surfaces(ctx, {axis(1, {{0, 0}, {std::nan(""), 0}}, 5, 30)}, {}, s), Error);
  SurfaceSettings bad = s;
  bad.min_radius = -1;
  EXPECT_THROW(street_surfaces(ctx, {}, {}, bad), Error);
}

TEST(StreetSurfaces, DegreeEightJunctionAndDeadEnds) {
  GeosContext ctx;
  SurfaceSettings s;
  std::vector<SurfaceAxis> axes;
  for (int k = 0; k < 8; ++k) {
    double a = k * kPi / 4;
    axes.push_back(axis(k + 1, {{0, 0}, {60 * std::cos(a), 60 * std::sin(a)}}, 7, 40));
  }
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  ASSERT_EQ(r.intersections.size(), 1u);  // dead ends have no junction surface
  EXPECT_EQ(r.corners.size(), 8u);
  for (const auto& n : r.nodes) {
    if (n.degree == 8) {
      EXPECT_EQ(n.axis_ids.size(), 8u);
    }
  }
  expect_valid_and_disjoint(ctx, r);
}

// Sidewalks (issue 5): beside each section and around the junction, never on a roadway or on
// each other; crossings on the arms of a junction of degree >= 3 with sidewalks on both sides,
// and none on a street without sidewalks.
TEST(StreetDetails, SidewalksStayOffRoadwaysAndCrossingsFollowTheRule) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes{axis(1, {{-60, 0}, {0, 0}}, 8, 30), axis(2, {{0, 0}, {60, 0}}, 8, 30),
                                axis(3, {{0, 0}, {0, 60}}, 8, 30), axis(4, {{0, 0}, {10, -30}, {0, -60}}, 8, 30)};
  for (std::size_t i = 0; i < 3; ++i) axes[i].sidewalk_left = axes[i].sidewalk_right = 2.0;
  axes[3].sidewalk_left = 3.0;  // a sidewalk on one side only: no crossing on that arm
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  expect_valid_and_disjoint(ctx, r);
  int around = 0;
  // Sidewalks are snapped to the micrometre grid: each vertex moves by at most a micrometre, so
  // a sidewalk may cross a curved roadway edge by its perimeter times that (a few square
  // millimetres along a junction's arcs), never more.
  for (const auto& w : r.sidewalks) {
    ASSERT_TRUE(w.surface);
    double perimeter = 0.0;
    GEOSLength_r(ctx.handle(), w.surface.get(), &perimeter);
    const double kGridOverlap = perimeter * 1e-6;
    EXPECT_EQ(GEOSisValid_r(ctx.handle(), w.surface.get()), 1);
    if (w.side == "around") ++around;
    for (const auto& s : r.sections) {
      if (s.surface) {
        EXPECT_LT(overlap_area(ctx, w.surface.get(), s.surface.get()), kGridOverlap);
      }
    }
    for (const auto& i : r.intersections) EXPECT_LT(overlap_area(ctx, w.surface.get(), i.surface.get()), kGridOverlap);
    for (const auto& o : r.sidewalks) {
      if (&o != &w) {
        EXPECT_LT(overlap_area(ctx, w.surface.get(), o.surface.get()), kGridOverlap);
      }
    }
  }
  EXPECT_EQ(around, 1);
  EXPECT_EQ(r.sidewalks.size(), 3u * 2u + 1u + 1u);
  ASSERT_EQ(r.crossings.size(), 3u);
  for (const auto& c : r.crossings) {
    EXPECT_NE(c.axis_id, 4);
    EXPECT_NEAR(area(ctx, c.surface.get()), 8.0 * 3.0, 1e-6);
  }
  // A negative sidewalk width is refused.
  axes[0].sidewalk_left = -1;
  EXPECT_THROW(street_surfaces(ctx, axes, {}, SurfaceSettings{}), Error);
}

// Street surfaces only (SurfaceSettings::details false): no lanes, markings, crossings or
// sidewalks, and the nodes, sections, corners and junctions exactly those of a run with them.
TEST(StreetDetails, SurfacesOnlyLeaveOutTheDetailsAndKeepTheSurfaces) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes{axis(1, {{-60, 0}, {0, 0}}, 8, 30), axis(2, {{0, 0}, {60, 0}}, 8, 30),
                                axis(3, {{0, 0}, {0, 60}}, 8, 30), axis(4, {{0, 0}, {10, -30}, {0, -60}}, 12, 50)};
  for (SurfaceAxis& a : axes) a.sidewalk_left = a.sidewalk_right = 2.0;
  SurfaceResult all = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  SurfaceSettings surfaces_only;
  surfaces_only.details = false;
  SurfaceResult bare = street_surfaces(ctx, axes, {}, surfaces_only);
  ASSERT_FALSE(all.lanes.empty());
  ASSERT_FALSE(all.sidewalks.empty());
  ASSERT_FALSE(all.crossings.empty());
  EXPECT_TRUE(bare.lanes.empty());
  EXPECT_TRUE(bare.markings.empty());
  EXPECT_TRUE(bare.crossings.empty());
  EXPECT_TRUE(bare.sidewalks.empty());
  EXPECT_EQ(bare.nodes.size(), all.nodes.size());
  ASSERT_EQ(bare.sections.size(), all.sections.size());
  for (std::size_t i = 0; i < all.sections.size(); ++i) {
    EXPECT_EQ(bare.sections[i].status, all.sections[i].status);
    EXPECT_EQ(GEOSEqualsExact_r(ctx.handle(), bare.sections[i].surface.get(), all.sections[i].surface.get(), 0.0), 1);
  }
  ASSERT_EQ(bare.intersections.size(), all.intersections.size());
  for (std::size_t i = 0; i < all.intersections.size(); ++i) {
    EXPECT_EQ(bare.intersections[i].node_id, all.intersections[i].node_id);
    EXPECT_EQ(GEOSEqualsExact_r(ctx.handle(), bare.intersections[i].surface.get(), all.intersections[i].surface.get(), 0.0), 1);
  }
  ASSERT_EQ(bare.corners.size(), all.corners.size());
  for (std::size_t i = 0; i < all.corners.size(); ++i) EXPECT_EQ(bare.corners[i].radius, all.corners[i].radius);
  expect_valid_and_disjoint(ctx, bare);
}

// The phase times add up to no more than the CPU time of the whole call (each phase is counted
// once, none is negative), and the sidewalks, the costliest phase on real cities, are timed.
TEST(StreetSurfaces, PhaseTimesAddUpToTheCallsCpuTime) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes;
  for (int i = 0; i < 6; ++i) {  // a 6 x 6 grid of 100 m blocks with sidewalks
    axes.push_back(axis(1 + i, {{0, 100.0 * i}, {500, 100.0 * i}}, 8, 50));
    axes.push_back(axis(101 + i, {{100.0 * i, 0}, {100.0 * i, 500}}, 8, 50));
  }
  for (SurfaceAxis& a : axes) a.sidewalk_left = a.sidewalk_right = 2;
  std::clock_t before = std::clock();
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  double call = static_cast<double>(std::clock() - before) / CLOCKS_PER_SEC;
  const SurfaceRunStats& t = r.stats;
  for (double phase : {t.topology, t.corners, t.sections, t.lanes, t.junctions, t.sidewalks}) EXPECT_GE(phase, 0.0);
  EXPECT_LE(t.topology + t.corners + t.sections + t.lanes + t.junctions + t.sidewalks, call + 1e-6);
  EXPECT_FALSE(r.sidewalks.empty());
  EXPECT_GT(t.sidewalks, 0.0);
}

namespace {
const SidewalkResult* junction_sidewalk(const SurfaceResult& r) {
  const SidewalkResult* found = nullptr;
  for (const auto& w : r.sidewalks) {
    if (w.side == "around") {
      EXPECT_EQ(found, nullptr) << "one sidewalk per junction";
      found = &w;
    }
  }
  return found;
}

// The 4-way cross of two straight streets 8 m wide through (0, 0), sidewalks `w` on both sides.
std::vector<SurfaceAxis> cross_with_sidewalks(double speed, double w) {
  std::vector<SurfaceAxis> axes{axis(1, {{-60, 0}, {0, 0}}, 8, speed), axis(2, {{0, 0}, {60, 0}}, 8, speed),
                                axis(3, {{0, 0}, {0, 60}}, 8, speed), axis(4, {{0, -60}, {0, 0}}, 8, speed)};
  for (SurfaceAxis& a : axes) a.sidewalk_left = a.sidewalk_right = w;
  return axes;
}
}  // namespace

// A junction's sidewalk is the band between each corner's curb and the curb moved out by the
// sidewalk width, up to the streets' border lines. On a cross whose arcs start at the border
// lines (no straight curb between): with a radius above the width, four bands between the
// segmentised arc of radius r and that of radius r - w (eight chords a quarter each); with a
// radius below it, the border lines cross at the arc's centre and each band is the whole
// segmentised quarter disc (a buffer's outline is cut there by the streets' own claims).
TEST(StreetDetails, JunctionSidewalksFollowTheCurbArcs) {
  GeosContext ctx;
  const double chords = 4 * std::sin(kPi / 16);  // a quarter circle of 8 chords: chords * r^2
  for (double speed : {30.0, 20.0}) {
    const double w = 2.0;
    SurfaceResult r = street_surfaces(ctx, cross_with_sidewalks(speed, w), {}, SurfaceSettings{});
    ASSERT_EQ(r.corners.size(), 4u);
    double radius = r.corners.front().radius;
    for (const auto& c : r.corners) ASSERT_EQ(c.status, "ok");
    const SidewalkResult* around = junction_sidewalk(r);
    ASSERT_NE(around, nullptr);
    EXPECT_EQ(GEOSisValid_r(ctx.handle(), around->surface.get()), 1);
    EXPECT_EQ(GEOSGetNumGeometries_r(ctx.handle(), around->surface.get()), 4);
    double expected = radius > w ? 4 * chords * (radius * radius - (radius - w) * (radius - w))
                                 : 4 * chords * radius * radius;
    EXPECT_NEAR(area(ctx, around->surface.get()), expected, 1e-3) << "speed " << speed << ", radius " << radius;
    EXPECT_DOUBLE_EQ(around->width, w);
    // Nothing of it on a roadway or on a street's sidewalk (the grid's micrometre aside).
    for (const auto& s : r.sections) EXPECT_LT(overlap_area(ctx, around->surface.get(), s.surface.get()), 1e-4);
    for (const auto& i : r.intersections) EXPECT_LT(overlap_area(ctx, around->surface.get(), i.surface.get()), 1e-4);
    for (const auto& o : r.sidewalks) {
      if (&o != around) {
        EXPECT_LT(overlap_area(ctx, around->surface.get(), o.surface.get()), 1e-4);
      }
    }
  }
}

// Each corner takes the wider of its two streets' sides facing it: on a T whose through street
// has no sidewalk on the far side, the far side of the junction gets none either.
TEST(StreetDetails, AJunctionCornerWithoutSidewalksOnEitherSideGetsNone) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes{axis(1, {{-60, 0}, {0, 0}}, 8, 30), axis(2, {{0, 0}, {60, 0}}, 8, 30),
                                axis(3, {{0, 0}, {0, 60}}, 8, 30)};
  axes[0].sidewalk_left = axes[1].sidewalk_left = 2.0;  // the north side, towards the side street
  axes[2].sidewalk_left = axes[2].sidewalk_right = 3.0;
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  const SidewalkResult* around = junction_sidewalk(r);
  ASSERT_NE(around, nullptr);
  EXPECT_EQ(GEOSGetNumGeometries_r(ctx.handle(), around->surface.get()), 2);  // the two corners by the side street
  double ymin = 0;
  GEOSGeom_getYMin_r(ctx.handle(), around->surface.get(), &ymin);
  EXPECT_GT(ymin, 4.0 - 1e-6);  // nothing south of the through street's north curb
  EXPECT_DOUBLE_EQ(around->width, 3.0);
}

// A corner without a band of its own claims the buffer of its own curb, not the junction the
// buffer of its whole ring: on a T whose side street leaves at 60 degrees, the obtuse corner's
// border lines lie farther out than its sidewalk reaches (the acute corner pushed them), so its
// band has no corner to end in. Its neighbours keep their bands, and the junction's sidewalk
// still closes the ring round it: no gap within the sidewalk's width of the junction.
TEST(StreetDetails, ACornerWithoutABandClaimsItsOwnCurbsBuffer) {
  GeosContext ctx;
  const double w = 3.0;
  const double rad = 60.0 * kPi / 180;
  std::vector<SurfaceAxis> axes{axis(1, {{-100, 0}, {0, 0}}, 8, 30), axis(2, {{0, 0}, {100, 0}}, 8, 30),
                                axis(3, {{0, 0}, {100 * std::cos(rad), 100 * std::sin(rad)}}, 8, 30)};
  for (SurfaceAxis& a : axes) a.sidewalk_left = a.sidewalk_right = w;
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  ASSERT_EQ(r.intersections.size(), 1u);
  ASSERT_EQ(r.intersections.front().status, "ok");
  EXPECT_EQ(r.stats.junction_sidewalks_by_corner, 1);
  EXPECT_EQ(r.stats.junction_sidewalks_by_buffer, 0);
  EXPECT_EQ(r.stats.junction_corners_by_buffer, 1);
  const SidewalkResult* around = junction_sidewalk(r);
  ASSERT_NE(around, nullptr);
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), around->surface.get()), 1);
  for (const auto& s : r.sections) EXPECT_LT(overlap_area(ctx, around->surface.get(), s.surface.get()), 1e-4);
  for (const auto& i : r.intersections) EXPECT_LT(overlap_area(ctx, around->surface.get(), i.surface.get()), 1e-4);
  std::vector<GeomPtr> all;
  for (const auto& o : r.sidewalks) {
    if (&o != around) {
      EXPECT_LT(overlap_area(ctx, around->surface.get(), o.surface.get()), 1e-4);
    }
    all.push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), o.surface.get()), "clone"));
  }
  for (const auto& s : r.sections) all.push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), s.surface.get()), "clone"));
  all.push_back(own(ctx, GEOSGeom_clone_r(ctx.handle(), r.intersections.front().surface.get()), "clone"));
  GeomPtr covered = own(ctx, GEOSUnaryUnion_r(ctx.handle(), make_collection(ctx, GEOS_GEOMETRYCOLLECTION, all).get()),
                        "union");
  GeomPtr near = own(ctx, GEOSBuffer_r(ctx.handle(), r.intersections.front().surface.get(), 0.9 * w, 8), "buffer");
  GeomPtr gap = own(ctx, GEOSDifference_r(ctx.handle(), near.get(), covered.get()), "difference");
  EXPECT_LT(area(ctx, gap.get()), 0.05);
}

namespace {
// A 3 x 3 grid of 80 m blocks with sidewalks, two lanes a street.
std::vector<SurfaceAxis> grid_with_lanes_and_sidewalks() {
  std::vector<SurfaceAxis> axes;
  for (int i = 0; i < 3; ++i) {
    axes.push_back(axis(1 + i, {{0, 80.0 * i}, {160, 80.0 * i}}, 7, 40));
    axes.push_back(axis(11 + i, {{80.0 * i, 0}, {80.0 * i, 160}}, 7, 40));
  }
  for (SurfaceAxis& a : axes) {
    a.sidewalk_left = a.sidewalk_right = 2.5;
    a.lane_input.lanes = 2;
  }
  return axes;
}
}  // namespace

// Asked for EWKB, the engine hands lanes, markings, crossings and sidewalks over as soon as they
// are built (their geometries null), and the bytes are those of the geometries it builds by
// default: the memory saving changes no output.
TEST(StreetSurfaces, OutputsHandedOverAsEwkbAreTheGeometriesWritten) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes = grid_with_lanes_and_sidewalks();
  SurfaceResult live = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  SurfaceOutput output;
  output.ewkb_srid = 2154;
  SurfaceResult handed = street_surfaces(ctx, axes, {}, SurfaceSettings{}, output);
  ASSERT_FALSE(live.lanes.empty());
  ASSERT_FALSE(live.markings.empty());
  ASSERT_FALSE(live.crossings.empty());
  ASSERT_FALSE(live.sidewalks.empty());
  auto same = [&](auto& live_items, auto& handed_items, auto geometry_of, const char* kind) {
    ASSERT_EQ(live_items.size(), handed_items.size()) << kind;
    for (std::size_t i = 0; i < live_items.size(); ++i) {
      GeomPtr& expected = geometry_of(live_items[i]);
      ASSERT_TRUE(expected) << kind << " " << i;
      EXPECT_FALSE(geometry_of(handed_items[i])) << kind << " " << i << ": still a GEOS geometry";
      EXPECT_EQ(handed_items[i].ewkb, write_ewkb(ctx, expected.get(), 2154)) << kind << " " << i;
    }
  };
  same(live.lanes, handed.lanes, [](LaneResult& l) -> GeomPtr& { return l.surface; }, "lane");
  same(live.markings, handed.markings, [](MarkingResult& m) -> GeomPtr& { return m.line; }, "marking");
  same(live.crossings, handed.crossings, [](CrossingResult& c) -> GeomPtr& { return c.surface; }, "crossing");
  same(live.sidewalks, handed.sidewalks, [](SidewalkResult& w) -> GeomPtr& { return w.surface; }, "sidewalk");
  // The rest stays as it was: sections and junctions are read by later phases and by the caller.
  ASSERT_EQ(live.sections.size(), handed.sections.size());
  for (std::size_t i = 0; i < live.sections.size(); ++i) {
    EXPECT_EQ(static_cast<bool>(live.sections[i].surface), static_cast<bool>(handed.sections[i].surface));
  }
}

TEST(StreetSurfaces, SidewalkClaimsAreHeldOnlyRoundTheirTurn) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes;
  for (int i = 0; i < 12; ++i) {  // a 12 x 12 grid of 60 m blocks with sidewalks
    axes.push_back(axis(1 + i, {{0, 60.0 * i}, {660, 60.0 * i}}, 7, 40));
    axes.push_back(axis(101 + i, {{60.0 * i, 0}, {60.0 * i, 660}}, 7, 40));
  }
  for (SurfaceAxis& a : axes) a.sidewalk_left = a.sidewalk_right = 2;
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  const SurfaceRunStats& t = r.stats;
  // 264 street sections, two sides each, and 144 junctions by corner
  ASSERT_GE(t.sidewalk_claims, 528 + 144);
  // In key order every street side's claim was held until the junctions, after them all
  // (more than half of the claims); along a Hilbert curve, only those round its front.
  EXPECT_GT(t.sidewalk_claims_held_peak, 0);
  EXPECT_LT(t.sidewalk_claims_held_peak, t.sidewalk_claims / 5);
  // The sidewalks still come in key order: the streets' by (axis, part, side), then the
  // junctions' by node.
  ASSERT_EQ(r.sidewalks.size(), 528u + 144u);
  auto key = [](const SidewalkResult& w) { return std::make_tuple(w.node_id != 0, w.node_id, w.axis_id, w.part, w.side); };
  for (std::size_t i = 1; i < r.sidewalks.size(); ++i) EXPECT_LT(key(r.sidewalks[i - 1]), key(r.sidewalks[i])) << i;
  // Sidewalks never overlap each other (the grid's micrometre aside).
  std::vector<Box> boxes;
  for (const SidewalkResult& w : r.sidewalks) {
    Box b{};
    GEOSGeom_getXMin_r(ctx.handle(), w.surface.get(), &b.xmin);
    GEOSGeom_getYMin_r(ctx.handle(), w.surface.get(), &b.ymin);
    GEOSGeom_getXMax_r(ctx.handle(), w.surface.get(), &b.xmax);
    GEOSGeom_getYMax_r(ctx.handle(), w.surface.get(), &b.ymax);
    boxes.push_back(b);
  }
  long pairs = 0;
  for_each_overlapping_pair(boxes, [&](std::size_t i, std::size_t j) {
    ++pairs;
    EXPECT_LT(overlap_area(ctx, r.sidewalks[i].surface.get(), r.sidewalks[j].surface.get()), 1e-3) << i << " " << j;
  });
  EXPECT_GT(pairs, 0);
}

TEST(StreetSurfaces, ARunInTwoStepsHandsOverTheLanesFirstAndMakesTheSameResult) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes = grid_with_lanes_and_sidewalks();
  SurfaceOutput output;
  output.ewkb_srid = 2154;
  SurfaceResult whole = street_surfaces(ctx, axes, {}, SurfaceSettings{}, output);
  SurfaceRun run(ctx, axes, {}, SurfaceSettings{}, output);
  run.through_lanes();
  std::vector<LaneResult> lanes = std::move(run.lanes());
  std::vector<MarkingResult> markings = std::move(run.markings());
  SurfaceResult rest = run.finish();
  // The lanes and markings are complete after the first step, and the second does not need them.
  ASSERT_FALSE(whole.lanes.empty());
  ASSERT_EQ(lanes.size(), whole.lanes.size());
  for (std::size_t i = 0; i < lanes.size(); ++i) EXPECT_EQ(lanes[i].ewkb, whole.lanes[i].ewkb) << i;
  ASSERT_EQ(markings.size(), whole.markings.size());
  for (std::size_t i = 0; i < markings.size(); ++i) EXPECT_EQ(markings[i].ewkb, whole.markings[i].ewkb) << i;
  EXPECT_TRUE(rest.lanes.empty());
  EXPECT_TRUE(rest.markings.empty());
  // Everything else as one call makes it.
  ASSERT_EQ(rest.sections.size(), whole.sections.size());
  for (std::size_t i = 0; i < rest.sections.size(); ++i) {
    EXPECT_EQ(write_ewkb(ctx, rest.sections[i].surface.get(), 2154), write_ewkb(ctx, whole.sections[i].surface.get(), 2154));
  }
  ASSERT_EQ(rest.intersections.size(), whole.intersections.size());
  ASSERT_EQ(rest.corners.size(), whole.corners.size());
  ASSERT_FALSE(whole.sidewalks.empty());
  ASSERT_EQ(rest.sidewalks.size(), whole.sidewalks.size());
  for (std::size_t i = 0; i < rest.sidewalks.size(); ++i) EXPECT_EQ(rest.sidewalks[i].ewkb, whole.sidewalks[i].ewkb) << i;
  ASSERT_EQ(rest.crossings.size(), whole.crossings.size());
  for (std::size_t i = 0; i < rest.crossings.size(); ++i) EXPECT_EQ(rest.crossings[i].ewkb, whole.crossings[i].ewkb) << i;
  // The inputs are checked as street_surfaces checks them.
  std::vector<SurfaceAxis> bad = axes;
  bad[0].roadway_width = -1;
  EXPECT_THROW(SurfaceRun(ctx, bad, {}, SurfaceSettings{}, output), Error);
}

// A grid of oblique streets at UTM-sized coordinates, as a city: the sections' flat ends (GEOS's
// buffer) and the junctions' border lines (computed here) meet a nanometre apart, so the exact
// contact test alone would send junctions to a GEOS overlay that changes nothing. The rounding
// bound settles every junction without one, and the surfaces stay valid and disjoint.
TEST(StreetSurfaces, JunctionsTouchingTheirSectionsButForRoundingNeedNoOverlay) {
  GeosContext ctx;
  const double x0 = 512345.25, y0 = 5412345.5, c = std::cos(0.3), sn = std::sin(0.3);
  auto at = [&](double x, double y) { return Point{x0 + c * x - sn * y, y0 + sn * x + c * y}; };
  std::vector<SurfaceAxis> axes;
  std::int64_t id = 1;
  for (int k = 0; k < 3; ++k) {
    axes.push_back(axis(id++, {at(-60, 80.0 * k), at(220, 80.0 * k + 7)}, 9, 50));
    axes.push_back(axis(id++, {at(80.0 * k, -60), at(80.0 * k - 9, 220)}, 7, 30));
  }
  SurfaceSettings s;
  s.details = false;
  SurfaceResult r = street_surfaces(ctx, axes, {}, s);
  ASSERT_EQ(r.intersections.size(), 9u);
  EXPECT_EQ(r.stats.junction_overlays, 0);
  EXPECT_GT(r.stats.junctions_touching_but_for_rounding, 0);
  EXPECT_EQ(r.stats.junctions_touching + r.stats.junctions_touching_but_for_rounding, 9);
  for (const auto& i : r.intersections) EXPECT_EQ(i.status, "ok");
  expect_valid_and_disjoint(ctx, r);
}
