// The energy ledger's state terms (SPEC §8): kinetic, potential, and what the contacts hold.
#include <cmath>

#include "step_phases.hpp"

namespace runout {

EnergyState World::energy(double reference_y) const {
  EnergyState e;
  const auto& p = particles_;
  const double g = -settings_.gravity.y();
  for (std::size_t k = 0; k < p.size(); ++k) {
    e.translational += 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k]);
    e.rotational += 0.5 / p.inv_inertia[k] * p.omega[k] * p.omega[k];
    e.potential += p.mass[k] * g * (p.y[k] - reference_y);
  }
  // Springs of the touching contacts; the history arrays hold this step's state.
  const phases::ContactEnergy c =
      phases::contact_energy({settings_, segments_, laws_}, p, pairs_, wall_contacts_);
  e.elastic = c.elastic;
  e.committed_normal = c.committed_normal;
  return e;
}

double World::largest_overlap_share() const {
  const auto& p = particles_;
  double largest = 0;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const std::int32_t i = pairs_.i[q], j = pairs_.j[q];
    const double overlap = p.radius[i] + p.radius[j] - std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
    largest = std::max(largest, overlap / std::min(p.radius[i], p.radius[j]));
  }
  for (std::size_t q = 0; q < wall_contacts_.size(); ++q) {
    const std::int32_t i = wall_contacts_.disc[q];
    const Segment& s = segments_[wall_contacts_.segment[q]];
    const WallTouch touch = wall_touch(s, {p.x[i], p.y[i]}, p.radius[i]);
    if (s.active && touch.acts) largest = std::max(largest, 1.0 - touch.gap / p.radius[i]);
  }
  return largest;
}

}  // namespace runout
