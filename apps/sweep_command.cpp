// `runout sweep`: one base scene over axes (SPEC §7's study), each case a `runout run` into
// DIR/cases/NAME. A case whose summary exists is skipped and a half-run one resumes from its
// checkpoint, so a sweep killed at any moment goes on where it stopped. Every route runs a case
// the same way, `runout sweep SWEEP --out DIR --case K`: here as child processes (--jobs), on
// Slurm as array tasks, with GNU parallel as a job list; results.csv is then the same bytes.
// Gathering the results and the job script or list: sweep_outputs.cpp.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "prepare.hpp"
#include "run_command.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/io/sweep_file.hpp"
#include "runout/setup.hpp"
#include "runout/timing.hpp"
#include "sweep.hpp"

namespace runout::app {

namespace {

namespace fs = std::filesystem;

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
  if (!o.emit.empty()) return emit_jobs(s, o, out, sweep_abs, self);
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
    const double secs = seconds_since(it->second.second);
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
