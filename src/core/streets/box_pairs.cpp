// CGAL translation unit.
#include "core/streets/box_pairs.hpp"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <utility>

#include "core/interrupts.hpp"

namespace streetgen::core {

namespace {

using CgalBox = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

std::vector<CgalBox> cgal_boxes_of(const std::vector<Box>& boxes) {
  std::vector<CgalBox> cgal_boxes;
  cgal_boxes.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    double lo[2] = {b.xmin, b.ymin};
    double hi[2] = {b.xmax, b.ymax};
    cgal_boxes.emplace_back(lo, hi, i);
  }
  return cgal_boxes;
}

}  // namespace

void for_each_overlapping_pair(const std::vector<Box>& boxes, const std::function<void(std::size_t, std::size_t)>& visit) {
  std::vector<CgalBox> cgal_boxes = cgal_boxes_of(boxes);
  InterruptPoller poller(4096);
  CGAL::box_self_intersection_d(
      cgal_boxes.begin(), cgal_boxes.end(),
      [&](const CgalBox& a, const CgalBox& b) {
        poller.tick();
        std::size_t i = a.info();
        std::size_t j = b.info();
        visit(std::min(i, j), std::max(i, j));
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
}

void for_each_overlapping_cross_pair(const std::vector<Box>& a, const std::vector<Box>& b,
                                     const std::function<void(std::size_t, std::size_t)>& visit) {
  std::vector<CgalBox> cgal_a = cgal_boxes_of(a);
  std::vector<CgalBox> cgal_b = cgal_boxes_of(b);
  InterruptPoller poller(4096);
  // (BIPARTITE: each pair of one box from each range once, the first argument from the first range)
  CGAL::box_intersection_d(
      cgal_a.begin(), cgal_a.end(), cgal_b.begin(), cgal_b.end(),
      [&](const CgalBox& x, const CgalBox& y) {
        poller.tick();
        visit(x.info(), y.info());
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED, CGAL::Box_intersection_d::BIPARTITE);
}

std::vector<std::size_t> hilbert_order(const std::vector<Box>& boxes) {
  using Kernel = CGAL::Simple_cartesian<double>;
  std::vector<Kernel::Point_2> centres;
  centres.reserve(boxes.size());
  for (const Box& b : boxes) centres.emplace_back((b.xmin + b.xmax) / 2, (b.ymin + b.ymax) / 2);
  std::vector<std::size_t> order(boxes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using Traits = CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Kernel::Point_2>::type>;
  CGAL::hilbert_sort(order.begin(), order.end(), Traits(CGAL::make_property_map(centres)));
  return order;
}

}  // namespace streetgen::core
