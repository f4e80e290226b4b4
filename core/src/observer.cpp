// The threading helpers observer.hpp declares for observers that wait on helpers of their own
// (the picture recorders): they are about the physics' OpenMP team, so they live with it in core.
#include "runout/observer.hpp"

#include <omp.h>

namespace runout {

int available_cores() { return omp_get_num_procs(); }

void wait_on_every_thread(int threads, const std::function<void()>& wait) {
  if (threads <= 1) return wait();
#pragma omp parallel num_threads(threads)
  wait();
}

}  // namespace runout
