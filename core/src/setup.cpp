#include "runout/setup.hpp"
#include "runout/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "runout/errors.hpp"
#include "runout/measure.hpp"

namespace runout {

namespace {

// Portable uniform doubles in [0, 1) from a fixed generator: same pile on every platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::mt19937_64 engine_;
};

constexpr double kDeg = kPi / 180.0;
// The largest pile runout builds, and what a disc costs in memory for the message: measured,
// the peak resident size of preparing thesis_2_10 (650 discs) and thesis_4_100 (8,000) was
// 6.5 and 15.6 MB, 1.2 kB a disc; 10 million discs are then about 13 GB.
constexpr double kMaxDiscs = 10'000'000;
constexpr double kBytesPerDisc = 1230;
// The preparation damps a pile once E_k/E_p is below this many times the settle threshold
// (it merely rings), or once it has had twice the free-fall time of its box to collapse.
constexpr double kDampingOnset = 100.0;

}  // namespace

double disc_count(const SpeciesDef& species, int reference_large_count, double large_diameter) {
  // The species' share of the area of N0 large discs over its mean disc area.
  const double ratio = large_diameter / species.diameter;
  const double per_share = species.distribution == SizeDistribution::spread
                               ? ratio * ratio  // SPEC eq. 3.1
                               : large_diameter * large_diameter * mean_inverse_square_diameter(species);
  const double n = species.area_share * reference_large_count * per_share;
  return std::ceil(n * (1.0 - 1e-9));  // 3200.0000000001 is 3200
}

