#include "runout/run.hpp"

#include <algorithm>
#include <cmath>

#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/timing.hpp"

namespace runout {

namespace {

// Lowest point of the scene at release: the floor in the thesis scene (Ep0 of table 3.2 is
// measured from there).
double lowest_point(const World& w) {
  double y = std::numeric_limits<double>::infinity();
  for (const auto& s : w.segments()) y = std::min({y, s.a.y(), s.b.y()});
  const auto& p = w.particles();
  for (std::size_t k = 0; k < p.size(); ++k) y = std::min(y, p.y[k] - p.radius[k]);
  return std::isfinite(y) ? y : 0.0;
}

}  // namespace

AvalancheRun::AvalancheRun(World& world, const SceneDef& scene, const SceneSetup& setup)
    : world_(world), scene_(scene), setup_(setup) {
  const auto& p = world.particles();
  state_.energy_reference_y = lowest_point(world);
  const double g = scene.integration.gravity;
  double ep = 0;
  for (std::size_t k = 0; k < p.size(); ++k) ep += p.mass[k] * g * (p.y[k] - state_.energy_reference_y);
  state_.ep0 = ep;
  state_.com_release = centre_of_mass(p);
  state_.top_release = highest_point(p);
  state_.next_sample = 0;
  state_.ledger = scene.output.series.energy;
  world.set_track_energy(state_.ledger);
  const EnergyState e = world.energy(state_.energy_reference_y);
  state_.energy_total0 = e.translational + e.rotational + e.potential + e.elastic;
  state_.committed0 = e.committed_normal;
  state_.dissipated_normal0 = world.dissipation().normal;
  state_.dissipated_friction0 = world.dissipation().friction;
  state_.dissipated_rolling0 = world.dissipation().rolling;
}

AvalancheRun::AvalancheRun(World& world, const SceneDef& scene, const SceneSetup& setup,
                           RunState state)
    : world_(world), scene_(scene), setup_(setup), state_(std::move(state)), resumed_(true) {
  // The losses before the checkpoint were counted only if the ledger was on from release.
  if (scene.output.series.energy && !state_.ledger)
    throw ConfigError("checkpoint", "output.series",
                      "the checkpoint was written by a run without the energy ledger, which cannot start midway: "
                      "resume without \"energy\" in output.series, or start the run afresh");
  world.set_track_energy(state_.ledger && scene.output.series.energy);
  state_.ledger = state_.ledger && scene.output.series.energy;
}

void AvalancheRun::add_observer(Observer& observer, Schedule schedule) {
  std::sort(schedule.at.begin(), schedule.at.end());
  Scheduled s{&observer, schedule, schedule.first, 0};
  // Skip what already happened: in a resumed run, everything due up to and including the
  // checkpoint's step (fire_observers' own test), so nothing is drawn or written twice.
  const double half_step = 0.5 * setup_.dt / setup_.unit_time;
  if (resumed_) {
    const double now = t_star();
    if (s.schedule.every > 0)
      while (now >= s.next_every - half_step) s.next_every += s.schedule.every;
    while (s.next_at < s.schedule.at.size() && now >= s.schedule.at[s.next_at] - half_step) ++s.next_at;
  }
  observers_.push_back(s);
}

double AvalancheRun::t_star() const { return world_.time() / setup_.unit_time; }

TimeseriesRow AvalancheRun::sample() const {
  const auto& p = world_.particles();
  const double d = setup_.unit_length;
  TimeseriesRow row;
  row.t_star = t_star();
  // With no potential energy at release (a lone disc on the floor) every ratio to Ep0 is
  // undefined: NaN, written as null / an empty field.
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  const double ep0 = state_.ep0 > 0 ? state_.ep0 : none;
  row.ek_over_ep0 = translational_energy(p) / ep0;
  row.erot_over_ep0 = rotational_energy(p) / ep0;
  const Eigen::Vector2d com = centre_of_mass(p);
  row.x_cm = com.x() / d;
  row.y_cm = com.y() / d;
  // Only the series an output asks for (OutputDef::series); the others stay NaN.
  const SeriesSelection& want = scene_.output.series;
  row.small_mean_height = row.large_mean_height = row.basal_spin = row.front_x = row.max_overlap = none;
  row.ep_over_ep0 = row.elastic_over_ep0 = row.dissipated_normal_over_ep0 = none;
  row.dissipated_friction_over_ep0 = row.dissipated_rolling_over_ep0 = row.residual_over_ep0 = none;
  if (want.segregation) {
    const SegregationHeights h = mean_heights(p, world_.segments(), setup_.roles);
    row.small_mean_height = h.small / d;
    row.large_mean_height = h.large / d;
  }
  if (want.basal_spin) row.basal_spin = basal_spin(p, world_.segments(), setup_.roles, setup_.unit_time);
  if (want.front) row.front_x = farthest_edge_x(p) / d;
  if (want.overlap) row.max_overlap = world_.largest_overlap_share();
  if (state_.ledger) {
    const EnergyState e = world_.energy(state_.energy_reference_y);
    const Dissipation& lost = world_.dissipation();
    const double normal = lost.normal - state_.dissipated_normal0 + e.committed_normal - state_.committed0;
    const double friction = lost.friction - state_.dissipated_friction0;
    const double rolling = lost.rolling - state_.dissipated_rolling0;
    row.ep_over_ep0 = e.potential / ep0;
    row.elastic_over_ep0 = e.elastic / ep0;
    row.dissipated_normal_over_ep0 = normal / ep0;
    row.dissipated_friction_over_ep0 = friction / ep0;
    row.dissipated_rolling_over_ep0 = rolling / ep0;
    row.residual_over_ep0 = (state_.energy_total0 - (e.translational + e.rotational + e.potential + e.elastic +
                                                     normal + friction + rolling)) / ep0;
  }
  return row;
}

void AvalancheRun::fire_observers() {
  const double half_step = 0.5 * setup_.dt / setup_.unit_time;
  const double now = t_star();
  for (auto& s : observers_) {
    bool due = false;
    if (s.schedule.every > 0 && now >= s.next_every - half_step) {
      due = true;
      while (s.next_every <= now + half_step) s.next_every += s.schedule.every;
    }
    while (s.next_at < s.schedule.at.size() && now >= s.schedule.at[s.next_at] - half_step) {
      due = true;
      ++s.next_at;
    }
    if (!due) continue;
    const auto t0 = Clock::now();
    s.observer->observe(world_, state_, now);
    observer_seconds_ += seconds_since(t0);
  }
}

std::int64_t AvalancheRun::steps_to_look(std::int64_t check_every) const {
  std::int64_t steps = check_every - world_.step_count() % check_every;
  // A time is due on the first step whose t* is within half a step of it. Counting the steps
  // to it from t* and dt may be off by one in the last bit, so the run stops a step short and
  // then goes a step at a time.
  const double steps_per_t_star = setup_.unit_time / setup_.dt, now = t_star();
  auto before = [&](double t) {
    const double ahead = std::floor((t - now) * steps_per_t_star - 0.5) - 1;
    if (ahead < static_cast<double>(steps)) steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(ahead));
  };
  before(state_.next_sample);
  if (scene_.output.end_time > 0) before(scene_.output.end_time);
  for (const auto& s : observers_) {
    if (s.schedule.every > 0) before(s.next_every);
    if (s.next_at < s.schedule.at.size()) before(s.schedule.at[s.next_at]);
  }
  return steps;
}

