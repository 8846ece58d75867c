// Terrain and water for growth (Nishida, Garcia-Dorado & Aliaga, "Example-Driven Procedural Urban
// Roads", sections 4.3.2 and 4.3.4): the grade of a street over a DEM, the direction of the
// contour a street on a steep slope bends to, and where an arterial that meets water reaches the
// far bank (a bridge). The DEM is a GridField (heights in the units of the coordinates: metres,
// since growth needs a metric SRID); NaN cells are unknown terrain and constrain nothing.
#pragma once
#include "core/no_postgres.hpp"

#include <functional>
#include <vector>

#include "core/geos_context.hpp"
#include "core/raster/grid_field.hpp"
#include "core/streets/polyline.hpp"

namespace streetgen::core {

// The steepest grade (rise over run, 0.1 = 10 %) of segment a-b over the DEM's band 0: the
// largest |dz| / ds between bilinear samples half a cell apart along it. Pairs with an unknown
// height are skipped; 0 when nothing along it is known.
double grade(const GridField& dem, Point a, Point b);

// The terrain gradient (dz/dx, dz/dy) at p by central differences of bilinear samples one cell
// apart; NaN components where a sample is unknown.
Point terrain_gradient(const GridField& dem, Point p);

// Nishida's "bend along the contour": from direction `angle` (radians) towards the contour
// direction (perpendicular to the gradient at p) nearer to it, in steps of at most `step`
// radians, the first direction whose segment of `length` from p has a grade <= max_grade.
// NaN when none does (too steep: the segment is discarded), or when the gradient is unknown or
// flat. `allowed` filters the directions (angles at the node).
double bend_to_contour(const GridField& dem, Point p, double angle, double length, double max_grade, double step,
                       const std::function<bool(double)>& allowed);

// An arterial meeting water (Nishida: "extend the road segment until it reaches the other side of
// the river; a change in orientation is allowed so that it crosses with a shorter distance").
struct WaterCrossing {
  bool found = false;
  double angle = 0.0;  // the direction taken (radians)
  double entry = 0.0;  // metres from p along it where the water begins
  double exit = 0.0;   // where the far bank begins
  double setback = 0.0;  // metres: the bridge's far end stands this far beyond `exit`, on land
};

// From p along each of `angles` (radians; the first one is the unturned direction), the first
// water the ray meets within `approach` metres, crossed to the far bank within `max_span` metres
// of water, with `landing` metres of land beyond it that `land(a, b)` accepts (region, obstacles,
// slope: the caller's legality) before any more water. The shortest span wins, then the earlier
// angle. Not found when the water goes on past max_span (the sea), the far bank is too narrow,
// or no angle meets water within `approach`. `water` is polygonal (unioned, valid).
WaterCrossing find_water_crossing(GeosContext& geos, const GEOSGeometry* water, Point p,
                                  const std::vector<double>& angles, double approach, double max_span, double landing,
                                  const std::function<bool(Point, Point)>& land);

}  // namespace streetgen::core
