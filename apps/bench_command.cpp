// `runout bench`: particle-steps per second of a settled pile and where the step's time goes
// (docs/performance.md), or with --frames the cost of drawing them.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "pictures.hpp"
#include "prepare.hpp"
#include "run_command.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/setup.hpp"

namespace runout::app {

int bench_command(const BenchOptions& o) {
  const std::string source = o.scene_path.empty() ? "<embedded bench scene>" : o.scene_path;
  SceneDef scene = load_scene(o.scene_path, o.overrides, io::embedded_bench_scene(), source);
  const SceneSetup setup = derive_setup(scene, source);
  PreparedWorld prepared = prepare(scene, setup, std::max(o.threads, omp_get_num_procs()),
                                   o.cache_dir.empty() ? default_cache_dir() : o.cache_dir, true, false);
  World& world = prepared.world;
  world.set_threads(o.threads);
  const long long warmup = o.warmup_steps >= 0 ? o.warmup_steps
                                              : static_cast<long long>(std::ceil(5.0 * setup.unit_time / setup.dt));
  for (long long s = 0; s < warmup; ++s) world.step();
  if (o.frames > 0) return bench_frames(world, scene, setup, o.picture, o.frames, 20);
  const double t_star_start = world.time() / setup.unit_time;
  const StepProfile before = world.profile();
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  for (long long s = 0; s < o.steps; ++s) world.step();
  const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  const StepProfile& after = world.profile();
  const double n = static_cast<double>(world.particles().size());
  std::printf("scene: %s\n", scene.name.c_str());
  std::printf("discs: %.0f\n", n);
  std::printf("threads: %d\n", o.threads);
  std::printf("t_star_start: %.3f\n", t_star_start);
  std::printf("steps: %lld\n", o.steps);
  std::printf("seconds: %.4f\n", secs);
  std::printf("pairs_listed_per_disc: %.3f\n", world.pairs().size() / n);
  std::printf("rebuilds: %lld\n", static_cast<long long>(after.rebuilds - before.rebuilds));
  std::printf("share_contact_forces: %.3f\n", (after.contact_forces - before.contact_forces) / secs);
  std::printf("share_integrate: %.3f\n", (after.integrate - before.integrate) / secs);
  std::printf("share_rebuild: %.3f\n", (after.rebuild - before.rebuild) / secs);
  std::printf("particle_steps_per_second: %.0f\n", n * o.steps / secs);
  return 0;
}

}  // namespace runout::app
