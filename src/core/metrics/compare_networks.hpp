// How far a network (b, e.g. a grown one) is from a reference (a, e.g. the example it was grown
// from): per scalar metric the relative difference, per distribution two distances, and one
// realism score.
//
//   relative_difference  (b - a) / |a|; 0 when both are 0; NaN when a alone is 0 or either is NaN
//   ks                   two-sample Kolmogorov-Smirnov statistic (sup |Fa - Fb|); for the circular
//                        orientation histogram Kuiper's statistic (max + min gap, rotation-free)
//   wasserstein          earth mover's distance W1 in the distribution's unit (m, m², degrees, ...);
//                        on the circle for orientation
//   realism_score        1 - median over the headline metrics (street density, intersection
//                        density, mean degree, dead-end share, 4-way share, CNR, orientation order
//                        φ, median block area) of min(1, |relative difference|); 1 is identical.
//                        The "per-pair median over all metrics" is 1 - realism_score.
#pragma once
#include <string>
#include <vector>

#include "core/metrics/network_stats.hpp"
#include "core/no_postgres.hpp"

namespace streetgen::core {

struct ComparisonRow {
  std::string metric;
  std::string kind;                                          // scalar, distribution, score
  double a, b, relative_difference, ks, wasserstein, score;  // NaN where not applicable
};

std::vector<ComparisonRow> compare_networks(const NetworkStats& a, const NetworkStats& b);

// Exposed for tests.
double ks_distance(std::vector<double> a, std::vector<double> b);
double wasserstein_distance(std::vector<double> a, std::vector<double> b);
double kuiper_histogram(const std::vector<double>& a, const std::vector<double>& b);
double circular_wasserstein_histogram(const std::vector<double>& a, const std::vector<double>& b, double bin_width);

}  // namespace streetgen::core
