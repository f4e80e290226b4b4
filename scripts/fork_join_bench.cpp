// What a step's fork and join cost beside a team kept across steps, with the shape of runout's
// two-thread step: a short serial part (1 us) and ~35 us of work per thread. Prints, per round,
// the time a step takes beyond the work: one `omp parallel` per step against one region for all
// steps that meets at two barriers a step (docs/performance_log.md, issue 11, twentieth session).
// A measuring tool, not part of the product:
//   g++ -O2 -fopenmp scripts/fork_join_bench.cpp -o /tmp/fork_join_bench
//   GOMP_SPINCOUNT=2000 /tmp/fork_join_bench [ROUNDS=3]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace {

using Clock = std::chrono::steady_clock;

double micros_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

// Busy for `us` microseconds (a stand-in for a block's share of the step).
void work_for(double us) {
  const auto t0 = Clock::now();
  while (micros_since(t0) < us) {
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 3;
  constexpr int kSteps = 20000;
  constexpr double kWork = 35, kSerial = 1;
  for (int round = 0; round < rounds; ++round) {
    auto t0 = Clock::now();
    for (int s = 0; s < kSteps; ++s) {
      work_for(kSerial);
#pragma omp parallel num_threads(2)
      work_for(kWork);
    }
    const double fork_join = micros_since(t0) / kSteps - kWork - kSerial;
    t0 = Clock::now();
#pragma omp parallel num_threads(2)
    for (int s = 0; s < kSteps; ++s) {
#pragma omp master
      work_for(kSerial);
#pragma omp barrier
      work_for(kWork);
#pragma omp barrier
    }
    const double kept = micros_since(t0) / kSteps - kWork - kSerial;
    std::printf("round %d: fork and join %.2f us a step; a kept team, two barriers %.2f us a step\n",
                round + 1, fork_join, kept);
  }
}
