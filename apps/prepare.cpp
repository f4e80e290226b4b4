#include "prepare.hpp"

#include <cstdio>
#include <cstdlib>

#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/outputs.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/timing.hpp"

namespace runout::app {

namespace {

std::vector<io::Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<io::Override> out;
  // A malformed --set (no key=value) is a bad command line; a bad value for a good key is a
  // bad scene value, reported by the reader with the key and its range.
  for (const auto& t : texts) {
    try {
      out.push_back(io::parse_override(t));
    } catch (const ConfigError& e) {
      throw UsageError(e.what());
    }
  }
  return out;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::uint64_t pile_key(const SceneDef& scene) {
  return io::fnv1a64(io::pile_key_text(scene) + "checkpoint-v" + std::to_string(kCheckpointVersion) +
                     "physics-" + kTrajectoryHash);
}

}  // namespace

SceneDef load_scene(const std::string& path, const std::vector<std::string>& overrides,
                    const std::string& embedded, const std::string& embedded_name) {
  const auto o = parse_overrides(overrides);
  return path.empty() ? io::read_scene(embedded, embedded_name, o) : io::read_scene_file(path, o);
}

std::string default_cache_dir() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/runout";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/runout";
  return ".runout-cache";
}

PreparedWorld prepare(const SceneDef& scene, const SceneSetup& setup, int threads,
                      const std::string& cache_dir, bool use_cache, bool quiet) {
  const auto t0 = Clock::now();
  if (!scene.avalanche) return {build_explicit_world(scene, setup, threads), false, 0.0, std::nullopt};

  const std::uint64_t key = pile_key(scene);
  const std::string path = cache_dir + "/pile-" + hex(key) + ".ckpt";
  if (use_cache && io::file_exists(path)) {
    try {
      World world = restore_world(read_checkpoint(io::read_file(path), key, path), scene, setup, threads, path);
      if (!quiet) std::fprintf(stderr, "runout: settled pile from cache %s\n", path.c_str());
      std::optional<SettleReport> settle;
      if (io::file_exists(path + ".json")) settle = io::read_settle_report(io::read_file(path + ".json"));
      release(world, setup);
      return {std::move(world), true, seconds_since(t0), settle};
    } catch (const IoError& e) {
      std::fprintf(stderr, "runout: warning: ignoring cached pile (%s); settling afresh\n", e.what());
    }
  }
  if (!quiet)
    std::fprintf(stderr, "runout: settling the pile (%d discs)\n",
                 [&] { int n = 0; for (int c : setup.counts) n += c; return n; }());
  auto progress = [quiet](double t_star, double ratio) {
    if (!quiet) std::fprintf(stderr, "  settling t* = %7.2f  E_k/E_p = %.3e\n", t_star, ratio);
  };
  SettleReport settle;
  World world = build_settled_pile(scene, setup, threads, progress, &settle);
  if (!quiet)
    std::fprintf(stderr,
                 "runout: pile settled at t* = %.2f (grown at %.2f); E_k/E_p = %.2e after %g t* "
                 "without damping\n",
                 settle.t_star_settled, settle.t_star_grown, settle.ek_over_ep_undamped,
                 scene.preparation.settle_hold);
  if (use_cache) {
    try {
      io::make_directories(cache_dir);
      io::remove_stale_temporaries(cache_dir);  // of runs killed while caching a pile
      io::write_file_atomically(path + ".json", io::settle_report_json(settle));
      io::write_file_atomically(path, encode_checkpoint(world, key, {}));
    } catch (const IoError& e) {
      std::fprintf(stderr, "runout: warning: could not cache the settled pile: %s\n", e.what());
    }
  }
  release(world, setup);
  return {std::move(world), false, seconds_since(t0), settle};
}

}  // namespace runout::app