SceneSetup derive_setup(const SceneDef& scene, const std::string& source) {
  if (scene.species.empty()) throw ConfigError(source, "species", "at least one species is required");
  {
    std::vector<std::pair<std::pair<double, double>, std::size_t>> centres;
    for (std::size_t k = 0; k < scene.particles.size(); ++k)
      centres.push_back({{scene.particles[k].x, scene.particles[k].y}, k});
    std::sort(centres.begin(), centres.end());
    for (std::size_t k = 1; k < centres.size(); ++k)
      if (centres[k].first == centres[k - 1].first)
        throw ConfigError(source, "particles[" + std::to_string(std::max(centres[k].second, centres[k - 1].second)) + "]",
                          "has the same centre as particles[" +
                              std::to_string(std::min(centres[k].second, centres[k - 1].second)) +
                              "]: coincident centres have no contact normal; move one of them");
  }
  SceneSetup s;
  s.table = derive_contact_table(scene.material, scene.contact, scene.species,
                                 scene.integration.gravity);

  s.unit_length = unit_length(scene.species);
  s.unit_time = unit_time(scene.species, scene.integration.gravity);
  for (int k = 0; k < static_cast<int>(scene.species.size()); ++k)
    if (scene.species[k].diameter > scene.species[s.largest_species].diameter) s.largest_species = k;
  s.large_diameter = scene.species[s.largest_species].diameter;
  s.walls = scene.walls;

  if (scene.avalanche) {
    const auto& a = *scene.avalanche;
    s.counts.resize(scene.species.size());
    double total = 0;
    for (size_t k = 0; k < scene.species.size(); ++k)
      total += disc_count(scene.species[k], a.reference_large_count, s.large_diameter);
    // Counted in floating point and capped before anything is allocated: a tiny diameter
    // must be an error naming the count, not an int overflow or a bare bad_alloc.
    if (total > kMaxDiscs) {
      std::ostringstream msg;
      msg << "the pile would hold " << std::llround(total) << " discs (about "
          << std::llround(total * kBytesPerDisc / 1e9) << " GB); runout takes at most "
          << static_cast<long long>(kMaxDiscs) << ": raise the smallest diameter or lower avalanche.reference_large_count";
      throw ConfigError(source, "species", msg.str());
    }
    for (size_t k = 0; k < scene.species.size(); ++k)
      s.counts[k] = static_cast<int>(disc_count(scene.species[k], a.reference_large_count, s.large_diameter));

    const double D = s.large_diameter, t = std::tan(a.incline_angle_deg * kDeg);
    const double gate_x = -a.incline_length * D * std::cos(a.incline_angle_deg * kDeg);
    const double back_x = gate_x - a.pile_width * D;
    const double floor_end = a.floor_length * D;
    const double h = a.wall_height * D;
    // A closed container (walls.hpp): every face one-sided, the discs on the left of each
    // polyline's direction, so no disc is squeezed through a wall (SPEC §2: rigid segments).
    // The bed: incline from the back wall's foot to the foot at (0, 0), then the floor.
    const auto left = WallInside::left;
    s.walls.push_back({"bed", {{back_x, -back_x * t}, {0.0, 0.0}, {floor_end, 0.0}}, true, left});
    s.walls.push_back({"back_wall", {{back_x, -back_x * t + h}, {back_x, -back_x * t}}, false, left});
    s.gate_wall = static_cast<int>(s.walls.size());
    s.walls.push_back({"gate", {{gate_x, -gate_x * t}, {gate_x, -gate_x * t + h}}, false, left});
    s.walls.push_back({"end_wall", {{floor_end, 0.0}, {floor_end, h}}, false, left});
  } else {
    s.counts.assign(scene.species.size(), 0);
    for (const auto& p : scene.particles) ++s.counts[p.species];
  }
  // Small and large are the smallest and largest species present: %A_p = 0 has no small
  // discs (then both are the large species), a polydisperse pile's classes may be empty.
  s.roles.small = s.roles.large = s.largest_species;
  for (int k = 0; k < static_cast<int>(scene.species.size()); ++k) {
    if (s.counts[k] == 0) continue;
    if (s.counts[s.roles.small] == 0 || scene.species[k].diameter <= scene.species[s.roles.small].diameter) s.roles.small = k;
    if (s.counts[s.roles.large] == 0 || scene.species[k].diameter > scene.species[s.roles.large].diameter) s.roles.large = k;
  }
  // Explicit integrators are stable for omega dt < 2: dt <= tau / pi (SPEC §8 extremes).
  if (scene.integration.dt_fraction > 1.0 / kPi) {
    std::ostringstream value;  // 0.35, not 0.350000
    value << scene.integration.dt_fraction;
    throw ConfigError(source, "integration.dt_fraction",
                      "value " + value.str() +
                          " is beyond the stability limit of the explicit integrators, 1/pi = 0.318 "
                          "of tau_min (omega dt < 2); use at most 0.3 (default 0.1)");
  }
  // The step is set by the species present: a %A_p = 0 pile has no small discs to resolve.
  std::vector<char> present(scene.species.size(), 0);
  bool any = false;
  for (std::size_t k = 0; k < present.size(); ++k) any |= (present[k] = s.counts[k] > 0);
  if (!any) present.assign(present.size(), 1);
  s.tau_min = minimum_collision_period(s.table, scene.species, scene.material.density, present);
  s.dt = scene.integration.dt_fraction * s.tau_min;
  return s;
}

