// Helper threads (drawing, encoding) run only on cores the simulation leaves idle (Linux
// SCHED_IDLE): preempting a physics thread mid-phase would stall its partner at the next
// barrier, so a frame would cost twice its CPU time. When every core is stepping, frames wait
// in their queue; when the queue is full the simulation pauses briefly and both cores draw.
#pragma once

#include <pthread.h>
#include <sched.h>

namespace runout::render {

inline void run_when_idle() {
  sched_param param{};
  param.sched_priority = 0;
  pthread_setschedparam(pthread_self(), SCHED_IDLE, &param);  // best effort: ignore failure
}

}  // namespace runout::render
