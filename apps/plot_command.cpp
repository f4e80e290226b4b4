// `runout plot DIR`: the thesis's figures from a sweep, drawn by matplotlib (scripts/runout_plot.py,
// installed beside runout) — the plotting library researchers know and can restyle, instead of
// axes drawn by hand.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

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

int run_plot_script(const std::string& self, const std::vector<std::string>& script_args) {
  const std::string script = find_script(self);
  // Debian's interpreter sees Debian's python3-matplotlib; another python3 on PATH may not.
  std::string python = "/usr/bin/python3";
  if (const char* p = std::getenv("RUNOUT_PYTHON"); p && *p) python = p;
  else if (!fs::exists(python)) python = "python3";
  std::vector<std::string> args = {python, script};
  args.insert(args.end(), script_args.begin(), script_args.end());
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw IoError("runout plot: cannot start " + python);
  if (pid == 0) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execvp(python.c_str(), argv.data());
    std::fprintf(stderr, "runout plot: cannot run %s (install python3-matplotlib)\n", python.c_str());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

int plot_command(const PlotOptions& o) {
  if (!fs::exists(fs::path(o.dir) / "points.csv"))
    throw UsageError("runout plot: " + o.dir + "/points.csv not found: run `runout sweep SWEEP --out " + o.dir + "` first");
  const std::string figures = o.out.empty() ? o.dir + "/figures" : o.out;
  if (o.frames) {
    // The pictures of the study come first: the script lays them out and puts them in the report.
    // Without the picture module (a build without OSMesa) the figures are still drawn, and
    // the message says what is missing.
    try {
      const int n = render_study_frames(o.dir, figures + "/frames");
      std::fprintf(stderr, "runout plot: %d study frames drawn in %s/frames\n", n, figures.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "runout plot: the study's frames were not drawn: %s\n", e.what());
      std::error_code ec;
      fs::remove(figures + "/frames/frames.json", ec);  // no stale list of pictures
    }
  }
  std::vector<std::string> args = {o.dir, "--out", figures};
  return run_plot_script(o.self, args);
}

}  // namespace runout::app
