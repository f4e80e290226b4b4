// What one system call costs on this machine: a futex wake with no one waiting (what
// libgomp calls at every fork, join and barrier), sched_yield (what a two-thread runout step's
// wait does after its spin) and getppid (the bare entry and exit). On the VMs of
// docs/performance_log.md (issue 11, twenty-eighth session) each took ~1.2-1.8 us, so a wait
// that yields notices its flag that much later. Run it on
// an otherwise idle machine: with another task runnable, sched_yield also times that task.
//   g++ -O2 scripts/syscall_cost.cpp -o /tmp/syscall_cost
//   /tmp/syscall_cost [CALLS=200000]   -> "futex_wake 1201 ns, sched_yield 1426 ns, getppid 1207 ns"
#include <linux/futex.h>
#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  long calls = 200000;
  char* end = nullptr;
  if (argc > 1) calls = std::strtol(argv[1], &end, 10);
  if (argc > 2 || calls < 1 || (argc > 1 && (end == argv[1] || *end != '\0'))) {
    std::fprintf(stderr, "usage: syscall_cost [CALLS]: one argument, a positive whole count\n");
    return 2;
  }
  using Clock = std::chrono::steady_clock;
  auto per_call = [calls](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::nano>(b - a).count() / static_cast<double>(calls);
  };
  int word = 0;
  const auto t0 = Clock::now();
  for (long i = 0; i < calls; ++i) syscall(SYS_futex, &word, FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
  const auto t1 = Clock::now();
  for (long i = 0; i < calls; ++i) sched_yield();
  const auto t2 = Clock::now();
  for (long i = 0; i < calls; ++i) syscall(SYS_getppid);
  const auto t3 = Clock::now();
  std::printf("futex_wake %.0f ns, sched_yield %.0f ns, getppid %.0f ns\n", per_call(t0, t1),
              per_call(t1, t2), per_call(t2, t3));
  return 0;
}
