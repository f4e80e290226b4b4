// `runout sweep`: one base scene over axes (SPEC §7's study), each case a `runout run` into
// DIR/cases/NAME. A case whose summary exists is skipped and a half-run one resumes from its
// checkpoint, so a sweep killed at any moment goes on where it stopped. Every route runs a case
// the same way, `runout sweep SWEEP --out DIR --case K`: here as child processes (--jobs), on
// Slurm as array tasks, with GNU parallel as a job list; results.csv is then the same bytes.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "prepare.hpp"
#include "run_command.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/io/sweep_file.hpp"
#include "runout/setup.hpp"

namespace runout::app {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Sweep {
  std::string text;        // the sweep file as read
  std::string base_text;   // the base scene
  std::string base_name;
  io::SweepDef def;
  // Work of each case per t* of flow (discs x steps per t*): what the estimate of the time
  // left weighs the cases by, since a D/d = 8.33 pile costs tens of times a D/d = 2 one.
  std::map<std::string, double> work;
};

// Reads the sweep and checks every case's scene before anything is written.
Sweep load_sweep(const std::string& path) {
  Sweep s;
  try {
    s.text = io::read_regular_file(path, 16u << 20);
  } catch (const IoError& e) {
    throw ConfigError(path, "(file)", e.what());
  }
  // The base is needed for D (the ratio axis): read it first, from the sweep's own folder.
  std::string base = "thesis";
  {
    const io::SweepDef probe = io::read_sweep(s.text, path, 1.0);
    base = probe.base;
  }
  if (base == "thesis") {
    s.base_text = io::embedded_bench_scene();
    s.base_name = "<built-in thesis scene>";
  } else {
    const fs::path p = fs::path(base).is_absolute() ? fs::path(base) : fs::path(path).parent_path() / base;
    s.base_name = p.string();
    try {
      s.base_text = io::read_regular_file(s.base_name, 64u << 20);
    } catch (const IoError& e) {
      throw ConfigError(path, "base", e.what());
    }
  }
  const SceneDef base_scene = io::read_scene(s.base_text, s.base_name);
  double large = 0;
  bool has_large = false, has_small = false;
  for (const auto& sp : base_scene.species) {
    if (sp.name == "large") { large = sp.diameter; has_large = true; }
    if (sp.name == "small") has_small = true;
  }
  s.def = io::read_sweep(s.text, path, has_large ? large : 1.0);
  for (const auto& key : s.def.axis_keys)
    if ((key == "ratio" || key == "small_share") && !(has_large && has_small))
      throw ConfigError(path, "axes." + key, "needs a base scene with species \"large\" and \"small\"");
  std::set<std::string> names;
  for (const auto& c : s.def.cases) {
    if (!names.insert(c.name).second)
      throw ConfigError(path, "axes", "two cases would share the folder name " + c.name);
    try {
      const SceneDef scene = io::read_scene(s.base_text, s.base_name, c.overrides);
      const SceneSetup setup = derive_setup(scene, s.base_name);
      check_runnable(scene, setup, s.base_name);
      double discs = 0;
      for (int n : setup.counts) discs += n;
      s.work[c.name] = discs * setup.unit_time / setup.dt;
    } catch (const ConfigError& e) {
      throw ConfigError(path, "case " + c.name, e.what());
    }
  }
  return s;
}

std::string case_dir(const std::string& out, const io::SweepCase& c) { return out + "/cases/" + c.name; }

// Numbers that differ from run to run of the same physics (wall times, threads, the cache):
// kept out of results.csv, so every route gives the same file, and written to timings.csv.
bool is_timing(const std::string& key) {
  static const std::set<std::string> keys = {"wall_seconds", "particle_steps_per_second", "profile_seconds",
                                             "preparation_seconds", "pile_from_cache", "threads"};
  return keys.count(key.substr(0, key.find('.'))) > 0;
}

void flatten(const nlohmann::json& j, const std::string& prefix, std::map<std::string, nlohmann::json>& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) flatten(*it, prefix.empty() ? it.key() : prefix + "." + it.key(), out);
  } else if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k) flatten(j[k], prefix + "[" + std::to_string(k) + "]", out);
  } else if (j.is_number() || j.is_null() || j.is_boolean()) {
    out[prefix] = j;
  }
}

std::string cell(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v.get<double>());
  return buf;
}

struct Gathered {
  std::size_t complete = 0;
};

