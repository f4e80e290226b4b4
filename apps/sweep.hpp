// The sweep a `runout sweep` works on, shared by sweep_command.cpp (reads the sweep file, runs
// its cases) and sweep_outputs.cpp (what it writes beside the cases: the tables gathered from
// their summaries, and the job script or list for Slurm or GNU parallel).
#pragma once

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.hpp"
#include "runout/io/sweep_file.hpp"

namespace runout::app {

struct Sweep {
  std::string text;        // the sweep file as read
  std::string base_text;   // the base scene
  std::string base_name;
  io::SweepDef def;
  // Work of each case per t* of flow (discs x steps per t*): what the estimate of the time
  // left weighs the cases by, since a D/d = 8.33 pile costs tens of times a D/d = 2 one.
  std::map<std::string, double> work;
};

std::string case_dir(const std::string& out, const io::SweepCase& c);  // DIR/cases/NAME

// A summary's number as results.csv writes it: integers whole, reals to 17 digits, true as 1,
// null as an empty cell.
std::string cell(const nlohmann::json& v);

struct Gathered {
  std::size_t complete = 0;
};

// Rewrites DIR/results.csv, timings.csv and points.csv from the cases that have a summary so far.
Gathered gather(const Sweep& s, const std::string& out);

// --emit: DIR/jobs.txt (parallel) or DIR/sweep.sbatch (slurm), each case the command
// `SELF sweep SWEEP_ABS --out OUT --case K`, and what to run next on stdout. Returns 0.
int emit_jobs(const Sweep& s, const SweepOptions& o, const std::string& out, const std::string& sweep_abs,
              const std::string& self);

}  // namespace runout::app
