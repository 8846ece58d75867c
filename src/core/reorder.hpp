// Putting a vector's items in another order without a second vector of them.
#pragma once
#include "core/no_postgres.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace streetgen::core {

// Moves items[order[k]] to position k for every k, in place: `order` must be a permutation of
// 0..items.size()-1. Each cycle of the permutation is followed once, holding one item aside, so
// the items (a city's outputs) are never held twice. Items are moved, never copied.
template <class T>
void apply_order(std::vector<T>& items, const std::vector<std::size_t>& order) {
  std::vector<bool> placed(items.size(), false);
  for (std::size_t start = 0; start < items.size(); ++start) {
    if (placed[start]) continue;
    T aside = std::move(items[start]);
    std::size_t k = start;
    for (;;) {
      placed[k] = true;
      std::size_t from = order[k];
      if (from == start) {
        items[k] = std::move(aside);
        break;
      }
      items[k] = std::move(items[from]);
      k = from;
    }
  }
}

// The order that sorts `keys` (std::stable_sort's: equal keys keep their order), for apply_order.
template <class Key>
std::vector<std::size_t> stable_order(const std::vector<Key>& keys) {
  std::vector<std::size_t> order(keys.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  return order;
}

}  // namespace streetgen::core
