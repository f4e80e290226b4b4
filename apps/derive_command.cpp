// `runout derive SCENE`: the seed's setup table (SPEC §3–4) for a scene — per species pair and
// per wall the reduced radius and mass, the stiffnesses, the chosen law's constants and the
// collision periods; tau_min, dt and steps per t*; the disc counts. SI and dimensionless.
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "prepare.hpp"
#include "run_command.hpp"
#include "runout/contact/registry.hpp"
#include "runout/derive.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/setup.hpp"

namespace runout::app {

namespace {

// A number as people read it: four significant digits, no binary noise (0.1, not
// 0.10000000000000001).
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

int derive_command(const DeriveOptions& o) {
  const std::string source = o.scene_path.empty() ? "<embedded quick scene>" : o.scene_path;
  const SceneDef scene = load_scene(o.scene_path, o.overrides, io::embedded_quick_scene(), source);
  const SceneSetup setup = derive_setup(scene, source);
  const double g = scene.integration.gravity;
  const int n = static_cast<int>(scene.species.size());
  const ContactTable& table = setup.table;
  const std::string& law = scene.contact.normal_model;

  nlohmann::json j;
  j["scene"] = scene.name;
  j["source"] = source;
  j["normal_model"] = law;
  j["tangential_model"] = scene.contact.tangential_model;
  j["rolling_model"] = scene.contact.rolling_model;
  j["unit_length_d"] = setup.unit_length;
  j["unit_time"] = setup.unit_time;
  j["tau_min"] = setup.tau_min;
  j["tau_min_over_unit_time"] = setup.tau_min / setup.unit_time;
  j["dt_fraction"] = scene.integration.dt_fraction;
  j["dt"] = setup.dt;
  j["steps_per_t_star"] = setup.unit_time / setup.dt;
  j["counts"] = nlohmann::json::object();
  for (int a = 0; a < n; ++a) j["counts"][scene.species[a].name] = setup.counts[a];
  j["contacts"] = nlohmann::json::array();
  // Every ordered pair (a disc of a among discs of b: the periods differ, the rest is
  // symmetric), then each species on a wall.
  for (int a = 0; a < n; ++a)
    for (int b = 0; b <= n; ++b) {
      const bool wall = b == n;
      const PairCoefficients& c = wall ? table.wall[a] : table.between(a, b);
      const CollisionPeriods t = collision_periods(table, scene.species, scene.material.density, a, wall ? -1 : b);
      nlohmann::json row;
      row["pair"] = scene.species[a].name + (wall ? " on a wall" : " among " + scene.species[b].name);
      row["r_star"] = c.reduced_radius;
      row["m_star"] = c.reduced_mass;
      row["k_load"] = c.k_load;
      row["k_unload"] = c.k_unload;
      row["k_tangential"] = c.tangential_stiffness_for_dt;  // Mindlin: at the design overlap
      row["friction"] = c.friction;
      row["k_unload_over_m_star"] = c.k_unload / c.reduced_mass;  // s^-2, SPEC §3's check column
      // Dimensionless: k_U r* / (m* g) = (alphadot0 f / alphamax)^2.
      row["k_unload_dimensionless"] = c.k_unload * c.reduced_radius / (c.reduced_mass * g);
      // A dashpot law's own constants (N/m or N/m^1.5, and N s/m or N s/m^1.25).
      NormalLaws::with(law, [&](auto normal) {
        const auto p = decltype(normal)::params(c);
        if constexpr (requires { p.damping; }) {
          row["normal_k"] = p.k;
          row["normal_damping"] = p.damping;
        }
      });
      row["ring"] = t.ring;
      row["tau_trans"] = t.translational;
      row["tau_rot"] = t.rotational;
      row["tau_trans_over_unit_time"] = t.translational / setup.unit_time;
      row["tau_rot_over_unit_time"] = t.rotational / setup.unit_time;
      j["contacts"].push_back(row);
    }
  if (o.json) {
    std::printf("%s\n", j.dump(1).c_str());
    return 0;
  }
  std::printf("scene %s (%s), laws: normal %s, tangential %s, rolling %s; e_n %s (walls %s), mu %s (walls %s)\n",
              scene.name.c_str(), source.c_str(), law.c_str(), scene.contact.tangential_model.c_str(),
              scene.contact.rolling_model.c_str(), num(scene.material.restitution).c_str(),
              num(scene.material.wall_restitution).c_str(), num(scene.material.friction).c_str(),
              num(scene.material.wall_friction).c_str());
  std::printf("d = %s m (the unit of length), t* unit sqrt(d/g) = %s s\n", num(setup.unit_length).c_str(),
              num(setup.unit_time).c_str());
  std::printf("discs:");
  for (int a = 0; a < n; ++a) std::printf(" %s %d", scene.species[a].name.c_str(), setup.counts[a]);
  std::printf("\n\n(a disc of the first species among discs of the second: ring = N_surr neighbours)\n%-18s %10s %10s %10s %10s %10s %12s %9s %5s %10s %10s\n", "contact", "r* (m)", "m* (kg)",
              "k_L (N/m)", "k_U (N/m)", "k_s (N/m)", "k_U/m* (1/s2)", "k_U r*/m*g", "ring", "tau_tr (s)",
              "tau_rot (s)");
  for (const auto& row : j["contacts"])
    std::printf("%-18s %10s %10s %10s %10s %10s %12s %9s %5s %10s %10s\n", row["pair"].get<std::string>().c_str(),
                num(row["r_star"]).c_str(), num(row["m_star"]).c_str(), num(row["k_load"]).c_str(),
                num(row["k_unload"]).c_str(), num(row["k_tangential"]).c_str(),
                num(row["k_unload_over_m_star"]).c_str(), num(row["k_unload_dimensionless"]).c_str(),
                num(row["ring"]).c_str(), num(row["tau_trans"]).c_str(), num(row["tau_rot"]).c_str());
  for (const auto& row : j["contacts"])
    if (row.contains("normal_k"))
      std::printf("%-18s %s k = %s, damping = %s\n", row["pair"].get<std::string>().c_str(), law.c_str(),
                  num(row["normal_k"]).c_str(), num(row["normal_damping"]).c_str());
  std::printf("\ntau_min = %s s (%s t*), dt = %s x tau_min = %s s, %s steps per t*\n", num(setup.tau_min).c_str(),
              num(setup.tau_min / setup.unit_time).c_str(), num(scene.integration.dt_fraction).c_str(),
              num(setup.dt).c_str(), num(setup.unit_time / setup.dt).c_str());
  return 0;
}

}  // namespace runout::app
