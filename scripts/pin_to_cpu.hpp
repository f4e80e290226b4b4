// Pins the calling thread to one CPU, for the two-vCPU probes in scripts/ (line_round_trip.cpp,
// line_handoff_probe.cpp): what they measure depends on which CPU each thread runs on.
#pragma once

#include <pthread.h>
#include <sched.h>

inline bool pin_to(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}
