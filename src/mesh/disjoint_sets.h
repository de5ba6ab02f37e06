// Union-find over 0..n-1 whose root is the smallest index of its set (a representative callers can use as
// is), with path halving. Internal: connected components, welding, texture-seam charts.
#pragma once
#include <algorithm>
#include <numeric>
#include <vector>

namespace iarap::detail {

class DisjointSets {
public:
  explicit DisjointSets(int n) : parent_(static_cast<std::size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      int& p = parent_[static_cast<std::size_t>(x)];
      p = parent_[static_cast<std::size_t>(p)]; // path halving
      x = p;
    }
    return x;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }

private:
  std::vector<int> parent_;
};

} // namespace iarap::detail