// DIR/results.csv (axes + every number of each summary), DIR/timings.csv and DIR/points.csv
// (cases that differ only in seed: mean, standard deviation and two standard errors).
Gathered gather(const Sweep& s, const std::string& out) {
  std::vector<std::map<std::string, nlohmann::json>> rows;
  std::vector<const io::SweepCase*> cases;
  std::vector<std::string> columns;
  std::set<std::string> seen;
  for (const auto& c : s.def.cases) {
    const std::string summary = case_dir(out, c) + "/summary.json";
    if (!io::file_exists(summary)) continue;
    std::map<std::string, nlohmann::json> flat;
    try {
      flatten(nlohmann::json::parse(io::read_file(summary)), "", flat);
    } catch (const std::exception& e) {
      throw IoError(summary + ": " + e.what());
    }
    for (const auto& [k, v] : flat)
      if (seen.insert(k).second) columns.push_back(k);
    rows.push_back(std::move(flat));
    cases.push_back(&c);
  }
  std::sort(columns.begin(), columns.end());
  std::string results = "case", timings = "case";
  for (const auto& a : s.def.axis_keys) results += "," + a;
  for (const auto& k : columns) (is_timing(k) ? timings : results) += "," + k;
  results += "\n";
  timings += "\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::string line = cases[r]->name, t = cases[r]->name;
    for (const auto& [axis, value] : cases[r]->axes) line += "," + value;
    for (const auto& k : columns) {
      const auto it = rows[r].find(k);
      std::string& to = is_timing(k) ? t : line;
      to += ',';
      if (it != rows[r].end()) to += cell(it->second);
    }
    results += line + "\n";
    timings += t + "\n";
  }
  io::write_file_atomically(out + "/results.csv", results);
  io::write_file_atomically(out + "/timings.csv", timings);

  // Points: the axes other than the seed.
  std::vector<std::string> point_axes;
  for (const auto& a : s.def.axis_keys)
    if (a != "seed" && a != "preparation.seed") point_axes.push_back(a);
  std::map<std::vector<std::string>, std::vector<std::size_t>> groups;
  std::vector<std::vector<std::string>> order;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::vector<std::string> key;
    for (const auto& [axis, value] : cases[r]->axes)
      if (axis != "seed" && axis != "preparation.seed") key.push_back(value);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(r);
  }
  std::string points;
  for (std::size_t a = 0; a < point_axes.size(); ++a) {
    if (a) points += ',';
    points += point_axes[a];
  }
  points += std::string(point_axes.empty() ? "" : ",") + "n";
  std::vector<std::string> numeric;
  for (const auto& k : columns)
    if (!is_timing(k)) numeric.push_back(k);
  for (const auto& k : numeric) points += "," + k + "_mean," + k + "_sd," + k + "_2se";
  points += "\n";
  for (const auto& key : order) {
    const auto& members = groups[key];
    std::string line;
    for (std::size_t a = 0; a < key.size(); ++a) {
      if (a) line += ',';
      line += key[a];
    }
    line += std::string(key.empty() ? "" : ",") + std::to_string(members.size());
    for (const auto& k : numeric) {
      std::vector<double> v;
      for (std::size_t r : members) {
        const auto it = rows[r].find(k);
        if (it != rows[r].end() && it->second.is_number()) v.push_back(it->second.get<double>());
      }
      char buf[96] = "";
      if (!v.empty()) {
        double mean = 0;
        for (double x : v) mean += x;
        mean /= static_cast<double>(v.size());
        double ss = 0;
        for (double x : v) ss += (x - mean) * (x - mean);
        if (v.size() > 1) {
          const double sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
          std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", mean, sd, 2 * sd / std::sqrt(double(v.size())));
        } else {
          std::snprintf(buf, sizeof buf, "%.17g,,", mean);  // one seed: no spread to tell
        }
      } else {
        std::snprintf(buf, sizeof buf, ",,");
      }
      line += std::string(",") + buf;
    }
    points += line + "\n";
  }
  io::write_file_atomically(out + "/points.csv", points);
  return {rows.size()};
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// One case, in this process: a `runout run` into its folder with --resume, holding a lock so a
// second process (an orphan of a killed sweep, a duplicate array task) never runs it at once.
int run_case(const Sweep& s, const SweepOptions& o, const io::SweepCase& c) {
  const std::string dir = case_dir(o.out_dir, c);
  if (io::file_exists(dir + "/summary.json")) return 0;
  io::make_directories(dir);
  const int lock = ::open((dir + "/.lock").c_str(), O_RDWR | O_CREAT, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX | LOCK_NB) != 0) {
    std::fprintf(stderr, "runout: case %s is being run by another process\n", c.name.c_str());
    return 75;
  }
  RunOptions r;
  r.scene_text = s.base_text;
  r.scene_name = s.base_name;
  for (const auto& ov : c.overrides) r.overrides.push_back(ov.key + "=" + ov.value);
  r.out_dir = dir;
  r.resume = true;
  r.quiet = true;
  r.threads = o.threads_per_job;
  r.cache_dir = o.cache_dir;
  if (c.keeps_states)
    for (double t : s.def.strip_times) r.states += (r.states.empty() ? "" : ",") + std::to_string(t);
  const int code = run_command(r);
  ::close(lock);
  return code;
}

