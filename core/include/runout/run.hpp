// The run: steps a World from release (t* = 0) until the mass is at rest again (a measured
// criterion, SPEC §5), an end time, or the time limit; samples the time series of SPEC §6;
// calls observers at chosen t*; and reports the study's measurements.
#pragma once

#include <atomic>
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "runout/measure.hpp"
#include "runout/observer.hpp"
#include "runout/run_state.hpp"
#include "runout/setup.hpp"
#include "runout/thread_governor.hpp"
#include "runout/world.hpp"

namespace runout {

struct RunResult {
  bool at_rest = false;
  bool reached_end_time = false;  // stopped by output.end_time
  bool interrupted = false;       // stopped on request (a signal) after a whole step: resumable
  double t_star_rest = std::numeric_limits<double>::quiet_NaN();
  double t_star_end = 0;
  std::int64_t steps = 0;
  double dt = 0;
  double wall_seconds = 0;
  double particle_steps_per_second = 0;
  std::vector<int> counts;  // per species
  std::vector<double> mean_height_over_d;  // per species, of the deposit (NaN: none of it)
  int n_large = 0, n_small = 0;
  Eigen::Vector2d com_release{0, 0}, com_rest{0, 0};
  double H_cm = 0, L_cm = 0, mu_global = 0;  // eqs. 4.2–4.4, metres
  double H_front = 0, L_front = 0, H_over_L_front = 0;
  double ep0 = 0;
  double peak_ek_over_ep0 = 0, t_star_peak_ek = 0;
  BasalLayer basal_layer;
  double H_layer_over_d = 0, H_layer_over_d_spread = 0;
  double final_basal_spin = 0;
  TimeseriesRow final_energy;        // the ledger at the end
  double worst_energy_residual = 0;  // largest |residual| / Ep0 over the run
  double max_overlap = 0;            // largest overlap / smaller radius seen in the samples
  StepProfile profile;
  // Wall time the simulation thread spent in observers this segment (planning pictures and
  // waiting for their helpers, writing checkpoints, dumps, VTK frames): what they cost the run.
  double observer_seconds = 0;
  // The fewest threads the physics stepped with this segment (below the run's count only where
  // a ThreadGovernor gave cores back to other programs; not the steps that left a core to the
  // observers' helpers).
  int fewest_threads = 0;
};

class AvalancheRun {
 public:
  // `world` is at t* = 0 (just released, or an explicit scene at its start).
  AvalancheRun(World& world, const SceneDef& scene, const SceneSetup& setup);
  // Continues from a checkpointed state instead.
  AvalancheRun(World& world, const SceneDef& scene, const SceneSetup& setup, RunState state);

  void add_observer(Observer& observer, Schedule schedule);
  // Progress: called about every t* unit with (t*, E_k/Ep0, steps per second).
  void set_progress(std::function<void(double, double, double)> progress) { progress_ = std::move(progress); }
  // The run goes on at least until this t* even once at rest (the last requested snapshot).
  void set_min_end_time(double t_star) { min_end_time_ = t_star; }
  // Looked at between steps (at least every 1/20 t*); once non-zero the run stops there,
  // before that step's rest test, so its state is a checkpoint's and a resume continues
  // exactly (SIGINT, SIGTERM).
  void set_stop_request(const std::atomic<int>* flag) { stop_request_ = flag; }
  // The physics' thread count follows the governor's advice, asked between steps (about every
  // 1/20 t*); `changed(t*, threads, cores_used)` hears of each change. The trajectory does not
  // depend on it.
  void set_thread_governor(ThreadGovernor* governor, std::function<void(double, int, double)> changed = {}) {
    governor_ = governor;
    threads_changed_ = std::move(changed);
  }
  RunResult run();

  const RunState& state() const { return state_; }
  double t_star() const;
  TimeseriesRow sample() const;

 private:
  struct Scheduled {
    Observer* observer;
    Schedule schedule;
    double next_every;
    std::size_t next_at = 0;
  };
  void fire_observers();
  void share_cores();
  // Steps the run can take before it must look again: up to the next sample, observer time,
  // end time or check (every `check_every` steps), never past one (World::advance).
  std::int64_t steps_to_look(std::int64_t check_every) const;
  bool finished();
  void freeze_rest();
  RunResult result(double wall_seconds) const;

  World& world_;
  const SceneDef& scene_;
  const SceneSetup& setup_;
  RunState state_;
  std::vector<Scheduled> observers_;
  std::function<void(double, double, double)> progress_;
  bool at_rest_ = false;
  // Continued from a checkpoint: the samples, observers and rest test of the checkpoint's own
  // step already ran before it was written (the uninterrupted run's schedule, SPEC §5).
  bool resumed_ = false;
  const std::atomic<int>* stop_request_ = nullptr;
  ThreadGovernor* governor_ = nullptr;
  std::function<void(double, int, double)> threads_changed_;
  int fewest_threads_ = 0;
  int threads_ = 1;  // the physics' threads but for the observers' helpers: the run's, or the governor's
  int cores_ = 1;    // the process's cores
  bool interrupted_ = false;
  bool reached_end_time_ = false;
  double min_end_time_ = 0;
  double observer_seconds_ = 0;
};

}  // namespace runout
