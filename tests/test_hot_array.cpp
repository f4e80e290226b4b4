// The storage of the step's arrays (hot_array.hpp): each large array on a cache line's start,
// with at least a page of nothing after it, and the arrays at different offsets in their pages.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <set>
#include <vector>

#include "runout/hot_array.hpp"

namespace runout {
namespace {

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

TEST(HotArray, LargeArraysStartALineAndLieAPageApart) {
  // The bench pile's disc arrays, and a few of its contact arrays.
  std::vector<HotArray<double>> doubles(8, HotArray<double>(3500, 1.0));
  std::vector<HotArray<std::int32_t>> ints(4, HotArray<std::int32_t>(7300, 2));
  struct Span { std::uintptr_t begin, end; };
  std::vector<Span> spans;
  for (const auto& v : doubles) spans.push_back({address(v.data()), address(v.data() + v.size())});
  for (const auto& v : ints) spans.push_back({address(v.data()), address(v.data() + v.size())});
  std::set<std::uintptr_t> offsets;
  for (const Span& a : spans) {
    EXPECT_EQ(a.begin % 64, 0u);
    offsets.insert(a.begin % 4096);
    for (const Span& b : spans)
      if (&a != &b && b.begin >= a.end) EXPECT_GE(b.begin - a.end, 4096u) << "a page after each array";
  }
  // 12 arrays; offsets drawn from 62 lines: all on one line would mean no spread at all.
  EXPECT_GT(offsets.size(), 1u);
}

TEST(HotArray, SmallArraysStartALine) {
  for (std::size_t n : {1, 7, 100, 511}) {
    const HotArray<double> v(n, 3.0);
    EXPECT_EQ(address(v.data()) % 64, 0u) << n;
  }
}

TEST(HotArray, KeepsItsValuesThroughGrowthAndCopies) {
  HotArray<double> v;
  for (int k = 0; k < 5000; ++k) v.push_back(0.5 * k);  // through small and large storage
  HotArray<double> copy = v;
  v.resize(100);
  v.shrink_to_fit();
  ASSERT_EQ(copy.size(), 5000u);
  for (int k = 0; k < 5000; ++k) ASSERT_EQ(copy[k], 0.5 * k);
  for (int k = 0; k < 100; ++k) ASSERT_EQ(v[k], 0.5 * k);
}

}  // namespace
}  // namespace runout
