// What `runout sweep` writes beside its cases: results.csv, timings.csv and points.csv gathered
// from the cases' summaries (--gather, and after every case of a local sweep), and the job
// script or list that runs the cases on Slurm or with GNU parallel (--emit).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <vector>

#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "sweep.hpp"

namespace runout::app {

namespace fs = std::filesystem;

namespace {

// Numbers that differ from run to run of the same physics (wall times, threads, the cache):
// kept out of results.csv, so every route gives the same file, and written to timings.csv.
bool is_timing(const std::string& key) {
  static const std::set<std::string> keys = {"wall_seconds", "particle_steps_per_second", "profile_seconds",
                                             "preparation_seconds", "pile_from_cache", "threads",
                                             "threads_fewest"};
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

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::string case_dir(const std::string& out, const io::SweepCase& c) { return out + "/cases/" + c.name; }

std::string cell(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v.get<double>());
  return buf;
}

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


int emit_jobs(const Sweep& s, const SweepOptions& o, const std::string& out, const std::string& sweep_abs,
              const std::string& self) {
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
  // slurm: sweep_command() has refused any other --emit before writing anything.
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

}  // namespace runout::app
