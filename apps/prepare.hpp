// What every command does before it steps: read the scene (file or embedded, with --set
// overrides) and get a released pile, settled afresh or read from the pile cache.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "runout/scene.hpp"
#include "runout/setup.hpp"
#include "runout/world.hpp"

namespace runout::app {

// The physics of this build, as the hash of a reference trajectory that tests/test_trajectory.cpp
// checks (tests/golden/trajectory_hash.txt, read by CMake): a cached pile is never one that this
// binary would not have settled itself.
inline constexpr const char* kTrajectoryHash = RUNOUT_TRAJECTORY_HASH;

// `path` empty: the embedded scene text, reported as `embedded_name` in errors.
SceneDef load_scene(const std::string& path, const std::vector<std::string>& overrides,
                    const std::string& embedded, const std::string& embedded_name);

// $XDG_CACHE_HOME/runout, else ~/.cache/runout, else ./.runout-cache.
std::string default_cache_dir();

struct PreparedWorld {
  World world;
  bool from_cache = false;
  double seconds = 0;  // settling or cache read
  std::optional<SettleReport> settle;  // what settling measured (kept beside a cached pile)
};

// An avalanche scene: the settled pile (from the cache when `use_cache` and present), released.
// An explicit scene: its discs and walls as given.
PreparedWorld prepare(const SceneDef& scene, const SceneSetup& setup, int threads,
                      const std::string& cache_dir, bool use_cache, bool quiet);

}  // namespace runout::app
