// The box joins against brute force on random boxes (with shared edges and corners: closed boxes).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/streets/box_pairs.hpp"

namespace streetgen::core {
namespace {

bool overlap(const Box& p, const Box& q) {
  return p.xmin <= q.xmax && q.xmin <= p.xmax && p.ymin <= q.ymax && q.ymin <= p.ymax;
}

// Boxes on a coarse grid of coordinates, so that many touch along an edge or at a corner.
std::vector<Box> random_boxes(std::mt19937& rng, std::size_t n) {
  std::uniform_int_distribution<int> at(0, 40), size(0, 6);
  std::vector<Box> boxes;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = at(rng), y = at(rng);
    boxes.push_back({x, y, x + size(rng), y + size(rng)});
  }
  return boxes;
}

TEST(BoxPairs, CrossPairsAreThePairsBetweenTheTwoSetsEachOnceInTheirOrder) {
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    const std::vector<Box> a = random_boxes(rng, 30 + round * 7);
    const std::vector<Box> b = random_boxes(rng, 200 + round * 11);
    std::set<std::pair<std::size_t, std::size_t>> expected;
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (std::size_t j = 0; j < b.size(); ++j) {
        if (overlap(a[i], b[j])) expected.emplace(i, j);
      }
    }
    std::vector<std::pair<std::size_t, std::size_t>> found;
    for_each_overlapping_cross_pair(a, b, [&](std::size_t i, std::size_t j) { found.emplace_back(i, j); });
    std::set<std::pair<std::size_t, std::size_t>> unique(found.begin(), found.end());
    EXPECT_EQ(unique.size(), found.size()) << "a pair reported twice, round " << round;
    EXPECT_EQ(unique, expected) << "round " << round;
    ASSERT_FALSE(expected.empty());
  }
  // Either set empty: no pair.
  const std::vector<Box> some = random_boxes(rng, 10);
  long calls = 0;
  for_each_overlapping_cross_pair({}, some, [&](std::size_t, std::size_t) { ++calls; });
  for_each_overlapping_cross_pair(some, {}, [&](std::size_t, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(BoxPairs, SelfPairsAreEveryOverlappingPairOnceWithTheSmallerIndexFirst) {
  std::mt19937 rng(11);
  const std::vector<Box> boxes = random_boxes(rng, 300);
  std::set<std::pair<std::size_t, std::size_t>> expected;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      if (overlap(boxes[i], boxes[j])) expected.emplace(i, j);
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> found;
  for_each_overlapping_pair(boxes, [&](std::size_t i, std::size_t j) { found.emplace_back(i, j); });
  const std::set<std::pair<std::size_t, std::size_t>> unique(found.begin(), found.end());
  EXPECT_EQ(unique.size(), found.size());
  EXPECT_EQ(unique, expected);
  ASSERT_FALSE(expected.empty());
}

}  // namespace
}  // namespace streetgen::core
