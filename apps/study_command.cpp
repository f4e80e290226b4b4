// `runout study accuracy`: what each speed/accuracy knob costs and what it changes in the
// published answers (mu, L_cm, the front), measured on several piles because a granular
// avalanche is chaotic: two runs that differ in the last bit of one force end with mu a few
// hundredths apart, so a knob's effect is only told from that scatter by comparing means.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>

#include "prepare.hpp"
#include "pictures.hpp"
#include "run_command.hpp"
#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/run.hpp"
#include "runout/timing.hpp"

namespace runout::app {

namespace {

struct Variant {
  std::string family, setting;
  std::function<void(SceneDef&)> apply;
  // Another force law holds the pile at other overlaps: a pile settled under Walton–Braun
  // would spring apart at release, so such a variant settles its own pile (same seed).
  bool own_pile = false;
};

// One knob changed at a time from the scene's settings, then the reference: the finest step
// and the stiffest contacts together. The reference must stay last.
std::vector<Variant> study_variants() {
  std::vector<Variant> v;
  for (double f : {0.2, 0.1, 0.05, 0.025})
    v.push_back({"dt_fraction", std::to_string(f).substr(0, 5), [f](SceneDef& s) { s.integration.dt_fraction = f; }});
  for (double a : {0.02, 0.005, 0.0025})
    v.push_back({"design_max_overlap", std::to_string(a).substr(0, 6), [a](SceneDef& s) { s.contact.design_max_overlap = a; }});
  v.push_back({"integrator", "velocity_verlet", [](SceneDef& s) { s.integration.integrator = IntegratorKind::velocity_verlet; }});
  v.push_back({"normal_model", "linear_dashpot (own pile)", [](SceneDef& s) { s.contact.normal_model = "linear_dashpot"; }, true});
  v.push_back({"normal_model", "hertz (own pile)", [](SceneDef& s) { s.contact.normal_model = "hertz"; }, true});
  v.push_back({"reference", "dt 0.025 + overlap 0.0025", [](SceneDef& s) {
                 s.integration.dt_fraction = 0.025;
                 s.contact.design_max_overlap = 0.0025;
               }});
  return v;
}

// One run (one variant on one pile): the raw figures, one row of runs.csv.
struct StudyRun {
  std::string family, setting;
  std::uint64_t seed = 0;
  bool ok = false;
  double dt = 0;
  long long steps = 0;
  double wall_seconds = 0, particle_steps_per_second = 0;
  double mu = 0, L_cm = 0, front = 0, max_overlap = 0, residual = 0;
  bool at_rest = false;
  double t_star_end = 0;
  std::string failure;  // a run that stopped with an error is a result too
};

const char* kRunsHeader =
    "family,setting,seed,status,dt,steps,wall_seconds,particle_steps_per_second,mu_global,L_cm,front,"
    "max_overlap,worst_energy_residual,at_rest,t_star_end,failure\n";

std::string run_row(const StudyRun& r) {
  std::string why = r.failure;
  for (char& c : why)
    if (c == ',' || c == '\n') c = ';';
  char line[512];
  std::snprintf(line, sizeof line, "%s,%s,%llu,%s,%.9g,%lld,%.6g,%.6g,%.9f,%.9g,%.9g,%.9g,%.9g,%s,%.3f,",
                r.family.c_str(), r.setting.c_str(), static_cast<unsigned long long>(r.seed),
                r.ok ? "ok" : "failed", r.dt, r.steps, r.wall_seconds, r.particle_steps_per_second, r.mu,
                r.L_cm, r.front, r.max_overlap, r.residual, r.at_rest ? "true" : "false", r.t_star_end);
  return line + why + "\n";
}

// Reads the rows an earlier (interrupted) study wrote; rows that do not parse are dropped
// and rerun.
std::vector<StudyRun> read_runs(const std::string& path) {
  std::vector<StudyRun> runs;
  std::istringstream in(io::read_file(path));
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (f.size() < 15) continue;
    try {
      StudyRun r;
      r.family = f[0]; r.setting = f[1]; r.seed = std::stoull(f[2]); r.ok = f[3] == "ok";
      r.dt = std::stod(f[4]); r.steps = std::stoll(f[5]); r.wall_seconds = std::stod(f[6]);
      r.particle_steps_per_second = std::stod(f[7]); r.mu = std::stod(f[8]); r.L_cm = std::stod(f[9]);
      r.front = std::stod(f[10]); r.max_overlap = std::stod(f[11]); r.residual = std::stod(f[12]);
      r.at_rest = f[13] == "true"; r.t_star_end = std::stod(f[14]);
      r.failure = f.size() > 15 ? f[15] : "";
      runs.push_back(r);
    } catch (const std::exception&) {
    }
  }
  return runs;
}

// A variant over its piles: means, the seed-to-seed spread of mu, the worst overlap.
struct Summary {
  int runs = 0, failed = 0;
  double wall = 0, steps = 0, seconds_per_t_star = 0, rate = 0, mu = 0, mu_sd = 0, L_cm = 0, front = 0, residual = 0;
  double max_overlap = 0;
  std::string failure;
  double standard_error() const { return runs > 1 ? mu_sd / std::sqrt(runs) : NAN; }
};

Summary summarise(const std::vector<const StudyRun*>& runs) {
  Summary s;
  for (const StudyRun* r : runs) {
    if (!r->ok) { ++s.failed; s.failure = r->failure.substr(0, r->failure.find(':')); continue; }
    ++s.runs;
    s.wall += r->wall_seconds; s.steps += static_cast<double>(r->steps); s.seconds_per_t_star += r->wall_seconds / std::max(r->t_star_end, 1e-9);
    s.rate += r->particle_steps_per_second; s.mu += r->mu; s.L_cm += r->L_cm; s.front += r->front;
    s.residual += r->residual;
    // NaN (the overlap series not selected) stays NaN.
    s.max_overlap = std::isnan(r->max_overlap) || std::isnan(s.max_overlap) ? NAN : std::max(s.max_overlap, r->max_overlap);
  }
  if (s.runs == 0) return s;
  const double n = s.runs;
  s.wall /= n; s.steps /= n; s.seconds_per_t_star /= n; s.rate /= n; s.mu /= n; s.L_cm /= n; s.front /= n; s.residual /= n;
  double ss = 0;
  for (const StudyRun* r : runs)
    if (r->ok) ss += (r->mu - s.mu) * (r->mu - s.mu);
  s.mu_sd = s.runs > 1 ? std::sqrt(ss / (n - 1)) : NAN;
  return s;
}

}  // namespace

