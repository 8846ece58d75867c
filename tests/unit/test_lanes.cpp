#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <numeric>

#include "core/error.hpp"
#include "core/streets/lanes.hpp"
#include "core/streets/street_surfaces.hpp"

using namespace streetgen::core;

namespace {

LaneInput input(std::optional<int> lanes, bool oneway, std::map<std::string, std::string> tags = {}) {
  LaneInput in;
  in.lanes = lanes;
  in.oneway = oneway;
  in.tags = std::move(tags);
  return in;
}

std::string layout(const LanePlan& p) {  // "type/direction" left to right
  std::string out;
  for (const LaneSpec& l : p.lanes) out += (out.empty() ? "" : " ") + l.type + "/" + l.direction;
  return out;
}

double total_width(const LanePlan& p) {
  return std::accumulate(p.lanes.begin(), p.lanes.end(), 0.0, [](double s, const LaneSpec& l) { return s + l.width; });
}

bool noted(const LanePlan& p, const std::string& kind) {
  for (const LaneNote& n : p.notes) {
    if (n.kind == kind) return true;
  }
  return false;
}

double area(GeosContext& ctx, const GEOSGeometry* g) {
  double a = 0;
  GEOSArea_r(ctx.handle(), g, &a);
  return a;
}

}  // namespace

