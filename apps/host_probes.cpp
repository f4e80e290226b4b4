// The host probes of `runout bench` (host_probes.hpp).
#include "host_probes.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "runout/timing.hpp"

namespace runout::app {

namespace {

// Independent multiply–add chains, enough of them to keep a core's floating-point pipes full
// rather than wait on one chain's latency, and few enough to stay in registers. The apps are
// built without the core's -march=native, so these are 12 two-wide SSE2 chains: multiply and
// add take 3 + 3 cycles and a core issues two of each a cycle, so 12 fill the pipes. Wider
// vectors would make fewer chains, latency-bound, and a second hyperthread could then fill the
// gaps, which would lift the one-core reading above 1.
void arithmetic(long rounds) {
  std::array<double, 24> a;
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 1.0 + 1e-9 * static_cast<double>(i);
  for (long r = 0; r < rounds; ++r)
    for (double& v : a) v = v * 0.999999999 + 1e-9;
  double sum = 0;
  for (double v : a) sum += v;
  // The sum is used by nothing else: this empty statement claims it (in a general register or
  // in memory, on any target), so the loop is kept.
  asm volatile("" : : "g"(sum));
}

}  // namespace

double line_round_trip_ns(long trips) {
  alignas(64) std::atomic<long> ball{0};
  int team = 0;
  const auto start = Clock::now();
#pragma omp parallel num_threads(2)
  {
    const int me = omp_get_thread_num();
    if (me == 0) team = omp_get_num_threads();
    // spin_until yields after a while, so two threads on one CPU (a cgroup or taskset of one)
    // pass the ball at each switch rather than once per time slice (~8 ms a trip).
    if (omp_get_num_threads() == 2)
      for (long k = me; k < 2 * trips; k += 2) {
        spin_until([&] { return ball.load(std::memory_order_acquire) == k; });
        ball.store(k + 1, std::memory_order_release);
      }
  }
  const double seconds = seconds_since(start);
  return team == 2 ? seconds / static_cast<double>(trips) * 1e9 : std::nan("");
}

double arithmetic_pair_speedup(long rounds) {
  // The better of two reads of each, so a stray interrupt or a moment of the host's in one read
  // lifts neither side. Alone: the first read may also meet the other thread still spinning
  // after the region before it (OpenMP's wait policy), which on a shared core slows this one.
  double alone = 1e300;
  for (int read = 0; read < 2; ++read) {
    const auto t0 = Clock::now();
    arithmetic(rounds);
    alone = std::min(alone, seconds_since(t0));
  }
  // Together: from the first thread's start to the last one's end, so two threads that take
  // turns on one CPU count as the two loops one after the other (2 × alone / together = 1).
  double together = 1e300;
  int team = 0;
  for (int read = 0; read < 2; ++read) {
    const auto epoch = Clock::now();
    double first_start = 1e300, last_end = 0;
#pragma omp parallel num_threads(2) reduction(min : first_start) reduction(max : last_end)
    {
      if (omp_get_thread_num() == 0) team = omp_get_num_threads();
      // Both start once both are awake.
#pragma omp barrier
      first_start = seconds_since(epoch);
      arithmetic(rounds);
      last_end = seconds_since(epoch);
    }
    together = std::min(together, last_end - first_start);
  }
  return team == 2 ? 2 * alone / together : std::nan("");
}

}  // namespace runout::app
