// The safety checks of SPEC §8, run inside every step: an impact beyond the overlap guard, a
// non-finite state, a disc that left the walls' box. Each stops the run with the step, t*, the
// disc and the knob to turn (NumericalError).
#include <cmath>
#include <sstream>

#include "runout/errors.hpp"
#include "runout/world.hpp"

namespace runout {

// SPEC §8: an overlap beyond the guard means the contact is far stiffer-demanding than the
// stiffness was designed for (too fast an impact, too large a step): stop with advice.
void World::check_overlap(double worst) {
  if (!beyond_guard(worst)) return;
  worst *= guard_radius_scale_;
  const auto& p = particles_;
  std::int64_t a = -1, b = -1;
  double found = 0;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const std::int32_t i = pairs_.i[q], j = pairs_.j[q];
    const double d = std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
    const double ratio = (p.radius[i] + p.radius[j] - d) / (p.radius[i] + p.radius[j]);
    if (ratio > found) { found = ratio; a = p.id[i]; b = p.id[j]; }
  }
  std::ostringstream msg;
  msg << "an impact overlap of " << static_cast<int>(100 * worst)
      << " % of the depth at which the contact is passed through (guard: "
      << static_cast<int>(100 * settings_.overlap_guard) << " %) at step " << steps_ << " (t* = "
      << time_ / settings_.unit_time << ")";
  if (a >= 0 && found * guard_radius_scale_ >= worst * 0.999) msg << " between discs " << a << " and " << b;
  else msg << " against a wall";
  msg << ": an impact faster than the contact stiffness was designed for, or too large a step. "
         "Raise contact.design_impact_speed (stiffer contacts) or lower contact.design_max_overlap, "
         "and/or lower integration.dt_fraction";
  throw NumericalError(msg.str());
}

void World::check_escape(double margin) const {
  if (segments_.empty()) return;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& s : segments_) {
    x0 = std::min({x0, s.a.x(), s.b.x()}); x1 = std::max({x1, s.a.x(), s.b.x()});
    y0 = std::min({y0, s.a.y(), s.b.y()}); y1 = std::max({y1, s.a.y(), s.b.y()});
  }
  const auto& p = particles_;
  for (std::size_t k = 0; k < p.size(); ++k) {
    // Above the walls is allowed (the pile box is open at the top); below or beside is not.
    if (p.y[k] < y0 - margin || p.x[k] < x0 - margin || p.x[k] > x1 + margin) {
      std::ostringstream msg;
      msg << "disc id " << p.id[k] << " left the domain at step " << steps_ << " (t* = "
          << time_ / settings_.unit_time << "), at (" << p.x[k] << ", " << p.y[k]
          << ") m, moving at (" << p.vx[k] << ", " << p.vy[k] << ") m/s: ";
      // One-sided walls cannot be squeezed through; a disc outside went over a wall's top, or
      // through a two-sided plate or more than a diameter through a face (walls.hpp).
      if (p.y[k] > y1 - margin)
        msg << "it flew over the top of a wall (raise the walls: avalanche.wall_height, or the "
               "scene's [[walls]])";
      else
        msg << "it was pushed through a wall (a two-sided plate once its centre crossed, or a "
               "face by more than its diameter): give the scene's walls an inside, or raise "
               "contact.design_impact_speed or lower integration.dt_fraction if the impact is "
               "far beyond the contact's design";
      throw NumericalError(msg.str());
    }
  }
}

void World::check_finite() const {
  if (finite_) return;
  const auto& p = particles_;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!std::isfinite(p.x[k] + p.y[k] + p.vx[k] + p.vy[k] + p.omega[k])) {
      std::ostringstream msg;
      msg << "non-finite state at step " << steps_ << " (t* = "
          << time_ / settings_.unit_time << ") for disc id " << p.id[k]
          << ": the time step is too large for the contact stiffness; lower "
             "integration.dt_fraction or contact.design_impact_speed / raise "
             "contact.design_max_overlap";
      throw NumericalError(msg.str());
    }
  }
}

}  // namespace runout