namespace {

// Explicit discs start where the user put them: two that overlap would fly apart at the first
// step (and be reported as an impact or an escape far from the cause), one outside the walls'
// box would be reported as having left it. Both are named as the scene's particles[k].
void check_explicit_discs(const SceneDef& scene, const SceneSetup& setup, const std::string& source) {
  const auto& discs = scene.particles;
  const auto name = [](std::size_t k) { return "particles[" + std::to_string(k) + "]"; };
  if (!setup.walls.empty()) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300;
    for (const auto& w : setup.walls)
      for (const auto& [x, y] : w.points) { x0 = std::min(x0, x); x1 = std::max(x1, x); y0 = std::min(y0, y); }
    for (std::size_t k = 0; k < discs.size(); ++k)
      if (discs[k].x < x0 || discs[k].x > x1 || discs[k].y < y0) {
        std::ostringstream msg;
        msg << "the disc at (" << discs[k].x << ", " << discs[k].y << ") m lies outside the walls' box (x in ["
            << x0 << ", " << x1 << "], y >= " << y0 << "): move it inside or extend the walls";
        throw ConfigError(source, name(k), msg.str());
      }
  }
  // Sweep along x: only discs whose x ranges meet can overlap (n log n, not n^2).
  std::vector<std::size_t> order(discs.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return discs[a].x < discs[b].x; });
  double widest = 0;
  for (const auto& d : discs) widest = std::max(widest, d.diameter);
  for (std::size_t a = 0; a < order.size(); ++a) {
    const ParticleDef& p = discs[order[a]];
    for (std::size_t b = a + 1; b < order.size() && discs[order[b]].x - p.x < widest; ++b) {
      const ParticleDef& q = discs[order[b]];
      const double sum = 0.5 * (p.diameter + q.diameter);
      const double gap = std::hypot(q.x - p.x, q.y - p.y) - sum;
      // A hundredth of the smaller radius: discs set in contact by hand stay allowed.
      if (gap < -0.01 * 0.5 * std::min(p.diameter, q.diameter)) {
        const std::size_t i = std::min(order[a], order[b]), j = std::max(order[a], order[b]);
        std::ostringstream msg;
        msg << "overlaps " << name(j) << " by " << -gap << " m (centres " << sum + gap
            << " m apart, radii add up to " << sum << " m): move them apart";
        throw ConfigError(source, name(i), msg.str());
      }
    }
  }
}

}  // namespace

void check_runnable(const SceneDef& scene, const SceneSetup& setup, const std::string& source) {
  int total = 0;
  for (int c : setup.counts) total += c;
  if (total == 0)
    throw ConfigError(source, scene.avalanche ? "avalanche.reference_large_count" : "particles",
                      "the scene has no discs to simulate (add [[particles]] or an [avalanche])");
  // A cadence shorter than one step would ask for more than one sample per step, for ever.
  const double step = setup.dt / setup.unit_time;  // t*
  const std::pair<const char*, double> cadences[] = {{"output.timeseries_every", scene.output.timeseries_every},
                                                     {"output.checkpoint_every", scene.output.checkpoint_every},
                                                     {"output.dump_every", scene.output.dump_every},
                                                     {"output.vtk_every", scene.output.vtk_every}};
  for (const auto& [key, every] : cadences)
    if (every > 0 && every < step) {
      std::ostringstream msg;
      msg << "value " << every << " t* is shorter than one time step of this scene (" << step
          << " t*); use at least one step (0 switches checkpoints, dumps and VTK frames off)";
      throw ConfigError(source, key, msg.str());
    }
  if (!scene.avalanche) check_explicit_discs(scene, setup, source);
}

StepSettings step_settings(const SceneDef& scene, const SceneSetup& setup, int threads) {
  StepSettings st;
  st.dt = setup.dt;
  st.gravity = {0.0, -scene.integration.gravity};
  st.skin = scene.integration.skin * setup.unit_length;
  st.integrator = scene.integration.integrator;
  st.contact.normal = scene.contact.normal_model;
  st.contact.tangential = scene.contact.tangential_model;
  st.contact.rolling = scene.contact.rolling_model;
  st.threads = threads;
  st.unit_time = setup.unit_time;
  // Piles are renumbered spatially for cache locality across threads; explicit scenes keep the
  // order the user gave (tests and scripts address their discs by position in the file).
  st.reorder_every = scene.avalanche ? 2000 : 0;
  st.overlap_guard = scene.contact.overlap_guard;
  // A tenth of the free-fall speed over a small radius: far above creep and jitter.
  st.impact_rate = 0.1 * std::sqrt(scene.integration.gravity * 0.5 * setup.unit_length);
  return st;
}

World build_explicit_world(const SceneDef& scene, const SceneSetup& setup, int threads) {
  Particles p;
  std::int64_t id = 1;
  for (const auto& d : scene.particles) {
    const double r = 0.5 * d.diameter;
    const double m = sphere_mass(r, scene.material.density);
    p.add(id++, d.species, d.x, d.y, r, m, sphere_inertia(m, r), d.vx, d.vy, d.omega);
  }
  return World(std::move(p), make_segments(setup.walls), setup.table,
               step_settings(scene, setup, threads));
}

