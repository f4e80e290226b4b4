// The storage of the arrays the step streams over (discs, contacts, force sums).
//
// Thread t of a step takes a contiguous block of discs and of contacts, so every such array is
// written by the first thread at its start and by the last thread at its end. The heap puts
// one array right after another, so the last thread's end of one array and the first thread's
// start of the next share pages, even cache lines: each core's prefetchers run into the lines
// the other core is writing, and those lines cross between the cores every step. On pages of its
// own, with a free page after it, an array's ends are out of the other core's reach. Each array
// starts at its own offset within its first page (from the page's address), so the k-th
// elements of a dozen arrays do not all fall in one L1 set (docs/performance_log.md, issue 11,
// twentieth session).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <new>
#include <vector>

namespace runout {

template <class T>
struct PageSpreadAllocator {
  using value_type = T;

  static constexpr std::size_t kPage = 4096, kLine = 64;
  // Smaller arrays are not worth two pages: the ordinary heap, each on whole lines.
  static constexpr std::size_t kSmallest = kPage;

  PageSpreadAllocator() noexcept = default;
  template <class U>
  PageSpreadAllocator(const PageSpreadAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    constexpr auto kLargest = static_cast<std::size_t>(std::numeric_limits<std::ptrdiff_t>::max());
    if (n > (kLargest - 3 * kPage) / sizeof(T)) throw std::bad_array_new_length();
    if (bytes < kSmallest) return static_cast<T*>(::operator new(bytes, std::align_val_t{kLine}));
    // [offset: 1-62 lines, the first holding the base] [the array] [at least one free page]
    const std::size_t total = (62 * kLine + bytes + 2 * kPage - 1) / kPage * kPage;
    void* base = std::aligned_alloc(kPage, total);
    if (base == nullptr) throw std::bad_alloc();
    const auto page = reinterpret_cast<std::uintptr_t>(base) / kPage;
    const std::size_t lines = 1 + (page * 0x9E3779B97F4A7C15ull >> 58) % 62;
    char* const start = static_cast<char*>(base) + lines * kLine;
    reinterpret_cast<void**>(start)[-1] = base;
    return reinterpret_cast<T*>(start);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kSmallest) {
      ::operator delete(p, std::align_val_t{kLine});
      return;
    }
    std::free(reinterpret_cast<void**>(p)[-1]);
  }

  template <class U>
  friend bool operator==(const PageSpreadAllocator&, const PageSpreadAllocator<U>&) noexcept {
    return true;
  }
};

// An array the step streams over.
template <class T>
using HotArray = std::vector<T, PageSpreadAllocator<T>>;

}  // namespace runout
