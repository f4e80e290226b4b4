// What two threads pay for streaming over adjacent halves of the same arrays (the blocks of a
// two-thread step, core/src/world.cpp) against the same halves with a page of memory between
// them. Each "step" every thread runs a kick–drift-like update over its half of F/2 pairs of
// arrays and the two meet at a barrier. No line is written by both threads; the block boundary
// sits on a cache line boundary. What differs is only what the cores' prefetchers fetch beyond
// the end of the half they stream (docs/performance_log.md, issue 11, nineteenth session). The
// earlier half streamed by one thread while the other only meets it at the barrier is the floor.
//
//   g++ -O3 -march=native -fopenmp scripts/block_boundary_bench.cpp -o /tmp/block_boundary_bench
//   GOMP_SPINCOUNT=2000 /tmp/block_boundary_bench [ROUNDS=3] [STEPS=20000] [gaps]
// With `gaps`, the adjacent layout with 0 to 512 doubles between the halves instead: how far
// the prefetchers run on (docs/performance_log.md, issue 11, thirty-fifth session).
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace {

constexpr int kDiscs = 3504, kHalf = 1752;  // 1752 doubles = 219 lines: the halves share no line
constexpr int kArrays = 24;                 // 12 (position, velocity) pairs
constexpr int kPage = 512;                  // doubles

enum class Layout { adjacent, page_apart, earlier_descending, earlier_alone };

void update(double* __restrict x, double* __restrict v, int i) {
  v[i] = v[i] * 0.999 + 1e-9;
  x[i] += v[i] * 1e-6;
}

double step_us(Layout layout, int steps, int gap_between = 0) {
  const int gap = layout == Layout::page_apart ? kPage : gap_between;
  const std::size_t bytes = ((kDiscs + gap) * sizeof(double) + 4095) / 4096 * 4096;
  std::vector<double*> a(kArrays);
  for (auto& p : a) {
    p = static_cast<double*>(std::aligned_alloc(4096, bytes));  // 4 KB aligned: a page apart from the next
    for (int i = 0; i < kDiscs + gap; ++i) p[i] = 1.0;
  }
  const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel num_threads(2)
  {
    const int t = omp_get_thread_num();
    const int lo = t == 0 ? 0 : kHalf + gap, hi = t == 0 ? kHalf : kDiscs + gap;
    const bool down = t == 0 && layout == Layout::earlier_descending;
    const bool idle = t == 1 && layout == Layout::earlier_alone;
    for (int s = 0; s < steps; ++s) {
      for (int k = 0; k < kArrays && !idle; k += 2) {
        if (down)
          for (int i = hi - 1; i >= lo; --i) update(a[k], a[k + 1], i);
        else
          for (int i = lo; i < hi; ++i) update(a[k], a[k + 1], i);
      }
#pragma omp barrier
    }
  }
  const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  for (auto* p : a) std::free(p);
  return us / steps;
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 3, steps = argc > 2 ? std::atoi(argv[2]) : 20000;
  if (argc > 3 && std::string_view(argv[3]) == "gaps") {
    for (int r = 1; r <= rounds; ++r) {
      std::printf("round %d, us a step by gap (doubles):", r);
      for (const int gap : {0, 8, 16, 32, 64, 128, 256, 512})
        std::printf("  %d: %.2f", gap, step_us(Layout::adjacent, steps, gap));
      std::printf("\n");
    }
    return 0;
  }
  for (int r = 1; r <= rounds; ++r)
    std::printf("round %d, us a step: adjacent halves %.2f, a page apart %.2f, adjacent with the earlier "
                "thread streaming down %.2f, the earlier half alone %.2f\n",
                r, step_us(Layout::adjacent, steps), step_us(Layout::page_apart, steps),
                step_us(Layout::earlier_descending, steps), step_us(Layout::earlier_alone, steps));
}