World restore_world(Checkpoint checkpoint, const SceneDef& scene, const SceneSetup& setup, int threads,
                    const std::string& name) {
  return restore_world(std::move(checkpoint), make_segments(setup.walls), setup.table,
                       step_settings(scene, setup, threads), name);
}

World build_settled_pile(const SceneDef& scene, const SceneSetup& setup, int threads,
                         const std::function<void(double, double)>& progress,
                         SettleReport* report) {
  const auto& a = *scene.avalanche;
  const auto& prep = scene.preparation;
  Random rng(prep.seed);
  const double D = setup.large_diameter, t = std::tan(a.incline_angle_deg * kDeg);
  const double gate_x = -a.incline_length * D * std::cos(a.incline_angle_deg * kDeg);
  const double back_x = gate_x - a.pile_width * D;

  // Final diameters, species by species, largest first (a fixed order for a fixed seed).
  std::vector<int> order(scene.species.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(), [&](int l, int r) {
    return scene.species[l].diameter > scene.species[r].diameter;
  });
  std::vector<double> final_radius;
  std::vector<int> species;
  double area = 0;
  for (int k : order) {
    const auto& sp = scene.species[k];
    const bool spread = sp.distribution == SizeDistribution::spread;
    // A class of a distribution takes its quantiles, largest first like the species.
    std::vector<double> sizes = spread ? std::vector<double>{} : class_diameters(sp, setup.counts[k]);
    for (int c = 0; c < setup.counts[k]; ++c) {
      const double dia = spread ? sp.diameter * rng.uniform(1.0 - sp.spread, 1.0 + sp.spread)
                                : sizes[sizes.size() - 1 - static_cast<std::size_t>(c)];
      final_radius.push_back(0.5 * dia);
      species.push_back(k);
      area += kPi * 0.25 * dia * dia;
    }
  }
  // Box above the incline between back wall and gate, of area (disc area / initial packing).
  const double width = gate_x - back_x;
  const double incline_integral = t * (gate_x * gate_x - back_x * back_x) / 2.0;  // < 0
  const double y_top = (area / prep.initial_packing - incline_integral) / width;

  const double speed = prep.initial_speed * std::sqrt(scene.integration.gravity * setup.unit_length);
  const double seed_fraction = 1e-3;  // radii start near zero
  Particles p;
  for (size_t k = 0; k < final_radius.size(); ++k) {
    const double rf = final_radius[k];
    double x = 0, y = 0;
    for (int tries = 0;; ++tries) {  // uniform in the box, one final radius clear of its walls
      x = rng.uniform(back_x + rf, gate_x - rf);
      y = rng.uniform(-gate_x * t, y_top);
      const double above_incline = (y + x * t) * std::cos(a.incline_angle_deg * kDeg);
      if (above_incline > rf) break;
      if (tries > 1000) throw ConfigError("scene", "avalanche.pile_width", "pile box too narrow for its discs");
    }
    // Mass and inertia are the final ones from the start: a tiny disc with the nominal
    // stiffness would need a far smaller time step.
    const double m = sphere_mass(rf, scene.material.density);
    p.add(static_cast<std::int64_t>(k + 1), species[k], x, y, seed_fraction * rf, m,
          sphere_inertia(m, rf),
          rng.uniform(-speed, speed), rng.uniform(-speed, speed), 0.0);
  }
  World world(std::move(p), make_segments(setup.walls), setup.table, step_settings(scene, setup, threads));

  // Growth r(t*) = r_final (1 - (1 - seed) exp(-t*/tau_g)), snapped to r_final at 1e-4. Once
  // the pile has collapsed it is damped (PFC local damping, preparation.damping); once E_k/E_p
  // has stayed below the threshold for settle_hold, the damping is switched off and the pile
  // must stay below it for another settle_hold under the undamped law, or damping resumes. So
  // the released pile is at rest under the very law the flow uses (SPEC §5).
  const double unit_time = setup.unit_time;
  const auto steps_per_unit = static_cast<std::int64_t>(std::ceil(unit_time / setup.dt));
  const std::int64_t check_every = std::max<std::int64_t>(1, steps_per_unit / 10);
  enum class Phase { growing, damped, undamped } phase = Phase::growing;
  double since = -1;  // damped: below the threshold since; undamped: damping off since
  SettleReport measured;
  const double gravity = scene.integration.gravity;
  const double collapse_time = 2.0 * std::sqrt(2.0 * (y_top + back_x * t) / gravity) / unit_time;  // t*
  for (std::int64_t step = 0;; ++step) {
    if (phase != Phase::growing && step % check_every != 0) {  // grown: to the check in one advance
      world.advance(check_every - step % check_every);
      step += check_every - step % check_every;
    }
    const double t_star = world.time() / unit_time;
    if (phase == Phase::growing) {
      const double shortfall = (1.0 - seed_fraction) * std::exp(-t_star / prep.growth_time);
      const bool grown = shortfall <= 1e-4;
      if (grown) {
        world.forget_normal_history();
        phase = Phase::damped;
        measured.t_star_grown = t_star;
      }
      const double scale = grown ? 1.0 : 1.0 - shortfall;
      // Every disc has the same share of its final radius: the guard judges overlaps against
      // the final radii, so seeds placed inside each other are not taken for impacts.
      world.set_overlap_guard(scene.contact.overlap_guard, scale);
      // By id: the world renumbers its discs spatially as they move.
      const auto& ids = world.particles().id;
      for (size_t k = 0; k < final_radius.size(); ++k) {
        const double rf = final_radius[static_cast<size_t>(ids[k] - 1)];
        const double m = sphere_mass(rf, scene.material.density);
        world.resize_disc(k, scale * rf, m, sphere_inertia(m, rf));
      }
    }
    world.step();
    if (step % check_every != 0) continue;
    world.check_escape(setup.large_diameter);
    // As after release (run.cpp): a disc rattling alone on top must not hold up a settled pile.
    const double ratio = mass_kinetic_energy(world.particles(), world.pairs()) / potential_energy(world.particles(), gravity);
    if (progress && step % (10 * check_every) == 0) progress(t_star, ratio);
    const bool quiet = ratio < prep.settle_ek_threshold;
    // Damping only once the pile has collapsed: damped, its fall would be slowed to (1 - damping) g.
    if (phase == Phase::damped && world.settings().local_damping == 0 &&
        (ratio < kDampingOnset * prep.settle_ek_threshold || t_star >= measured.t_star_grown + collapse_time))
      world.set_local_damping(prep.damping);
    if (phase == Phase::damped) {
      if (!quiet) {
        since = -1;
      } else if (since < 0) {
        since = t_star;
      } else if (t_star - since >= prep.settle_hold) {
        if (prep.damping == 0) {  // the undamped law all along: settled
          measured.ek_over_ep_undamped = ratio;
          measured.t_star_settled = t_star;
          break;
        }
        phase = Phase::undamped;
        world.set_local_damping(0.0);
        since = t_star;
      }
    } else if (phase == Phase::undamped) {
      if (!quiet) {  // still ringing without damping: damp it again
        phase = Phase::damped;
        world.set_local_damping(prep.damping);
        since = -1;
        ++measured.damped_rounds;
      } else if (t_star - since >= prep.settle_hold) {
        measured.ek_over_ep_undamped = ratio;
        measured.t_star_settled = t_star;
        break;
      }
    }
    if (t_star > prep.settle_max_time) {
      std::ostringstream msg;
      msg << "the pile did not settle by t* = " << prep.settle_max_time << " (step "
          << world.step_count() << ", E_k/E_p = " << ratio << " against the threshold "
          << prep.settle_ek_threshold << ", "
          << (phase == Phase::growing ? "still growing" : "damped rounds: " + std::to_string(measured.damped_rounds + 1))
          << "); raise preparation.settle_max_time";
      throw NumericalError(msg.str());
    }
  }
  measured.peak_impact_overlap = world.peak_impact_overlap();
  if (report) *report = measured;
  return world;
}

void release(World& world, const SceneSetup& setup) {
  if (setup.gate_wall >= 0) world.deactivate_wall(setup.gate_wall);
  world.set_clock(0.0, 0);
}

}  // namespace runout
