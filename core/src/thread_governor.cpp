#include "runout/thread_governor.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "runout/timing.hpp"

namespace runout {

namespace {

ThreadGovernor::Usage process_usage() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  const auto wall = Clock::now();
  // The machine's idle and iowait ticks: the first line of /proc/stat, "cpu" and the counters
  // user, nice, system, idle, iowait in clock ticks (proc(5)).
  double idle = 0;
  if (std::ifstream stat("/proc/stat"); stat) {
    std::string cpu;
    unsigned long long user = 0, nice = 0, system = 0, idle_ticks = 0, iowait = 0;
    if (stat >> cpu >> user >> nice >> system >> idle_ticks >> iowait && cpu == "cpu")
      idle = static_cast<double>(idle_ticks + iowait) / static_cast<double>(sysconf(_SC_CLK_TCK));
  }
  return {seconds_between(Clock::time_point{}, wall), seconds(u.ru_utime) + seconds(u.ru_stime), idle};
}

}  // namespace

ThreadGovernor::ThreadGovernor(int most, double window_seconds, double retry_seconds,
                               std::function<Usage()> now)
    : most_(std::max(1, most)), window_(window_seconds), retry_(retry_seconds),
      now_(now ? std::move(now) : std::function<Usage()>(process_usage)) {}

int ThreadGovernor::advise(int current) {
  if (most_ == 1) return 1;
  const Usage now = now_();
  // A window starts afresh at the first call and whenever the count changed under it.
  if (!started_ || current != window_threads_) {
    started_ = true;
    window_threads_ = current;
    window_start_ = now;
    return current;
  }
  const double wall = now.wall_seconds - window_start_.wall_seconds;
  if (wall < window_) return current;
  last_cores_ = (now.cpu_seconds - window_start_.cpu_seconds) / wall;
  last_idle_cores_ = (now.idle_seconds - window_start_.idle_seconds) / wall;
  window_start_ = now;
  int next = current;
  const bool short_window = current > 1 && last_cores_ < kFairShare * current && last_idle_cores_ < kIdleCores;
  short_windows_ = short_window ? short_windows_ + 1 : 0;
  if (short_windows_ >= 2) {
    // The cores the run got, at least one; fewer than it has now.
    next = std::clamp(static_cast<int>(std::lround(last_cores_)), 1, current - 1);
    reduced_at_ = now.wall_seconds;
    short_windows_ = 0;
  } else if (short_windows_ > 0) {
    // One short window: wait for the next before judging.
  } else if (current < most_ && now.wall_seconds - reduced_at_ >= retry_) {
    next = most_;  // tried for one window; dropped again if the cores are still taken
  }
  window_threads_ = next;
  return next;
}

}  // namespace runout