// While the observers' helpers work, the physics leaves them the cores it would otherwise
// share with them (Observer::helper_cores).
void AvalancheRun::share_cores() {
  int helpers = 0;
  for (auto& s : observers_) helpers += s.observer->helper_cores();
  const int lent = std::max(0, threads_ + helpers - cores_);
  const int now = std::max(1, threads_ - lent);
  if (now != world_.settings().threads) world_.set_threads(now);
}

// At rest (SPEC §5): the kinetic energy of the mass stays below the threshold (of Ep0) for
// `hold` t*. The mass is every disc touching another disc: with no rolling resistance in the
// model (as in the thesis) a lone disc rolling on the floor never stops, and must not keep the
// run going forever. The time series keeps the total E_k (eq. 4.5).
bool AvalancheRun::finished() {
  world_.check_escape(setup_.large_diameter);
  const double now = t_star();
  const auto& p = world_.particles();
  const double total = state_.ep0 > 0 ? translational_energy(p) / state_.ep0 : 0.0;
  if (total > state_.peak_ek) { state_.peak_ek = total; state_.t_star_peak_ek = now; }
  const double ratio = state_.ep0 > 0 ? mass_kinetic_energy(world_.particles(), world_.pairs()) / state_.ep0 : 0.0;
  const double half_step = 0.5 * setup_.dt / setup_.unit_time;
  const bool may_stop = now >= min_end_time_ - half_step;
  if (ratio < scene_.rest.ek_threshold) {
    if (state_.below_since < 0) state_.below_since = now;
    at_rest_ = now - state_.below_since >= scene_.rest.hold;
    if (at_rest_ && may_stop) return true;
    if (at_rest_ && !state_.rest_frozen) freeze_rest();
  } else {
    state_.below_since = -1;
    at_rest_ = false;
  }
  return now >= std::max(scene_.rest.max_time, min_end_time_);
}