const io::SweepCase& find_case(const Sweep& s, const std::string& which) {
  for (std::size_t k = 0; k < s.def.cases.size(); ++k)
    if (s.def.cases[k].name == which || std::to_string(k) == which) return s.def.cases[k];
  throw UsageError("--case: " + which + " is neither a case name nor an index in [0, " +
                   std::to_string(s.def.cases.size() - 1) + "]");
}

std::string duration(double seconds) {
  char buf[48];
  if (seconds < 90) std::snprintf(buf, sizeof buf, "%.0f s", seconds);
  else if (seconds < 5400) std::snprintf(buf, sizeof buf, "%.0f min", seconds / 60);
  else std::snprintf(buf, sizeof buf, "%.1f h", seconds / 3600);
  return buf;
}

}  // namespace

int sweep_command(const SweepOptions& o) {
  const Sweep s = load_sweep(o.sweep_path);
  const std::string out = fs::absolute(o.out_dir).lexically_normal().string();
  if (!o.one_case.empty()) find_case(s, o.one_case);  // a bad --case before anything is written
  if (!o.emit.empty() && o.emit != "slurm" && o.emit != "parallel")
    throw UsageError("--emit: \"" + o.emit + "\" is not slurm or parallel");

  // One sweep per folder: a different sweep file would mix cases of two studies.
  const std::string copy = out + "/sweep.toml";
  if (io::file_exists(copy) && io::read_file(copy) != s.text)
    throw UsageError(out + " holds another sweep (its sweep.toml differs from " + o.sweep_path +
                     "): choose another --out; nothing was changed");
  io::make_directories(out + "/cases");
  if (!io::file_exists(copy)) io::write_file_atomically(copy, s.text);

  const std::string sweep_abs = fs::absolute(o.sweep_path).string();
  const std::string self = fs::absolute(o.self).string();
  auto case_command = [&](const std::string& which) {
    std::string cmd = quote(self) + " sweep " + quote(sweep_abs) + " --out " + quote(out) + " --case " + which +
                      " --threads-per-job " + std::to_string(o.threads_per_job);
    if (!o.cache_dir.empty()) cmd += " --cache-dir " + quote(fs::absolute(o.cache_dir).string());
    return cmd;
  };
  if (o.emit == "parallel") {
    std::string jobs;
    for (const auto& c : s.def.cases) jobs += case_command(c.name) + "\n";
    io::write_file_atomically(out + "/jobs.txt", jobs);
    std::printf("%s/jobs.txt: %zu cases. Run them with GNU parallel, then gather:\n  parallel --jobs %d < %s/jobs.txt\n"
                "  %s sweep %s --out %s --gather\n",
                out.c_str(), s.def.cases.size(), std::max(1, o.jobs), out.c_str(), quote(self).c_str(),
                quote(sweep_abs).c_str(), quote(out).c_str());
    return 0;
  }
  if (o.emit == "slurm") {
    std::ostringstream b;
    b << "#!/bin/bash\n# runout sweep " << sweep_abs << ": one array task per case (a task whose case is\n"
      << "# complete returns at once; a half-run one resumes from its checkpoint).\n"
      << "#SBATCH --job-name=runout-sweep\n#SBATCH --array=0-" << s.def.cases.size() - 1 << "\n"
      << "#SBATCH --cpus-per-task=" << o.threads_per_job << "\n#SBATCH --output=" << out << "/cases/slurm-%A_%a.log\n"
      << "export OMP_WAIT_POLICY=PASSIVE\n"
      << "exec " << case_command("\"$SLURM_ARRAY_TASK_ID\"") << "\n";
    io::write_file_atomically(out + "/sweep.sbatch", b.str());
    std::printf("%s/sweep.sbatch: %zu array tasks. Submit, then gather:\n  sbatch %s/sweep.sbatch\n  %s sweep %s --out %s --gather\n",
                out.c_str(), s.def.cases.size(), out.c_str(), quote(self).c_str(), quote(sweep_abs).c_str(), quote(out).c_str());
    return 0;
  }
  if (!o.one_case.empty()) return run_case(s, o, find_case(s, o.one_case));
  if (o.gather) {
    const Gathered g = gather(s, out);
    std::fprintf(stderr, "runout: %zu of %zu cases complete; %s/results.csv, points.csv\n", g.complete,
                 s.def.cases.size(), out.c_str());
    return g.complete == s.def.cases.size() ? 0 : 1;
  }

  // Local: up to --jobs child processes, each `runout sweep ... --case NAME`, its stderr in the
  // case's run.log; a child dies with this process (PR_SET_PDEATHSIG: SIGTERM, so it writes a
  // checkpoint), so a killed sweep leaves no orphans.
  std::vector<const io::SweepCase*> todo;
  for (const auto& c : s.def.cases)
    if (!io::file_exists(case_dir(out, c) + "/summary.json")) todo.push_back(&c);
  std::fprintf(stderr, "runout: sweep of %zu cases, %zu to run, %d at a time\n", s.def.cases.size(), todo.size(),
               std::max(1, o.jobs));
  if (o.jobs > 1) ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0);  // idle waits must not spin
  const pid_t parent = ::getpid();
  std::map<pid_t, std::pair<const io::SweepCase*, Clock::time_point>> running;
  std::vector<std::string> failed;
  std::size_t next = 0, done = 0;
  double spent = 0, work_done = 0, work_all = 0;
  for (const auto* c : todo) work_all += s.work.at(c->name);
  gather(s, out);
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && running.size() < static_cast<std::size_t>(std::max(1, o.jobs))) {
      const io::SweepCase& c = *todo[next++];
      const std::string dir = case_dir(out, c);
      io::make_directories(dir);
      const std::string log = dir + "/run.log";
      std::vector<std::string> args = {self, "sweep", sweep_abs, "--out", out, "--case", c.name,
                                       "--threads-per-job", std::to_string(o.threads_per_job)};
      if (!o.cache_dir.empty()) { args.push_back("--cache-dir"); args.push_back(o.cache_dir); }
      const pid_t pid = ::fork();
      if (pid < 0) throw IoError(std::string("cannot start a case: fork failed"));
      if (pid == 0) {
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (::getppid() != parent) ::_exit(1);
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (fd >= 0) { ::dup2(fd, 1); ::dup2(fd, 2); ::close(fd); }
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv(self.c_str(), argv.data());
        ::_exit(127);
      }
      running[pid] = {&c, Clock::now()};
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) break;
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const io::SweepCase& c = *it->second.first;
    const double secs = std::chrono::duration<double>(Clock::now() - it->second.second).count();
    running.erase(it);
    ++done;
    spent += secs;
    work_done += s.work.at(c.name);
    const std::string summary = case_dir(out, c) + "/summary.json";
    std::string mu;
    if (io::file_exists(summary)) {
      const auto j = nlohmann::json::parse(io::read_file(summary), nullptr, false);
      mu = "mu_global = ";
      mu += j.is_object() && j["mu_global"].is_number() ? cell(j["mu_global"]).substr(0, 6) : std::string("null");
    } else {
      mu = "failed (see ";
      mu += case_dir(out, c);
      mu += "/run.log)";
      failed.push_back(c.name);
    }
    gather(s, out);
    const std::size_t left = todo.size() - done;
    // Seconds per unit of work so far, times the work not finished (the running cases' whole),
    // shared by the jobs: cases that differ in size are weighed by their size.
    const double eta = work_done > 0 ? spent / work_done * (work_all - work_done) / std::max(1, o.jobs) : 0;
    std::string more;
    if (left) {
      more = ", about ";
      more += duration(eta);
      more += " more";
    }
    std::fprintf(stderr, "  [%zu/%zu] %s  %s  %s; %zu left%s\n", done, todo.size(), c.name.c_str(), duration(secs).c_str(),
                 mu.c_str(), left, more.c_str());
  }
  const Gathered g = gather(s, out);
  std::fprintf(stderr, "runout: %zu of %zu cases complete; %s/results.csv, points.csv\n", g.complete,
               s.def.cases.size(), out.c_str());
  if (!failed.empty()) {
    std::string list;
    for (const auto& f : failed) list += " " + f;
    std::fprintf(stderr, "runout: failed:%s (each case's run.log says why; run the sweep again to retry)\n", list.c_str());
    return 1;
  }
  return 0;
}

}  // namespace runout::app
