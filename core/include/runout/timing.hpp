// Wall-clock time for the profiles, benches and progress lines, and the wait of one thread on
// another: one place for both, used by the core and by the command line alike.
#pragma once

#include <chrono>
#include <thread>

namespace runout {

// A steady clock: the profiles and rates must not jump when the system clock is set.
using Clock = std::chrono::steady_clock;

inline double seconds_between(Clock::time_point t0, Clock::time_point t1) {
  return std::chrono::duration<double>(t1 - t0).count();
}

inline double seconds_since(Clock::time_point t0) { return seconds_between(t0, Clock::now()); }

// Waits until `ready()`: a short spin (the other thread is nearly always there by now), then
// yielding, so threads that share a CPU (more threads than cores, a cgroup or taskset of one)
// hand it over at each yield rather than spin away the other's time slice.
template <class Ready>
void spin_until(Ready ready) {
  for (int spins = 0; !ready(); ++spins)
    if (spins > 4096) std::this_thread::yield();
}

}  // namespace runout
