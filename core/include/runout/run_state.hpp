// What a run carries between steps and a checkpoint keeps of it (RunState), and the time
// series rows it samples: what observers are handed with the World (observer.hpp).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "runout/measure.hpp"
#include "runout/particles.hpp"

namespace runout {

struct TimeseriesRow {
  double t_star = 0;
  double ek_over_ep0 = 0;     // translational, eq. 4.5
  double erot_over_ep0 = 0;
  double x_cm = 0, y_cm = 0;  // in d
  double small_mean_height = 0, large_mean_height = 0;  // in d, above the bed
  double basal_spin = 0;      // omega sqrt(d/g) of small discs touching the bed
  double front_x = 0;         // farthest disc edge, in d
  // Energy ledger since release, each over Ep0 (SPEC §8): E_total(0) = ep + ek + erot + elastic
  // + dissipated_normal + dissipated_friction + dissipated_rolling + residual; the residual is
  // the integrator's error.
  double ep_over_ep0 = 0;
  double elastic_over_ep0 = 0;
  double dissipated_normal_over_ep0 = 0;
  double dissipated_friction_over_ep0 = 0;
  double dissipated_rolling_over_ep0 = 0;  // rolling resistance (contact.rolling_model)
  double residual_over_ep0 = 0;
  double max_overlap = 0;  // largest overlap / smaller radius among touching disc pairs now
};

// Everything a run carries between steps; saved in checkpoints so a run resumes exactly.
struct RunState {
  bool ledger = true;  // the energy ledger is kept (fixed at release: a resume cannot start it midway)
  double ep0 = 0;
  double energy_reference_y = 0;
  Eigen::Vector2d com_release{0, 0};
  FrontReach top_release;
  double below_since = -1;  // t* since which E_k/Ep0 has stayed below the threshold
  double peak_ek = 0, t_star_peak_ek = 0;
  double next_sample = 0;
  std::vector<TimeseriesRow> series;
  // The last row of `series` is the end row run() adds when it stops (not a scheduled sample):
  // a run resumed from its final checkpoint takes it back, so it is not there twice.
  bool series_ends_with_end_row = false;
  double wall_seconds = 0;  // spent before a resume
  // Ledger origin at release: total energy, committed hysteresis and dissipation counters.
  double energy_total0 = 0, committed0 = 0, dissipated_normal0 = 0, dissipated_friction0 = 0,
         dissipated_rolling0 = 0;
  double worst_residual = 0;  // largest |residual| / Ep0 seen
  double max_overlap = 0;     // largest overlap / smaller radius seen in the samples
  // The discs when the mass first came to rest, kept only when the run goes on after that
  // (to a later snapshot): the deposit (mu, L_cm, H/L, basal layer, final sample) is measured
  // there, so a later snapshot does not change it. Run-long figures (peak E_k, worst residual,
  // largest overlap, the time series) still cover the whole run.
  bool rest_frozen = false;
  double t_star_rest = 0;
  Particles rest_particles;  // only the arrays of Particles::for_each_deposit are filled
  TimeseriesRow rest_sample;

  // The one list of what a checkpoint keeps of a run, in the codec's order (the deposit at
  // rest follows, when frozen): f(name, member, bookkeeping). Bookkeeping values are the
  // run's own and never NaN; the others are measurements, which may be undefined.
  template <class Self, class F>
  static void for_each_stored(Self& s, F&& f) {
    f("ledger", s.ledger, true);
    f("ep0", s.ep0, true); f("energy_reference_y", s.energy_reference_y, true);
    f("com_release.x", s.com_release.x(), true); f("com_release.y", s.com_release.y(), true);
    f("top_release.top_x", s.top_release.top_x, true); f("top_release.top_y", s.top_release.top_y, true);
    f("below_since", s.below_since, true); f("peak_ek", s.peak_ek, true);
    f("t_star_peak_ek", s.t_star_peak_ek, true); f("next_sample", s.next_sample, true);
    f("wall_seconds", s.wall_seconds, true);
    f("energy_total0", s.energy_total0, true); f("committed0", s.committed0, true);
    f("dissipated_normal0", s.dissipated_normal0, true);
    f("dissipated_friction0", s.dissipated_friction0, true);
    f("dissipated_rolling0", s.dissipated_rolling0, true);
    f("worst_residual", s.worst_residual, false);
    f("max_overlap", s.max_overlap, false);
    f("series", s.series, false);
    f("series_ends_with_end_row", s.series_ends_with_end_row, true);
    f("rest_frozen", s.rest_frozen, true);
  }
  // Kept only when rest_frozen.
  template <class Self, class F>
  static void for_each_stored_at_rest(Self& s, F&& f) {
    f("t_star_rest", s.t_star_rest, true);
    f("rest_sample", s.rest_sample, false);
  }
};
std::string encode_run_state(const RunState& s);
RunState decode_run_state(const std::string& bytes, const std::string& name);


}  // namespace runout
