// Sweep files (runout sweep): a base scene and the axes to vary, read strictly like scenes
// (an unknown key, an empty axis or a value out of range names the file and the key).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "runout/io/scene_file.hpp"

namespace runout::io {

// One case of a sweep: its folder name, its axis values (as written) and the scene overrides
// they stand for.
struct SweepCase {
  std::string name;
  std::vector<std::pair<std::string, std::string>> axes;  // axis key, value text
  std::vector<Override> overrides;
  bool keeps_states = false;  // saves its states at the strip times (runout run --states)
};

struct SweepDef {
  std::string source;                  // the sweep file, for errors
  std::string base;                    // "thesis" (the built-in thesis pile) or a scene path
  std::vector<std::string> axis_keys;  // in file order
  std::vector<SweepCase> cases;        // the product (or the zip) of the axes, first axis slowest
  // [pictures]: the t* of the flow sequence (thesis fig. 3.4; its last panel is the deposit at
  // rest), saved as states by the cases of the first seed (`seeds = "all"`: every case).
  std::vector<double> strip_times = {0, 20, 40, 60, 80, 100};
};

// Axes: `ratio` (D/d: species.small.diameter = D / ratio, 8.33 standing for the thesis's
// d = 0.12 m), `small_share` (%A_p in [0, 100]: the small and large area shares, SPEC eq.
// 3.1), `seed` (preparation.seed) and any scene key written as a quoted dotted name.
// `large_diameter` is the base scene's large diameter D.
SweepDef read_sweep(const std::string& text, const std::string& source, double large_diameter);

}  // namespace runout::io
