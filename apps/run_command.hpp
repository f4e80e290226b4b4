// `runout run` and `runout bench`: the glue between the command line, the scene file, the
// core's run loop and the files a run writes.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "pictures.hpp"
#include "runout/world.hpp"

namespace runout::app {

struct RunOptions {
  std::string scene_path;  // empty: scene_text, else the embedded quick pile
  std::string scene_text;  // a scene given as text (a sweep's base), named scene_name in errors
  std::string scene_name;
  std::string out_dir;
  std::vector<std::string> overrides;
  int threads = 0;  // 0: all cores
  long long seed = -1;
  double dump_every = -1;  // < 0: from the scene
  double vtk_every = -1;   // < 0: from the scene
  bool resume = false;
  bool overwrite = false;  // replace another scene's results in out_dir (runout's own files only)
  std::string cache_dir;   // empty: $XDG_CACHE_HOME/runout or ~/.cache/runout
  bool no_cache = false;
  bool quiet = false;
  bool end_at_last_snapshot = false;  // stop at the last --snapshots time, at rest or not
  std::string states;  // "0,20,40": the whole state (a checkpoint) at these t*, OUT/states/
  PictureOptions pictures;
};

// bench --ahead's names of StepSettings::Ahead: the option's allowed values and their meaning.
inline const std::map<std::string, StepSettings::Ahead> kAheadNames{
    {"when_safe", StepSettings::Ahead::when_safe},
    {"always", StepSettings::Ahead::always},
    {"never", StepSettings::Ahead::never}};

struct BenchOptions {
  std::string scene_path;  // empty: the embedded bench scene (D/d = 4, %A_p = 40)
  long long steps = 20000;
  long long warmup_steps = -1;  // -1: run to t* = 5 after release first; 0: none
  int threads = 1;
  // > 0: time this thread count too, in turns with `threads` every `turn_steps` steps of the
  // same run, so a host whose speed drifts over seconds slows both alike (docs/performance.md).
  int against_threads = 0;
  // With --threads T: also step T copies of the pile, each at one thread by its own thread,
  // in turns alone and side by side (the host's ceiling for threads that share nothing).
  bool ceiling = false;
  // >= 0 (--ceiling-halo): the copies also run side by side reading this many discs of each
  // other's every step, between two meetings (bench_command.cpp, Ceiling).
  long long ceiling_halo = -1;
  // When --threads' steps start their forces before the verdict on the step before
  // (StepSettings::Ahead, by its name in kAheadNames); --against-threads always runs with the
  // default, when_safe.
  std::string ahead = "when_safe";
  // Keep the energy ledger (--ledger), as a run does whose output.series has "energy" (the
  // default); off, the step is timed as LAMMPS's deck runs it, without dissipation counters.
  bool ledger = false;
  long long turn_steps = 1000;
  // Non-empty (--turn-log, with --against-threads): each turn's seconds at both counts and the
  // line round trips read around it, as CSV.
  std::string turn_log;
  std::string cache_dir;
  std::vector<std::string> overrides;
  long long frames = 0;  // > 0: time this many frames of drawing, PNG and video instead
  PictureOptions picture;
};

struct StudyOptions {
  std::string scene_path;  // empty: the embedded quick pile
  std::string out_dir;
  int seeds = 3;           // piles preparation.seed, +1, ... : every variant runs on each
  bool resume = false;     // keep the runs already in OUT/runs.csv
  int threads = 1;
  std::string cache_dir;
  std::vector<std::string> overrides;
};

int run_command(const RunOptions& o);    // returns the process exit code
// `runout study accuracy` (study_command.cpp): one scene over a grid of the speed/accuracy
// knobs on several piles; writes runs.csv, study.csv, study.md and study.png into the output folder.
int study_command(const StudyOptions& o);
int bench_command(const BenchOptions& o);

struct SweepOptions {
  std::string sweep_path;
  std::string out_dir;
  int jobs = 1;              // cases side by side on this machine
  int threads_per_job = 1;
  std::string one_case;      // --case K (index from 0, or the case's name): run only that one
  std::string emit;          // "slurm" or "parallel": write the job script / list and stop
  bool gather = false;       // only collect results.csv and points.csv
  std::string cache_dir;
  std::string self;          // this binary, for the cases it starts
};
struct DeriveOptions {
  std::string scene_path;  // empty: the embedded quick pile
  std::vector<std::string> overrides;
  bool json = false;
};
// `runout derive` (derive_command.cpp): the setup table of SPEC §3-4 for a scene.
int derive_command(const DeriveOptions& o);

struct KeysOptions {
  bool json = false;
};
// `runout keys` (keys_command.cpp): every scene key with its range, default and meaning.
int keys_command(const KeysOptions& o);

struct PlotOptions {
  std::string dir;   // a sweep folder
  std::string out;   // default DIR/figures
  bool frames = true;  // the study's frames (figs. 3.4, 4.7-4.10) from the cases' states
  std::string self;  // this binary: the script is found beside it
};
// `runout plot DIR` (plot_command.cpp): runs scripts/runout_plot.py (matplotlib) on a sweep.
int plot_command(const PlotOptions& o);
// Draws the study's frames of a sweep's finished cases into FRAMES_DIR (study_frames.cpp):
// the pictures and FRAMES_DIR/frames.json, which lists them. Returns the number of pictures.
int render_study_frames(const std::string& sweep_dir, const std::string& frames_dir);
// Runs scripts/runout_plot.py (found beside `self`) with these arguments; its exit code.
int run_plot_script(const std::string& self, const std::vector<std::string>& script_args);

// `runout sweep` (sweep_command.cpp): one scene over axes, each case in DIR/cases/NAME, resumable.
int sweep_command(const SweepOptions& o);

}  // namespace runout::app
