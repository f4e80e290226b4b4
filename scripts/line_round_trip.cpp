// How long one cache line takes to go from CPU 0 to CPU 1 and back: two threads, pinned, pass
// a counter back and forth. Where two vCPUs sit on the host decides it (docs/performance_log.md,
// issue 11 sixteenth session: ~55 ns in the host's fast mode, ~330 ns in its slow one), and
// a two-thread runout step moves a few hundred lines between its threads (the block boundary).
//   g++ -O2 -pthread scripts/line_round_trip.cpp -o /tmp/line_round_trip
//   /tmp/line_round_trip [TRIPS=200000]   -> "round trip: 55 ns"
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "pin_to_cpu.hpp"

namespace {

// Waits for the counter to reach `from`, then hands it on: the line crosses once per call.
void pass(std::atomic<long>& ball, long from) {
  while (ball.load(std::memory_order_acquire) != from) {}
  ball.store(from + 1, std::memory_order_release);
}

}  // namespace

int main(int argc, char** argv) {
  const long trips = argc > 1 ? std::atol(argv[1]) : 200000;
  if (trips < 1) {
    std::fprintf(stderr, "usage: line_round_trip [TRIPS >= 1]\n");
    return 2;
  }
  alignas(64) std::atomic<long> ball{0};
  std::atomic<bool> pinned{true};
  std::thread other([&] {
    if (!pin_to(1)) pinned = false;
    for (long k = 1; k < 2 * trips; k += 2) pass(ball, k);
  });
  if (!pin_to(0)) pinned = false;
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < 2 * trips; k += 2) pass(ball, k);
  while (ball.load(std::memory_order_acquire) != 2 * trips) {}
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  other.join();
  if (!pinned) {
    std::fprintf(stderr, "line_round_trip: could not pin to CPUs 0 and 1\n");
    return 1;
  }
  std::printf("round trip: %.0f ns\n", seconds / trips * 1e9);
  return 0;
}
