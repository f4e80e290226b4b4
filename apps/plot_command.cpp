// `runout plot DIR`: the thesis's figures from a sweep, drawn by matplotlib (scripts/runout_plot.py,
// installed beside runout) — the plotting library researchers know and can restyle, instead of
// axes drawn by hand.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "runout/errors.hpp"

namespace runout::app {

namespace fs = std::filesystem;

namespace {

// $RUNOUT_PLOT_SCRIPT, else beside the binary (the build tree), else ../share/runout (installed).
std::string find_script(const std::string& self) {
  if (const char* s = std::getenv("RUNOUT_PLOT_SCRIPT"); s && *s) return s;
  const fs::path dir = fs::path(self).parent_path();
  for (const fs::path& p : {dir / "runout_plot.py", dir / ".." / "share" / "runout" / "runout_plot.py"})
    if (fs::exists(p)) return p.string();
  throw IoError("runout plot: runout_plot.py not found beside " + self + " or in ../share/runout (set RUNOUT_PLOT_SCRIPT)");
}

}  // namespace

int plot_command(const PlotOptions& o) {
  if (!fs::exists(fs::path(o.dir) / "points.csv"))
    throw UsageError("runout plot: " + o.dir + "/points.csv not found: run `runout sweep SWEEP --out " + o.dir + "` first");
  const std::string script = find_script(o.self);
  // Debian's interpreter sees Debian's python3-matplotlib; another python3 on PATH may not.
  std::string python = "/usr/bin/python3";
  if (const char* p = std::getenv("RUNOUT_PYTHON"); p && *p) python = p;
  else if (!fs::exists(python)) python = "python3";
  std::vector<std::string> args = {python, script, o.dir};
  if (!o.out.empty()) { args.push_back("--out"); args.push_back(o.out); }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execvp(python.c_str(), argv.data());
  throw IoError("runout plot: cannot run " + python + " (install python3-matplotlib)");
}

}  // namespace runout::app
