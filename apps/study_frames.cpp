// The study's frames for `runout plot` (thesis fig. 3.4 and figs. 4.7–4.10): each case's saved
// states (runout run --states, which the sweep asks for) and its final checkpoint, drawn by the
// picture module in windows chosen here from the discs, with a JSON beside each picture saying
// what it covers. runout_plot.py lays them out with axes, the deposit's centroid and a legend.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/measure.hpp"
#include "runout/setup.hpp"

namespace runout::app {

namespace fs = std::filesystem;

namespace {

struct Window {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void add(double x, double y) { x0 = std::min(x0, x); y0 = std::min(y0, y); x1 = std::max(x1, x); y1 = std::max(y1, y); }
};

// The flow's extent in one state: every disc edge, except that the farthest 1 % of discs
// along x (lone discs rolling ahead, on to the end wall) do not stretch the strip.
void add_flow(Window& w, const Particles& p) {
  if (p.size() == 0) return;
  std::vector<double> front(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) front[k] = p.x[k] + p.radius[k];
  const std::size_t at = static_cast<std::size_t>(0.99 * (front.size() - 1));
  std::nth_element(front.begin(), front.begin() + at, front.end());
  const double reach = front[at];
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.x[k] + p.radius[k] <= reach) {
      w.add(p.x[k] - p.radius[k], p.y[k] - p.radius[k]);
      w.add(p.x[k] + p.radius[k], p.y[k] + p.radius[k]);
    }
}

// The picture size for a window: `width` pixels across, the height from the window's aspect
// (even, for video tools), at least 96.
std::string size_for(const Window& w, int width) {
  int h = static_cast<int>(std::lround(width * (w.y1 - w.y0) / (w.x1 - w.x0)));
  h = std::clamp(h + h % 2, 96, 4096);
  return std::to_string(width) + "x" + std::to_string(h);
}

std::string window_text(const Window& w) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g,%.9g", w.x0, w.y0, w.x1, w.y1);
  return buf;
}


void draw(const std::string& checkpoint, const std::string& scene, const Window& w, int width,
          const std::string& color, const std::string& png) {
  RenderOptions r;
  r.checkpoint = checkpoint;
  r.scene = scene;
  r.output = png;
  r.describe = png.substr(0, png.size() - 4) + ".json";
  r.quiet = true;
  r.picture.camera = "window";
  r.picture.window = window_text(w);
  r.picture.size = size_for(w, width);
  r.picture.color = color;
  r.picture.no_overlays = true;  // the figure draws axes, labels and the legend
  r.picture.outlines = true;
  if (render_command(r) != 0) throw IoError("runout plot: could not draw " + checkpoint);
}

}  // namespace

// Draws DIR/figures/frames/NAME/{strip_K,deposit}.png (+ .json) for every finished case and
// writes DIR/figures/frames/frames.json listing them. Returns the number of pictures.
int render_study_frames(const std::string& sweep_dir, const std::string& frames_dir) {
  nlohmann::json manifest;
  manifest["cases"] = nlohmann::json::array();
  int pictures = 0;
  std::vector<fs::path> cases;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(sweep_dir) / "cases", ec))
    if (e.is_directory() && fs::exists(e.path() / "summary.json") && fs::exists(e.path() / "checkpoint.bin"))
      cases.push_back(e.path());
  std::sort(cases.begin(), cases.end());
  for (const fs::path& dir : cases) {
    const std::string scene_path = (dir / "scene.resolved.toml").string();
    const SceneDef scene = io::read_scene_file(scene_path);
    const SceneSetup setup = derive_setup(scene, scene_path);
    const std::uint64_t key = io::physics_key(scene);
    auto load = [&](const fs::path& file) {
      World world = build_explicit_world(scene, setup, 1);
      decode_checkpoint(io::read_regular_file(file.string(), UINTMAX_MAX), key, world, file.string());
      return world;
    };
    const std::string name = dir.filename().string();
    const fs::path out = fs::path(frames_dir) / name;
    io::make_directories(out.string());
    nlohmann::json entry;
    entry["case"] = name;
    const double D = setup.large_diameter, d = setup.unit_length;
    entry["large_diameter"] = D;
    entry["small_diameter"] = d;

    // Fig. 3.4: the states in time order, then the deposit (the final checkpoint), all in one
    // window so that the panels compare.
    std::vector<fs::path> states;
    for (const auto& e : fs::directory_iterator(dir / "states", ec))
      if (e.path().extension() == ".bin" && e.path().filename().string().rfind("state_t", 0) == 0)
        states.push_back(e.path());
    std::sort(states.begin(), states.end());  // state_t0020.00.bin: the name sorts by t*
    const World final_state = load(dir / "checkpoint.bin");
    if (!states.empty()) {
      states.push_back(dir / "checkpoint.bin");
      Window w;
      std::vector<World> worlds;
      for (const auto& s : states) {
        worlds.push_back(s == states.back() ? final_state : load(s));
        add_flow(w, worlds.back().particles());
      }
      w = {w.x0 - D, std::min(w.y0, 0.0) - 0.5 * D, w.x1 + D, w.y1 + D};
      entry["strip"] = nlohmann::json::array();
      for (std::size_t k = 0; k < states.size(); ++k) {
        char file[32];
        std::snprintf(file, sizeof file, "strip_%02zu.png", k);
        draw(states[k].string(), scene_path, w, 1800, "species", (out / file).string());
        entry["strip"].push_back({{"png", name + "/" + file}, {"at_rest", k + 1 == states.size()}});
        ++pictures;
      }
    }

    // Figs. 4.7–4.10: the deposit around its centroid (marked by the figure), the basal layer
    // highlighted, at a scale where one small disc is about 8 pixels across: 200 d wide, or the
    // whole body of the deposit if it is shorter.
    const Particles& p = final_state.particles();
    const BasalLayer layer = basal_layer(p, final_state.segments(), setup.roles, D, scene.output.basal_layer_packing);
    double area = 0, cx = 0, cy = 0;
    for (std::size_t k = 0; k < p.size(); ++k)
      if (p.x[k] >= layer.deposit_start && p.x[k] <= layer.deposit_end) {
        const double a = p.radius[k] * p.radius[k];
        area += a;
        cx += a * p.x[k];
        cy += a * p.y[k];
      }
    if (area > 0) {
      cx /= area;
      cy /= area;
      const double half = 0.5 * std::min(layer.deposit_end - layer.deposit_start + 2 * D, 200 * d);
      Window w;
      w.add(cx - half, 0.0);
      w.add(cx + half, 0.0);
      for (std::size_t k = 0; k < p.size(); ++k)
        if (std::abs(p.x[k] - cx) < half) w.add(p.x[k], p.y[k] + p.radius[k]);
      w = {w.x0, std::min(w.y0, 0.0) - 0.3 * D, w.x1, w.y1 + 0.5 * D};
      draw((dir / "checkpoint.bin").string(), scene_path, w, 1600, "layer", (out / "deposit.png").string());
      entry["deposit"] = {{"png", name + "/deposit.png"}, {"centroid", {cx, cy}},
                          {"layer_discs", std::count(layer.member.begin(), layer.member.end(), 1)}};
      ++pictures;
    }
    manifest["cases"].push_back(entry);
  }
  io::write_file_atomically(frames_dir + "/frames.json", manifest.dump(1) + "\n");
  return pictures;
}

}  // namespace runout::app