TEST(PlanLanes, TwoWayOneWayAndTags) {
  LanePlan p = plan_lanes(input(2, false), 7.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");
  EXPECT_DOUBLE_EQ(p.lanes[0].width, 3.5);
  EXPECT_TRUE(p.notes.empty());

  p = plan_lanes(input(3, true), 9.75);
  EXPECT_EQ(layout(p), "driving/forward driving/forward driving/forward");

  p = plan_lanes(input(1, false), 4.0);
  EXPECT_EQ(layout(p), "driving/both");

  // Forward/backward counts, turn lanes in the direction of travel (backward: from the centre out).
  p = plan_lanes(input(3, false, {{"lanes:forward", "2"}, {"lanes:backward", "1"},
                                  {"turn:lanes:forward", "left|through;right"}, {"turn:lanes:backward", "left"}}),
                 10.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward driving/forward");
  EXPECT_EQ(p.lanes[0].turn, "left");
  EXPECT_EQ(p.lanes[1].turn, "left");
  EXPECT_EQ(p.lanes[2].turn, "through;right");
  EXPECT_TRUE(p.notes.empty());

  // Cycle lanes at the curbs, with their own width; driving lanes share the rest.
  p = plan_lanes(input(2, false, {{"cycleway", "lane"}}), 9.0);
  EXPECT_EQ(layout(p), "cycle/backward driving/backward driving/forward cycle/forward");
  EXPECT_DOUBLE_EQ(p.lanes[0].width, 1.5);
  EXPECT_DOUBLE_EQ(p.lanes[1].width, 3.0);
  // A contraflow cycle lane on a one-way, a bus lane that is one of the counted lanes.
  p = plan_lanes(input(2, true, {{"cycleway:left", "opposite_lane"}, {"busway:right", "lane"}}), 8.0);
  EXPECT_EQ(layout(p), "cycle/backward driving/forward bus/forward");
  // A bus lane added where the direction has one lane only.
  p = plan_lanes(input(2, false, {{"busway:right", "lane"}}), 10.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward bus/forward");
  // lanes=3 with one each way and no lanes:both_ways: a shared centre lane.
  p = plan_lanes(input(3, false, {{"lanes:forward", "1"}, {"lanes:backward", "1"}}), 10.0);
  EXPECT_EQ(layout(p), "driving/backward driving/both driving/forward");
  EXPECT_TRUE(p.notes.empty());
  // Tracks and shared lanes are not in the roadway: no lane, no note.
  p = plan_lanes(input(2, false, {{"cycleway", "track"}, {"busway", "no"}}), 7.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");
  EXPECT_TRUE(p.notes.empty());
}

TEST(PlanLanes, BadInputFallsBackAndSaysSo) {
  // Widths always add up to the roadway.
  for (double w : {1.0, 3.0, 5.5, 7.0, 12.3}) {
    for (int n : {1, 2, 3, 6, 20}) {
      for (bool oneway : {false, true}) {
        LanePlan p = plan_lanes(input(n, oneway, {{"cycleway", "lane"}, {"busway", "lane"}}), w);
        ASSERT_FALSE(p.lanes.empty());
        EXPECT_NEAR(total_width(p), w, 1e-9) << n << " lanes on " << w << " m";
        for (const LaneSpec& l : p.lanes) EXPECT_GT(l.width, 0.0);
      }
    }
  }
  // Six lanes on 7 m: as many as fit at 2 m, one way at least each way.
  LanePlan p = plan_lanes(input(6, false), 7.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward driving/forward");
  EXPECT_TRUE(noted(p, "lanes_do_not_fit"));
  // Two lanes on 3 m: one lane for both directions.
  p = plan_lanes(input(2, false), 3.0);
  EXPECT_EQ(layout(p), "driving/both");
  EXPECT_TRUE(noted(p, "lanes_do_not_fit"));
  // A cycle lane that does not fit goes first.
  p = plan_lanes(input(1, true, {{"cycleway:right", "lane"}}), 2.75);
  EXPECT_EQ(layout(p), "driving/forward");
  EXPECT_TRUE(noted(p, "lanes_do_not_fit"));
  // lanes=0 and junk counts: ignored, the count comes from the width (2.75 m a lane).
  p = plan_lanes(input(std::nullopt, false, {{"lanes", "0"}}), 5.5);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  p = plan_lanes(input(2, false, {{"lanes:forward", "two"}}), 7.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  // Contradictory counts: split evenly.
  p = plan_lanes(input(2, false, {{"lanes:forward", "2"}, {"lanes:backward", "2"}}), 7.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");
  EXPECT_TRUE(noted(p, "lane_tags_contradict"));
  p = plan_lanes(input(2, true, {{"lanes:backward", "1"}}), 7.0);
  EXPECT_EQ(layout(p), "driving/forward driving/forward");
  EXPECT_TRUE(noted(p, "lane_tags_contradict"));
  // Unknown values and turn lists of the wrong length: ignored.
  p = plan_lanes(input(2, true, {{"cycleway", "rainbow"}, {"turn:lanes", "left|through|right"}}), 7.0);
  EXPECT_EQ(layout(p), "driving/forward driving/forward");
  EXPECT_TRUE(p.lanes[0].turn.empty());
  EXPECT_EQ(std::count_if(p.notes.begin(), p.notes.end(), [](const LaneNote& n) { return n.kind == "lane_tag_ignored"; }), 2);
  p = plan_lanes(input(2, true, {{"turn:lanes", "left|teleport"}}), 7.0);
  EXPECT_EQ(p.lanes[0].turn, "left");
  EXPECT_TRUE(p.lanes[1].turn.empty());
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  EXPECT_THROW(plan_lanes(input(2, false), 0.0), Error);
}

TEST(SignedOffset, LeftPositiveAndBisectorAtSharpBends) {
  Polyline l{{0, 0}, {10, 0}};
  EXPECT_DOUBLE_EQ(signed_offset(l, {5, 2}), 2.0);
  EXPECT_DOUBLE_EQ(signed_offset(l, {5, -3}), -3.0);
  // A hairpin: a point beyond the bend's vertex, on the outside, is on the right.
  Polyline hairpin{{0, 0}, {10, 0}, {1, 1}};
  EXPECT_LT(signed_offset(hairpin, {12, -0.5}), 0.0);
}

// On a bent polyline the lanes tile the section: the offset curves, not a translation.
TEST(SectionLanes, TileTheSectionOnAPolyline) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes(3);
  axes[0].id = 1;
  axes[0].line = {{0, 0}, {60, 0}, {100, 30}, {110, 80}};
  axes[0].roadway_width = 12;
  axes[0].speed_kmh = 50;
  axes[0].lane_input = input(3, false, {{"lanes:forward", "2"}, {"cycleway:right", "lane"}});
  axes[1].id = 2;
  axes[1].line = {{110, 80}, {160, 80}};
  axes[1].roadway_width = 7;
  axes[1].speed_kmh = 50;
  axes[2].id = 3;
  axes[2].line = {{110, 80}, {110, 130}};
  axes[2].roadway_width = 7;
  axes[2].speed_kmh = 50;
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  const SectionResult* sec = nullptr;
  for (const SectionResult& s : r.sections) {
    if (s.axis_id == 1) sec = &s;
  }
  ASSERT_TRUE(sec && sec->surface);
  std::vector<const LaneResult*> lanes;
  for (const LaneResult& l : r.lanes) {
    if (l.axis_id == 1) lanes.push_back(&l);
  }
  ASSERT_EQ(lanes.size(), 4u);
  double sum = 0.0;
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    EXPECT_EQ(lanes[i]->index, static_cast<int>(i) + 1);
    EXPECT_EQ(GEOSisValid_r(ctx.handle(), lanes[i]->surface.get()), 1);
    sum += area(ctx, lanes[i]->surface.get());
    for (std::size_t j = i + 1; j < lanes.size(); ++j) {
      GeomPtr o = own(ctx, GEOSIntersection_r(ctx.handle(), lanes[i]->surface.get(), lanes[j]->surface.get()), "overlap");
      EXPECT_LT(area(ctx, o.get()), 1e-6);
    }
  }
  EXPECT_NEAR(sum, area(ctx, sec->surface.get()), 1e-6 * area(ctx, sec->surface.get()));
  // Each lane's area is its width times the centre line between the borders, within what the
  // bends' round joins change (the lanes are offsets, not translations).
  double len = sec->end_border - sec->start_border;
  EXPECT_NEAR(area(ctx, lanes[0]->surface.get()) / len, lanes[0]->spec.width, 0.25);
  EXPECT_EQ(lanes[3]->spec.type, "cycle");
  // Markings: the centre line between lanes 1 and 2 (one way, two the other: solid), a dashed
  // separator between the forward driving lanes, a solid one by the cycle lane, a stop line at
  // the T junction across the forward lanes; every point of a separator at its offset.
  int centre = 0, dashed = 0, solid_sep = 0, stop = 0;
  Polyline axis_part = substring(sec->centre_line, sec->start_border, sec->end_border);
  for (const MarkingResult& m : r.markings) {
    if (m.axis_id != 1) continue;
    if (m.kind == "centre_line") {
      ++centre;
      EXPECT_EQ(m.style, "solid");
      EXPECT_EQ(m.position, 1);
    } else if (m.kind == "lane_separator") {
      (m.style == "dashed" ? dashed : solid_sep)++;
    } else if (m.kind == "stop_line") {
      ++stop;
      EXPECT_EQ(m.position, 1);
      double l = 0;
      GEOSLength_r(ctx.handle(), m.line.get(), &l);
      EXPECT_NEAR(l, lanes[1]->spec.width + lanes[2]->spec.width + lanes[3]->spec.width, 1e-6);
    }
    if (m.kind == "stop_line") continue;
    double expected = 6.0;
    for (int k = 0; k < m.position; ++k) expected -= lanes[k]->spec.width;
    const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx.handle(), m.line.get());
    ASSERT_NE(seq, nullptr);
    unsigned int n = 0;
    GEOSCoordSeq_getSize_r(ctx.handle(), seq, &n);
    for (unsigned int i = 0; i < n; ++i) {
      Point p;
      GEOSCoordSeq_getXY_r(ctx.handle(), seq, i, &p.x, &p.y);
      EXPECT_NEAR(signed_offset(axis_part, p), expected, 1e-6) << m.kind << " " << m.position;
    }
  }
  EXPECT_EQ(centre, 1);
  EXPECT_EQ(dashed, 1);
  EXPECT_EQ(solid_sep, 1);
  EXPECT_EQ(stop, 1);
}

// Six lanes of a sixth of the width: the centre boundary comes out of the sums as about 1e-15 m,
// a distance GEOS 3.11's OffsetCurve fails on; it is the centre line itself.
TEST(SectionLanes, CentreBoundaryFromInexactWidths) {
  GeosContext ctx;
  for (double w : {16.7, 17.3, 19.9, 21.1}) {
    LanePlan plan = plan_lanes(input(6, false), w);
    ASSERT_EQ(plan.lanes.size(), 6u);
    Polyline centre{{0, 0}, {40, 3}, {80, 0}};
    GEOSGeometry* seq_line = nullptr;
    {
      GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx.handle(), 3, 2);
      for (unsigned i = 0; i < 3; ++i) GEOSCoordSeq_setXY_r(ctx.handle(), seq, i, centre[i].x, centre[i].y);
      seq_line = GEOSGeom_createLineString_r(ctx.handle(), seq);
    }
    GeomPtr line(seq_line, GeomDeleter{ctx.handle()});
    GeomPtr surface = own(ctx, GEOSBufferWithStyle_r(ctx.handle(), line.get(), w / 2, 8, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_ROUND, 5.0), "buffer");
    std::vector<LaneResult> lanes;
    std::vector<MarkingResult> markings;
    ASSERT_NO_THROW(section_lanes(ctx, 1, 0, centre, surface.get(), false, plan, true, true, lanes, markings)) << w;
    EXPECT_EQ(lanes.size(), 6u);
    EXPECT_EQ(std::count_if(markings.begin(), markings.end(), [](const MarkingResult& m) { return m.kind == "centre_line"; }), 1);
  }
}

// Street parking (Berlin's tagging): the traffic lanes stay on the axis, parking widens the
// roadway on its side; widths by orientation, the tagged width, the old scheme, fallbacks.
TEST(PlanLanes, StreetParkingAtTheCurbs) {
  // Rübelandstraße, Neukölln: width 6, parking on the right only. The real curbs lie 2 m left
  // and 4 m right of the OSM way.
  LanePlan p = plan_lanes(input(2, false, {{"parking:left", "no"}, {"parking:right", "lane"},
                                           {"parking:right:orientation", "parallel"}}), 6.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward parking/forward");
  EXPECT_DOUBLE_EQ(p.lanes[2].width, 2.0);
  EXPECT_DOUBLE_EQ(p.lanes[0].width, 2.0);
  EXPECT_NEAR(total_width(p), 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(p.centre_offset, -1.0);
  EXPECT_TRUE(p.notes.empty());

  // Jonasstraße: width 11, parallel on the left, perpendicular on the right: curbs 4 m and 7 m.
  p = plan_lanes(input(2, false, {{"parking:both", "lane"}, {"parking:left:orientation", "parallel"},
                                  {"parking:right:orientation", "perpendicular"}}), 11.0);
  EXPECT_EQ(layout(p), "parking/backward driving/backward driving/forward parking/forward");
  EXPECT_DOUBLE_EQ(p.centre_offset, -1.5);
  // the left curb: the backward traffic lane and the parking lane, from the axis
  EXPECT_DOUBLE_EQ(p.lanes[0].width + p.lanes[1].width, 4.0);

  // A tagged width and half on the kerb; the old scheme; a one-way's left parking runs forward.
  p = plan_lanes(input(1, true, {{"parking:left", "half_on_kerb"}, {"parking:left:width", "2.4"}}), 5.0);
  EXPECT_EQ(layout(p), "parking/forward driving/forward");
  EXPECT_DOUBLE_EQ(p.lanes[0].width, 1.2);
  EXPECT_DOUBLE_EQ(p.centre_offset, 0.6);
  p = plan_lanes(input(2, false, {{"parking:lane:both", "diagonal"}}), 15.0);
  EXPECT_EQ(layout(p), "parking/backward driving/backward driving/forward parking/forward");
  EXPECT_DOUBLE_EQ(p.lanes[0].width, 4.5);
  EXPECT_DOUBLE_EQ(p.centre_offset, 0.0);
  p = plan_lanes(input(2, false, {{"parking:lane:right", "parallel"}, {"parking:lane:right:parallel", "on_kerb"}}), 7.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");  // on the kerb: not in the roadway

  // Lay-bys, separate parking and "no" take no roadway; unknown values and bad widths are noted.
  EXPECT_EQ(plan_lanes(input(2, false, {{"parking:both", "street_side"}}), 7.0).lanes.size(), 2u);
  p = plan_lanes(input(2, false, {{"parking:right", "sometimes"}}), 7.0);
  EXPECT_EQ(p.lanes.size(), 2u);
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  p = plan_lanes(input(2, false, {{"parking:right", "lane"}, {"parking:right:width", "wide"}}), 7.0);
  EXPECT_DOUBLE_EQ(p.lanes.back().width, 2.0);
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  // Separately mapped bays take the depth the importer measured along that side
  // (parking:<side>:separate_width), and nothing without it.
  p = plan_lanes(input(2, false, {{"parking:left", "lane"}, {"parking:right", "separate"},
                                  {"parking:right:separate_width", "5.1"}}), 13.1);
  EXPECT_EQ(layout(p), "parking/backward driving/backward driving/forward parking/forward");
  EXPECT_DOUBLE_EQ(p.lanes.back().width, 5.1);
  EXPECT_NEAR(p.lanes[1].width + p.lanes[2].width, 6.0, 1e-12);
  EXPECT_TRUE(p.notes.empty());
  EXPECT_EQ(street_parking_widths(input(2, false, {{"parking:both", "separate"}, {"parking:left:separate_width", "2"}})),
            std::make_pair(2.0, 0.0));
  EXPECT_EQ(plan_lanes(input(2, false, {{"parking:right", "separate"}}), 7.0).lanes.size(), 2u);
  p = plan_lanes(input(2, false, {{"parking:right", "separate"}, {"parking:right:separate_width", "5 m"}}), 7.0);
  EXPECT_EQ(p.lanes.size(), 2u);
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  // Parking that leaves no driving lane goes, and says so: the roadway is centred again.
  p = plan_lanes(input(2, false, {{"parking:both", "lane"}, {"parking:both:orientation", "perpendicular"}}), 11.0);
  EXPECT_EQ(layout(p), "driving/backward driving/forward");
  EXPECT_DOUBLE_EQ(p.centre_offset, 0.0);
  EXPECT_TRUE(noted(p, "lanes_do_not_fit"));
}

// A street with parking on one side: its section reaches 2 m left and 4 m right of the axis, the
// junction's curb arcs start from those borders, lanes tile the shifted section, and nothing
// overlaps.
TEST(SectionLanes, ParkingShiftsTheRoadwayAndItsCorners) {
  GeosContext ctx;
  std::vector<SurfaceAxis> axes(3);
  axes[0].id = 1;
  axes[0].line = {{0, 0}, {50, 0}, {100, 10}};
  axes[0].roadway_width = 6;
  axes[0].speed_kmh = 30;
  axes[0].lane_input = input(2, false, {{"parking:right", "lane"}});
  axes[1].id = 2;
  axes[1].line = {{100, 10}, {100, 70}};
  axes[1].roadway_width = 7;
  axes[1].speed_kmh = 30;
  axes[2].id = 3;
  axes[2].line = {{100, 10}, {100, -50}};
  axes[2].roadway_width = 7;
  axes[2].speed_kmh = 30;
  SurfaceResult r = street_surfaces(ctx, axes, {}, SurfaceSettings{});
  const SectionResult* sec = nullptr;
  for (const SectionResult& s : r.sections) {
    if (s.axis_id == 1) sec = &s;
  }
  ASSERT_TRUE(sec && sec->surface);
  // Probe across the straight first segment at x = 20: inside from y = -4 to y = 2.
  auto inside = [&](Point p) {
    GeomPtr pt = own(ctx, GEOSGeom_createPointFromXY_r(ctx.handle(), p.x, p.y), "point");
    return GEOSContains_r(ctx.handle(), sec->surface.get(), pt.get()) == 1;
  };
  EXPECT_TRUE(inside({20, 1.9}));
  EXPECT_FALSE(inside({20, 2.1}));
  EXPECT_TRUE(inside({20, -3.9}));
  EXPECT_FALSE(inside({20, -4.1}));
  // The lanes: driving 2 + 2, parking 2 on the right, tiling the section.
  std::vector<const LaneResult*> lanes;
  double sum = 0.0;
  for (const LaneResult& l : r.lanes) {
    if (l.axis_id != 1) continue;
    lanes.push_back(&l);
    sum += area(ctx, l.surface.get());
  }
  ASSERT_EQ(lanes.size(), 3u);
  EXPECT_EQ(lanes[2]->spec.type, "parking");
  EXPECT_NEAR(sum, area(ctx, sec->surface.get()), 1e-6 * area(ctx, sec->surface.get()));
  // The T junction: valid, built from its arcs (not the fallback), overlapping no section.
  ASSERT_EQ(r.intersections.size(), 1u);
  const IntersectionResult& ir = r.intersections[0];
  EXPECT_EQ(GEOSisValid_r(ctx.handle(), ir.surface.get()), 1);
  EXPECT_EQ(ir.status, "ok");
  for (const SectionResult& s : r.sections) {
    if (!s.surface) continue;
    GeomPtr o = own(ctx, GEOSIntersection_r(ctx.handle(), ir.surface.get(), s.surface.get()), "overlap");
    EXPECT_LT(area(ctx, o.get()), 1e-6) << "section of axis " << s.axis_id;
  }
  // The two corners beside axis 1 keep its sides: the arc on its right (south, towards axis 3)
  // starts 4 m from the axis, the one on its left 2 m.
  int checked = 0;
  for (const CornerResult& c : r.corners) {
    if (c.radius <= 0.0) continue;
    for (int k = 0; k < 2; ++k) {
      const EdgeEnd& e = k == 0 ? c.a : c.b;
      if (e.axis_id != 1) continue;
      Point touch = k == 0 ? c.arc.front() : c.arc.back();
      double off = signed_offset(axes[0].line, touch);
      EXPECT_NEAR(std::abs(off), off > 0 ? 2.0 : 4.0, 0.05) << "corner " << c.a.axis_id << "-" << c.b.axis_id;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2);
}

// OSM `placement`: where the way runs across its lanes (counted as `lanes` counts them).
TEST(PlanLanes, PlacementSaysWhereTheWayRuns) {
  // A one-way of three 3 m lanes drawn along the right edge of its first lane (Fremantle).
  LanePlan p = plan_lanes(input(3, true, {{"placement", "right_of:1"}}), 9.0);
  EXPECT_DOUBLE_EQ(p.centre_offset, 3.0 - 4.5);  // 3 m of roadway on its left, 6 m on its right
  EXPECT_TRUE(p.notes.empty());
  p = plan_lanes(input(3, true, {{"placement", "left_of:1"}}), 9.0);
  EXPECT_DOUBLE_EQ(p.centre_offset, -4.5);
  p = plan_lanes(input(3, true, {{"placement", "middle_of:2"}}), 9.0);
  EXPECT_DOUBLE_EQ(p.centre_offset, 0.0);
  // A cycle lane at the left curb is not counted, but its width lies left of lane 1.
  p = plan_lanes(input(2, true, {{"placement", "left_of:1"}, {"cycleway:left", "lane"}}), 7.5);
  EXPECT_EQ(layout(p), "cycle/forward driving/forward driving/forward");
  EXPECT_DOUBLE_EQ(p.centre_offset, 1.5 - 3.75);
  // transition: the default; a lane that does not exist or junk: noted and the default.
  EXPECT_DOUBLE_EQ(plan_lanes(input(3, true, {{"placement", "transition"}}), 9.0).centre_offset, 0.0);
  p = plan_lanes(input(2, true, {{"placement", "right_of:4"}}), 6.0);
  EXPECT_DOUBLE_EQ(p.centre_offset, 0.0);
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
  p = plan_lanes(input(2, true, {{"placement", "centre"}}), 6.0);
  EXPECT_TRUE(noted(p, "lane_tag_ignored"));
}