void AvalancheRun::freeze_rest() {
  const Particles& p = world_.particles();
  Particles& f = state_.rest_particles;
  f = p;
  Particles::for_each_array(f, [](const char* name, auto& v) {
    if (!Particles::in_deposit(name)) v.clear();
  });
  state_.rest_sample = sample();
  state_.t_star_rest = state_.below_since;
  state_.rest_frozen = true;
}

RunResult AvalancheRun::run() {
  const auto t0 = Clock::now();
  const std::int64_t steps0 = world_.step_count();
  const auto steps_per_unit = static_cast<std::int64_t>(std::ceil(setup_.unit_time / setup_.dt));
  const std::int64_t check_every = std::max<std::int64_t>(1, steps_per_unit / 20);
  auto last_report = t0;
  fewest_threads_ = threads_ = world_.settings().threads;
  cores_ = available_cores();
  std::int64_t steps_at_report = steps0;

  auto record = [&] {
    if (t_star() >= state_.next_sample - 0.5 * setup_.dt / setup_.unit_time) {
      state_.series.push_back(sample());
      state_.series_ends_with_end_row = false;
      state_.worst_residual = std::max(state_.worst_residual, std::abs(state_.series.back().residual_over_ep0));
      state_.max_overlap = std::max(state_.max_overlap, state_.series.back().max_overlap);
      while (state_.next_sample <= t_star() + 0.5 * setup_.dt / setup_.unit_time)
        state_.next_sample += scene_.output.timeseries_every;
    }
  };
  // output.end_time is looked at every step (it is a time the user asked for, to the step); it
  // changes no state, so a run stopped there and resumed with a later end time is the run
  // that never stopped.
  const double half_step = 0.5 * setup_.dt / setup_.unit_time;
  auto end_time_reached = [&] {
    if (scene_.output.end_time > 0 && t_star() >= scene_.output.end_time - half_step) reached_end_time_ = true;
    return reached_end_time_;
  };
  // A resumed run's checkpoint was written after this step's sample and observers, and before
  // its rest test (run_command writes the last one after the end row, which is taken back).
  at_rest_ = false;
  bool done = false;
  if (!resumed_) {
    record();
    fire_observers();
    share_cores();
    done = finished();
  } else {
    if (state_.series_ends_with_end_row) state_.series.pop_back();
    state_.series_ends_with_end_row = false;
    if (world_.step_count() % check_every == 0) done = finished();
  }
  done = end_time_reached() || done;
  while (!done) {
    // Between two looks nothing is due, so those steps go in as few parallel regions as the
    // lists allow (World::advance): the same steps, the same bits.
    world_.advance(steps_to_look(check_every));
    record();
    fire_observers();
    share_cores();
    if (stop_request_ && stop_request_->load(std::memory_order_relaxed) != 0) {
      interrupted_ = true;  // no end row: the state is exactly a checkpoint taken at this step
      break;
    }
    if (end_time_reached()) done = true;
    if (world_.step_count() % check_every == 0) {
      done = finished() || done;
      if (governor_) {
        const int next = governor_->advise(threads_);
        if (next != threads_) {
          threads_ = next;
          share_cores();
          fewest_threads_ = std::min(fewest_threads_, next);
          if (threads_changed_) threads_changed_(t_star(), next, governor_->last_cores_used());
        }
      }
      // One reading of the clock serves both the interval and the next report's start.
      const auto now = Clock::now();
      const double secs = seconds_between(last_report, now);
      if (progress_ && secs >= 2.0) {
        const double rate = secs > 0 ? (world_.step_count() - steps_at_report) / secs : 0.0;
        last_report = now;
        steps_at_report = world_.step_count();
        progress_(t_star(), state_.series.empty() ? 0.0 : translational_energy(world_.particles()) / std::max(state_.ep0, 1e-300), rate);
      }
    }
  }
  world_.set_threads(threads_);  // the helpers' cores back: a later segment starts from the run's count
  // The final state is always in the series, once.
  if (!interrupted_ && (state_.series.empty() || state_.series.back().t_star != t_star())) {
    state_.series.push_back(sample());
    state_.series_ends_with_end_row = true;
  }
  const double secs = seconds_since(t0);
  state_.wall_seconds += secs;
  RunResult r = result(state_.wall_seconds);
  r.particle_steps_per_second =
      secs > 0 ? double(world_.step_count() - steps0) * double(world_.particles().size()) / secs : 0.0;
  return r;
}

