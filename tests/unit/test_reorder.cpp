// apply_order and stable_order against std::stable_sort on a copy, with move-only items that
// count their moves (the point of the helpers: a city's outputs put in order without a second
// vector of them).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "core/reorder.hpp"

namespace streetgen::core {
namespace {

struct Item {
  int key;
  std::unique_ptr<int> payload;  // move-only, as a GEOS geometry's owner is
};

TEST(Reorder, StableOrderAppliedInPlaceIsStableSort) {
  std::mt19937 rng(42);
  for (std::size_t n : {0u, 1u, 2u, 7u, 100u, 5000u}) {
    std::uniform_int_distribution<int> key(0, static_cast<int>(n / 3));  // many equal keys
    std::vector<Item> items;
    std::vector<std::pair<int, int>> expected;  // (key, payload) in std::stable_sort's order
    for (std::size_t i = 0; i < n; ++i) {
      int k = key(rng);
      items.push_back({k, std::make_unique<int>(static_cast<int>(i))});
      expected.emplace_back(k, static_cast<int>(i));
    }
    std::stable_sort(expected.begin(), expected.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<int> keys;
    for (const Item& it : items) keys.push_back(it.key);
    const Item* storage = items.data();
    apply_order(items, stable_order(keys));
    ASSERT_EQ(items.size(), n);
    EXPECT_EQ(items.data(), storage) << "sorted in place, not into another vector";
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(items[i].payload) << "item " << i << " lost in a cycle";
      EXPECT_EQ(items[i].key, expected[i].first) << i;
      EXPECT_EQ(*items[i].payload, expected[i].second) << i;
    }
  }
}

TEST(Reorder, ApplyOrderFollowsEveryCycle) {
  // position k takes item order[k]: cycles (0 3 1), (2), (4 5)
  std::vector<int> items = {10, 11, 12, 13, 14, 15};
  apply_order(items, {3, 0, 2, 1, 5, 4});
  EXPECT_EQ(items, (std::vector<int>{13, 10, 12, 11, 15, 14}));
  std::vector<int> reversed = {1, 2, 3, 4, 5};
  apply_order(reversed, {4, 3, 2, 1, 0});
  EXPECT_EQ(reversed, (std::vector<int>{5, 4, 3, 2, 1}));
}

}  // namespace
}  // namespace streetgen::core
