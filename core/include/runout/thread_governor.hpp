// How many threads a run's physics uses while other programs share its cores. The threads of
// a step meet twice (the handoff and OpenMP's join), so a step waits for whichever thread the
// scheduler has parked: two 2-thread runs on two cores ran 15 M particle-steps/s each, where
// one thread each would run near the 1-thread speed (docs/performance_log.md). The physics is
// bit-identical at any thread count, so the count can follow the cores the run actually gets.
//
// The signal is the process's own CPU time over a window of wall time: threads that are not
// parked keep running (computing or spinning), so a run that gets its cores uses about one CPU
// second per thread per second. Getting clearly less (below kFairShare of that) for two windows
// in a row (one short window is often the host, not another program), while the machine's
// cores were busy (less than kIdleCores of them idle: a run's own serial phases also leave its
// threads parked, but then a core idles), the run drops to the cores it got. Whether they are
// back cannot be told from fewer threads, so every retry interval the full count is tried again.
#pragma once

#include <functional>

namespace runout {

class ThreadGovernor {
 public:
  struct Usage {
    double wall_seconds = 0, cpu_seconds = 0;  // now, and this process's CPU time so far
    double idle_seconds = 0;  // the machine's idle CPU time so far, summed over its cores
  };
  static constexpr double kFairShare = 0.75, kIdleCores = 0.25;

  // `most`: the threads the run may use (its cores). `now`: reads the usage so far, by default
  // the steady clock, getrusage(RUSAGE_SELF) and the idle time of /proc/stat (0 where it cannot
  // be read: every short window then counts).
  explicit ThreadGovernor(int most, double window_seconds = 1.0, double retry_seconds = 30.0,
                          std::function<Usage()> now = {});

  // Called between steps, cheaply and often; the threads the run should use from now on.
  // `current` is what it uses now (a window spans one count only).
  int advise(int current);

  int most() const { return most_; }
  // The CPU seconds per wall second of the last finished window (what the run got).
  double last_cores_used() const { return last_cores_; }

 private:
  int most_;
  double window_, retry_;
  std::function<Usage()> now_;
  bool started_ = false;
  int window_threads_ = 0;
  Usage window_start_;
  double reduced_at_ = 0;  // wall time of the last drop below most
  int short_windows_ = 0;  // windows in a row that got less than the fair share
  double last_cores_ = 0, last_idle_cores_ = 0;
};

}  // namespace runout
