// The most a two-thread step can gain on this machine: a fixed amount of pure arithmetic per
// step, run on one thread, then split exactly in half over two threads that meet once a step at
// an OpenMP parallel region (as runout's step does), alternating in rounds. No data crosses
// between the threads, so whatever the ratio falls short of 2 is the host's (the hypervisor
// taking a vCPU away, one vCPU slower than the other) plus the fork and join.
// docs/performance_log.md, issue 11 twelfth session.
// KIND picks the arithmetic: `chains` (two dependent multiply-add chains: bound by latency, so
// it barely notices a sibling hyperthread of the host running beside it), `ports` (sixteen
// independent chains: bound by the core's execution ports, as runout's kernels are) or
// `stream` (a kick-drift over each thread's own L2-resident arrays of 3,500 discs: loads,
// stores and arithmetic). Issue 11, sixteenth session.
//   g++ -O2 -fopenmp scripts/lockstep_bench.cpp -o /tmp/lockstep
//   GOMP_SPINCOUNT=2000 /tmp/lockstep [STEP_US=75] [STEPS=20000] [ROUNDS=7] [KIND=chains]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

// Two independent multiply-add chains: `iterations` of them take a fixed time on one core.
double arithmetic(long iterations, double seed) {
  double a = seed, d = 0.5 * seed;
  for (long i = 0; i < iterations; ++i) {
    a = a * 1.0000001 + 1e-9;
    d = d * 0.9999999 + 1e-9;
  }
  return a + d;
}

// Sixteen independent chains: enough in flight to keep the floating-point ports busy.
double ports(long iterations, double seed) {
  double a[16];
  for (int c = 0; c < 16; ++c) a[c] = seed + c;
  for (long i = 0; i < iterations / 16; ++i)
    for (int c = 0; c < 16; ++c) a[c] = a[c] * 1.0000001 + 1e-9;
  double sum = 0;
  for (int c = 0; c < 16; ++c) sum += a[c];
  return sum;
}

// A kick-drift over one thread's own discs, SoA, sized as the bench pile (3,500 discs).
struct Discs {
  static constexpr long kCount = 3500;
  std::vector<double> x, y, vx, vy, fx, fy, inv_mass;
  Discs() : x(kCount, 1.0), y(kCount, 2.0), vx(kCount, 0.1), vy(kCount, 0.2), fx(kCount, 1e-3),
            fy(kCount, -1e-3), inv_mass(kCount, 0.5) {}
};
double stream(Discs& d, long iterations, double seed) {
  const double dt = 1e-6 * seed;
  long k = 0;
  for (long i = 0; i < iterations; ++i) {
    d.vx[k] += dt * d.fx[k] * d.inv_mass[k];
    d.vy[k] += dt * (d.fy[k] * d.inv_mass[k] - 9.81);
    d.x[k] += dt * d.vx[k];
    d.y[k] += dt * d.vy[k];
    if (++k == Discs::kCount) k = 0;
  }
  return d.x[0] + d.y[Discs::kCount - 1];
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Each thread's result on a cache line of its own, so nothing crosses between the cores.
struct alignas(64) Result { double value = 0; };

}  // namespace

int main(int argc, char** argv) {
  const double step_us = argc > 1 ? std::atof(argv[1]) : 75.0;  // the one-thread step
  const int steps = argc > 2 ? std::atoi(argv[2]) : 20000;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 7;
  const char* name = argc > 4 ? argv[4] : "chains";
  enum class Kind { chains, ports, stream, unknown };
  const Kind kind = !std::strcmp(name, "chains")   ? Kind::chains
                    : !std::strcmp(name, "ports")  ? Kind::ports
                    : !std::strcmp(name, "stream") ? Kind::stream
                                                   : Kind::unknown;
  if (!(step_us > 0) || steps < 1 || rounds < 1 || kind == Kind::unknown) {
    std::fprintf(stderr, "usage: lockstep [STEP_US > 0] [STEPS >= 1] [ROUNDS >= 1] [KIND=chains|ports|stream]\n");
    return 2;
  }
  // One thread's work takes the whole step; two threads take half each, on discs of their own.
  Discs discs[2];
  auto work = [&](long iterations, double seed) {
    if (kind == Kind::ports) return ports(iterations, seed);
    if (kind == Kind::stream) return stream(discs[omp_get_thread_num()], iterations, seed);
    return arithmetic(iterations, seed);
  };
  constexpr long kCalibration = 20000000;
  auto t0 = Clock::now();
  volatile double sink = work(kCalibration, 1.0);
  const long iterations = static_cast<long>(step_us * kCalibration / (seconds_since(t0) * 1e6));
  std::vector<double> one, two, ratio;
  for (int r = 0; r < rounds; ++r) {
    Result out[2];
    t0 = Clock::now();
    for (int k = 0; k < steps; ++k) {
#pragma omp parallel num_threads(1)
      out[0].value += work(iterations, 1.0 + k * 1e-12);
    }
    one.push_back(seconds_since(t0) / steps * 1e6);
    t0 = Clock::now();
    for (int k = 0; k < steps; ++k) {
#pragma omp parallel num_threads(2)
      out[omp_get_thread_num()].value += work(iterations / 2, 1.0 + k * 1e-12);
    }
    two.push_back(seconds_since(t0) / steps * 1e6);
    ratio.push_back(one.back() / two.back());
    sink = out[0].value + out[1].value;
    std::printf("round %d: 1 thread %.1f us a step, 2 threads %.1f us a step, two/one %.2f\n",
                r + 1, one.back(), two.back(), ratio.back());
  }
  std::printf("medians: 1 thread %.1f us, 2 threads %.1f us; two/one %.2f (median of rounds %.2f)\n",
              median(one), median(two), median(one) / median(two), median(ratio));
  return sink > 0 ? 0 : 1;
}