int study_command(const StudyOptions& o) {
  const std::string source = o.scene_path.empty() ? "<embedded quick scene>" : o.scene_path;
  const SceneDef base = load_scene(o.scene_path, o.overrides, io::embedded_quick_scene(), source);
  const SceneSetup base_setup = derive_setup(base, source);
  check_runnable(base, base_setup, source);
  io::make_directories(o.out_dir);
  const std::string cache = o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;
  const std::string runs_path = o.out_dir + "/runs.csv";
  const std::vector<Variant> variants = study_variants();

  // The scene (after --set) the runs belong to: --resume never mixes runs of two scenes.
  const std::string key_path = o.out_dir + "/study.key";
  char key_text[32];
  std::snprintf(key_text, sizeof key_text, "%016llx\n",
                static_cast<unsigned long long>(io::fnv1a64(io::write_scene(base))));
  std::vector<StudyRun> runs;
  if (o.resume && io::file_exists(runs_path)) {
    if (io::file_exists(key_path) && io::read_file(key_path) != key_text)
      throw std::invalid_argument(runs_path + " holds runs of another scene or other --set values; "
                                  "use another --out, or drop --resume to start again");
    runs = read_runs(runs_path);
  }
  io::write_file_atomically(key_path, key_text);
  auto done = [&](const Variant& v, std::uint64_t seed) {
    for (const auto& r : runs)
      if (r.family == v.family && r.setting == v.setting && r.seed == seed) return true;
    return false;
  };
  auto save_runs = [&] {
    std::string csv = kRunsHeader;
    for (const auto& r : runs) csv += run_row(r);
    io::write_file_atomically(runs_path, csv);
  };

  for (int k = 0; k < o.seeds; ++k) {
    SceneDef seeded = base;
    seeded.preparation.seed = base.preparation.seed + static_cast<std::uint64_t>(k);
    const std::uint64_t seed = seeded.preparation.seed;
    // Every variant of this seed starts from the same settled pile (settled with the scene's
    // own knobs), so within a seed the differences are the knobs', not another pile's.
    std::string start, start_failure;
    for (const auto& v : variants) {
      if (done(v, seed)) continue;
      StudyRun row;
      row.family = v.family; row.setting = v.setting; row.seed = seed;
      auto t0 = Clock::now();
      // A setting refused at setup, a pile that does not settle or a run that stops with a
      // numerical error is a result too: it becomes a failed row, and the study goes on.
      try {
        SceneDef scene = seeded;
        v.apply(scene);
        const SceneSetup setup = derive_setup(scene, source);
        row.dt = setup.dt;
        World world = build_explicit_world(scene, setup, o.threads);
        if (v.own_pile) {
          world = prepare(scene, setup, o.threads, cache, true, true).world;
        } else {
          if (!start_failure.empty()) throw NumericalError(start_failure);
          if (start.empty()) {
            try {
              start = encode_checkpoint(
                  prepare(seeded, derive_setup(seeded, source), o.threads, cache, true, true).world, 0, {});
            } catch (const std::runtime_error& e) {
              start_failure = std::string("the shared pile: ") + e.what();  // not settled again per variant
              throw;
            }
          }
          decode_checkpoint(start, 0, world, "settled pile");
        }
        AvalancheRun run(world, scene, setup);
        t0 = Clock::now();
        const RunResult r = run.run();
        row.ok = true;
        row.steps = r.steps; row.particle_steps_per_second = r.particle_steps_per_second;
        row.mu = r.mu_global; row.L_cm = r.L_cm; row.front = r.final_energy.front_x;
        row.max_overlap = r.max_overlap; row.residual = r.worst_energy_residual;
        row.at_rest = r.at_rest; row.t_star_end = r.t_star_end;
      } catch (const std::runtime_error& e) {  // ConfigError, NumericalError, IoError
        row.failure = e.what();
      }
      row.wall_seconds = seconds_since(t0);
      if (row.ok)
        std::fprintf(stderr, "runout study: seed %llu, %s = %s: mu %.4f, %.1f s\n",
                     static_cast<unsigned long long>(seed), v.family.c_str(), v.setting.c_str(), row.mu,
                     row.wall_seconds);
      else
        std::fprintf(stderr, "runout study: seed %llu, %s = %s failed: %s\n", static_cast<unsigned long long>(seed),
                     v.family.c_str(), v.setting.c_str(), row.failure.c_str());
      runs.push_back(row);
      save_runs();  // after every run, so an interrupted study resumes (--resume)
    }
  }
  save_runs();

  // Per variant over the requested seeds only.
  const std::uint64_t first = base.preparation.seed, last = first + static_cast<std::uint64_t>(o.seeds);
  std::vector<Summary> summaries;
  for (const auto& v : variants) {
    std::vector<const StudyRun*> mine;
    for (const auto& r : runs)
      if (r.family == v.family && r.setting == v.setting && r.seed >= first && r.seed < last) mine.push_back(&r);
    summaries.push_back(summarise(mine));
  }
  const Summary& ref = summaries.back();
  if (ref.runs == 0) throw NumericalError("every reference run failed: " + ref.failure);
  // mu of a variant against the reference, pile by pile (seed by seed): the mean difference
  // and two standard errors of it. Below that noise the knob's effect on mu cannot be told
  // from the pile-to-pile scatter.
  auto mu_of = [&](const Variant& v, std::uint64_t seed) {
    for (const auto& r : runs)
      if (r.ok && r.family == v.family && r.setting == v.setting && r.seed == seed) return r.mu;
    return double(NAN);
  };
  auto paired = [&](const Variant& v) {
    std::vector<double> d;
    for (std::uint64_t seed = first; seed < last; ++seed) {
      const double a = mu_of(v, seed), b = mu_of(variants.back(), seed);
      if (std::isfinite(a) && std::isfinite(b)) d.push_back(a - b);
    }
    double mean = 0, ss = 0;
    for (double x : d) mean += x / d.size();
    for (double x : d) ss += (x - mean) * (x - mean);
    const double n = d.size();
    return std::pair{std::abs(mean), d.size() > 1 ? 2 * std::sqrt(ss / (n - 1) / n) : double(NAN)};
  };

  std::string csv = "family,setting,runs,failed,steps,wall_seconds,seconds_per_t_star,particle_steps_per_second,mu_mean,mu_sd,"
                    "mu_error,mu_noise_2se,L_cm_rel_error,front_rel_error,max_overlap,mean_worst_energy_residual\n";
  std::string md =
      "| knob | setting | runs | steps | wall s | s per t* | M particle-steps/s | mu mean ± sd | abs. mean difference to reference | 2 s.e. | "
      "L_cm rel. error | front rel. error | max overlap / r | residual / Ep0 |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[1024];
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const Variant& v = variants[k];
    const Summary& s = summaries[k];
    if (s.runs == 0) {
      csv += v.family + "," + v.setting + ",0," + std::to_string(s.failed) + ",,,,,,,,,,,,\n";
      md += "| " + v.family + " | " + v.setting + " | failed: " + s.failure + " | | | | | | | | | | | |\n";
      continue;
    }
    // The reference row shows the two standard errors of its own mean.
    const auto [error, noise] = &s == &ref ? std::pair{0.0, 2 * ref.standard_error()} : paired(v);
    const double L_error = std::abs(s.L_cm - ref.L_cm) / ref.L_cm;
    const double front_error = std::abs(s.front - ref.front) / ref.front;
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%.0f,%.3f,%.5f,%.4g,%.6f,%.6f,%.6f,%.6f,%.5f,%.5f,%.4f,%.4f\n",
                  v.family.c_str(), v.setting.c_str(), s.runs, s.failed, s.steps, s.wall, s.seconds_per_t_star, s.rate,
                  s.mu, s.mu_sd, error, noise, L_error, front_error, s.max_overlap, s.residual);
    csv += line;
    std::snprintf(line, sizeof line,
                  "| %s | %s | %d%s | %.3g | %.1f | %.3f | %.1f | %.4f ± %.4f | %.4f | %.4f | %.3f | %.3f | %.3f | %.3f |\n",
                  v.family.c_str(), v.setting.c_str(), s.runs, s.failed ? (" (+" + std::to_string(s.failed) + " failed)").c_str() : "",
                  s.steps, s.wall, s.seconds_per_t_star, s.rate / 1e6, s.mu, s.mu_sd, error, noise, L_error, front_error,
                  s.max_overlap, s.residual);
    md += line;
  }
  io::write_file_atomically(o.out_dir + "/study.csv", csv);
  io::write_file_atomically(o.out_dir + "/study.md", md);
  // The plot (study.png, study.pdf) is matplotlib's, from study.csv (scripts/runout_plot.py).
  try {
    const std::string title = "speed against accuracy: " + base.name + " (" + std::to_string(o.seeds) + " piles)";
    if (run_plot_script(std::filesystem::canonical("/proc/self/exe").string(), {"--study", o.out_dir, "--title", title}) != 0)
      std::fprintf(stderr, "runout study: no plot (runout_plot.py failed)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "runout study: no plot (%s)\n", e.what());
  }
  std::printf("%s", md.c_str());
  return 0;
}

}  // namespace runout::app