RunResult AvalancheRun::result(double wall_seconds) const {
  RunResult r;
  // The deposit is measured when the mass first came to rest, even if the run went on.
  const bool frozen = state_.rest_frozen;
  const auto& p = frozen ? state_.rest_particles : world_.particles();
  r.at_rest = frozen || at_rest_;
  r.reached_end_time = reached_end_time_;
  r.interrupted = interrupted_;
  r.t_star_end = t_star();
  if (frozen) r.t_star_rest = state_.t_star_rest;
  else if (at_rest_) r.t_star_rest = state_.below_since;
  r.steps = world_.step_count();
  r.dt = setup_.dt;
  r.wall_seconds = wall_seconds;
  r.observer_seconds = observer_seconds_;
  r.fewest_threads = fewest_threads_ > 0 ? fewest_threads_ : world_.settings().threads;
  r.counts = setup_.counts;
  // Large = the species of the largest nominal diameter; everything else counts as small.
  r.n_large = setup_.counts[setup_.largest_species];
  r.n_small = 0;
  for (int c : setup_.counts) r.n_small += c;
  r.n_small -= r.n_large;
  r.com_release = state_.com_release;
  r.com_rest = centre_of_mass(p);
  r.H_cm = std::abs(r.com_rest.y() - r.com_release.y());   // eq. 4.2
  r.L_cm = std::abs(r.com_rest.x() - r.com_release.x());   // eq. 4.3
  // eq. 4.4; undefined (null) when the centre of mass did not travel: below a millionth of d,
  // L_cm is rounding noise (two discs that collide head-on and stop) and H/L would be noise too.
  r.mu_global = r.L_cm > 1e-6 * setup_.unit_length ? r.H_cm / r.L_cm : std::numeric_limits<double>::quiet_NaN();
  const double front = farthest_edge_x(p);
  r.H_front = state_.top_release.top_y - state_.energy_reference_y;
  r.L_front = front - state_.top_release.top_x;
  r.H_over_L_front = r.L_front > 0 ? r.H_front / r.L_front : std::numeric_limits<double>::quiet_NaN();
  r.ep0 = state_.ep0;
  r.peak_ek_over_ep0 = state_.peak_ek;
  r.t_star_peak_ek = state_.t_star_peak_ek;
  r.basal_layer = basal_layer(p, world_.segments(), setup_.roles, setup_.large_diameter,
                              scene_.output.basal_layer_packing);
  r.H_layer_over_d = r.basal_layer.mean_thickness / setup_.unit_length;
  r.H_layer_over_d_spread = r.basal_layer.spread / setup_.unit_length;
  r.final_basal_spin = basal_spin(p, world_.segments(), setup_.roles, setup_.unit_time);
  r.mean_height_over_d = mean_heights_by_species(p, world_.segments(), static_cast<int>(setup_.counts.size()));
  for (double& h : r.mean_height_over_d) h /= setup_.unit_length;
  r.final_energy = frozen ? state_.rest_sample : sample();
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  r.worst_energy_residual = state_.ledger
                                ? std::max(state_.worst_residual, std::abs(r.final_energy.residual_over_ep0))
                                : none;
  r.max_overlap = scene_.output.series.overlap ? std::max(state_.max_overlap, r.final_energy.max_overlap) : none;
  r.profile = world_.profile();
  return r;
}

}  // namespace runout
