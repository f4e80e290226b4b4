// What one step's thread synchronisation costs on this machine: an empty OpenMP parallel
// region (fork + join), an OpenMP barrier inside one region, and a two-thread ping-pong on one
// atomic (the floor any barrier pays). docs/performance_log.md, issue 11 sixth session.
//   g++ -O2 -fopenmp -pthread scripts/omp_sync_bench.cpp -o /tmp/omp_sync && /tmp/omp_sync
// With LLVM's runtime instead of GCC's (Debian libomp-14-dev):
//   g++ -O2 -fopenmp -c scripts/omp_sync_bench.cpp -o /tmp/o.o &&
//   g++ /tmp/o.o -o /tmp/omp_sync_llvm -pthread -L/usr/lib/llvm-14/lib -Wl,-rpath,/usr/lib/llvm-14/lib -lomp
#include <omp.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

int main() {
  using Clock = std::chrono::steady_clock;
  constexpr int kRounds = 200000;
  auto micro = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count() / kRounds * 1e6;
  };
  volatile int sink = 0;
  auto t0 = Clock::now();
  for (int i = 0; i < kRounds; ++i) {
#pragma omp parallel num_threads(2)
    sink = sink + omp_get_thread_num();
  }
  std::printf("omp parallel region (fork + join): %.2f us\n", micro(t0));
  t0 = Clock::now();
#pragma omp parallel num_threads(2)
  for (int i = 0; i < kRounds; ++i) {
#pragma omp barrier
  }
  std::printf("omp barrier: %.2f us\n", micro(t0));
  alignas(64) std::atomic<int> flag{0};
  std::thread other([&] {
    for (int i = 0; i < kRounds; ++i) {
      while (flag.load(std::memory_order_acquire) != 2 * i + 1) {}
      flag.store(2 * i + 2, std::memory_order_release);
    }
  });
  t0 = Clock::now();
  for (int i = 0; i < kRounds; ++i) {
    flag.store(2 * i + 1, std::memory_order_release);
    while (flag.load(std::memory_order_acquire) != 2 * i + 2) {}
  }
  other.join();
  std::printf("atomic ping-pong round trip: %.2f us\n", micro(t0));
  return 0;
}
