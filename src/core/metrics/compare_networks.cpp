#include "core/metrics/compare_networks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace streetgen::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double relative_difference(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return kNaN;
  if (a == 0.0) return b == 0.0 ? 0.0 : kNaN;
  return (b - a) / std::abs(a);
}

std::vector<double> as_doubles(const std::vector<int>& v) { return std::vector<double>(v.begin(), v.end()); }

// Cumulative histograms after normalising each to sum 1; empty if either sums to 0.
bool cumulative_gaps(const std::vector<double>& a, const std::vector<double>& b, std::vector<double>& gaps) {
  if (a.size() != b.size() || a.empty()) return false;
  double sa = 0.0, sb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sa += a[i];
    sb += b[i];
  }
  if (!(sa > 0.0) || !(sb > 0.0)) return false;
  double fa = 0.0, fb = 0.0;
  gaps.clear();
  for (std::size_t i = 0; i < a.size(); ++i) {
    fa += a[i] / sa;
    fb += b[i] / sb;
    gaps.push_back(fa - fb);
  }
  return true;
}

}  // namespace

double ks_distance(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return kNaN;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::size_t i = 0, j = 0;
  double d = 0.0;
  while (i < a.size() || j < b.size()) {
    double x = j == b.size() || (i < a.size() && a[i] <= b[j]) ? a[i] : b[j];
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d, std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return d;
}

double wasserstein_distance(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return kNaN;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::size_t i = 0, j = 0;
  double w = 0.0, prev = std::min(a.front(), b.front());
  while (i < a.size() || j < b.size()) {
    double x = j == b.size() || (i < a.size() && a[i] <= b[j]) ? a[i] : b[j];
    w += std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()) * (x - prev);
    prev = x;
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
  }
  return w;
}

double kuiper_histogram(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> gaps;
  if (!cumulative_gaps(a, b, gaps)) return kNaN;
  auto [lo, hi] = std::minmax_element(gaps.begin(), gaps.end());
  return std::max(*hi, 0.0) - std::min(*lo, 0.0);
}

// W1 on the circle between two histograms: min over c of sum |G_i - c| x bin width, reached at
// the median of the cumulative gaps G_i (Rabin, Delon and Gousseau 2011).
double circular_wasserstein_histogram(const std::vector<double>& a, const std::vector<double>& b, double bin_width) {
  std::vector<double> gaps;
  if (!cumulative_gaps(a, b, gaps)) return kNaN;
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  double c = sorted[sorted.size() / 2];
  double w = 0.0;
  for (double g : gaps) w += std::abs(g - c);
  return w * bin_width;
}

std::vector<ComparisonRow> compare_networks(const NetworkStats& a, const NetworkStats& b) {
  std::vector<ComparisonRow> rows;
  std::vector<double> headline;
  const auto& table = metric_table();
  for (std::size_t m = 0; m < kMetricCount; ++m) {
    double rd = relative_difference(a.value[m], b.value[m]);
    rows.push_back({table[m].name, "scalar", a.value[m], b.value[m], rd, kNaN, kNaN, kNaN});
    if (table[m].headline && !std::isnan(rd)) headline.push_back(std::min(1.0, std::abs(rd)));
  }
  auto distribution = [&](const char* name, const std::vector<double>& x, const std::vector<double>& y) {
    rows.push_back({name, "distribution", kNaN, kNaN, kNaN, ks_distance(x, y), wasserstein_distance(x, y), kNaN});
  };
  distribution("degree", as_doubles(a.degrees), as_doubles(b.degrees));
  distribution("segment_length", a.segment_lengths, b.segment_lengths);
  distribution("block_area", a.block_areas, b.block_areas);
  distribution("block_compactness", a.block_compactness, b.block_compactness);
  distribution("block_aspect_ratio", a.block_aspect_ratios, b.block_aspect_ratios);
  rows.push_back(
      {"orientation", "distribution", kNaN, kNaN, kNaN,
       kuiper_histogram(a.orientation_histogram, b.orientation_histogram),
       circular_wasserstein_histogram(a.orientation_histogram, b.orientation_histogram, 360.0 / kOrientationBins),
       kNaN});
  double median = kNaN;
  if (!headline.empty()) {
    std::sort(headline.begin(), headline.end());
    median = quantile_sorted(headline, 0.5);
  }
  rows.push_back({"median_abs_relative_difference", "score", kNaN, kNaN, kNaN, kNaN, kNaN, median});
  rows.push_back({"realism_score", "score", kNaN, kNaN, kNaN, kNaN, kNaN, std::isnan(median) ? kNaN : 1.0 - median});
  return rows;
}

}  // namespace streetgen::core
