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

void for_each_overlapping_pair(const std::vector<Box>& boxes, const std::function<void(std::size_t, std::size_t)>& visit) {
  using CgalBox = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
  std::vector<CgalBox> cgal_boxes;
  cgal_boxes.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    double lo[2] = {b.xmin, b.ymin};
    double hi[2] = {b.xmax, b.ymax};
    cgal_boxes.emplace_back(lo, hi, i);
  }
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
