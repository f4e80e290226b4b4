// What sees a run as it goes (frame sinks, dumps, checkpoints) and when: the one piece of the
// run (run.hpp) that the renderer's recorders need, so they do not include the whole run.
// An observer is handed the World and the run's state; it never reaches back into the run.
#pragma once

#include <functional>
#include <vector>

#include "runout/run_state.hpp"
#include "runout/world.hpp"

namespace runout {

// Something that wants to see the world at chosen times: frame sinks, dumps, checkpoints.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void observe(const World& world, const RunState& state, double t_star) = 0;
  // The cores this observer's own helper threads (a movie's drawing and encoding) are working
  // on now; asked between steps, so it may also notice here that they are done. Where these
  // and the physics' threads would be more than the process's cores, the physics steps with
  // fewer threads (at least one) until they are done: it is bit-identical at any thread count,
  // so only the speed changes, and a two-thread step loses less than a core's worth to a
  // third thread (docs/performance_log.md, issue 12, tenth session).
  virtual int helper_cores() { return 0; }
};

// When an observer fires: every `every` t* from `first`, and/or at listed times. It fires on the
// first step whose t* is within half a step of the requested time (the physics never bends to
// an observer, so attaching one does not change the results).
struct Schedule {
  double every = 0;
  double first = 0;
  std::vector<double> at;
};

// Runs `wait`, a blocking wait (for room in a helper's queue, say), on each of the run's
// `threads` physics threads at once, so every core is free while the simulation waits. An
// idle OpenMP team spins on its cores for milliseconds before it sleeps: a helper the
// simulation waits for would otherwise get one core where the physics leaves two idle
// (docs/performance_log.md, issue 12).
void wait_on_every_thread(int threads, const std::function<void()>& wait);
// The cores this process may run on (its CPU affinity): a run with fewer physics threads
// leaves its helpers a core of their own.
int available_cores();

}  // namespace runout
