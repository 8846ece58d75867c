// CGAL translation unit.
#include "core/streets/box_pairs.hpp"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>

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

}  // namespace streetgen::core
