#include "run_command.hpp"

#include <omp.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "prepare.hpp"
#include "run_folder.hpp"
#include "pictures.hpp"
#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/outputs.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/run.hpp"
#include "runout/setup.hpp"

namespace runout::app {

namespace {

// Writes OUT/checkpoint.bin at its schedule, keeping the one before (run_folder.hpp).
class CheckpointWriter : public Observer {
 public:
  CheckpointWriter(const RunFolder& folder, std::uint64_t key) : folder_(folder), key_(key) {}
  void observe(const World& world, const RunState& state, double t_star) override {
    if (t_star <= 0) return;
    write_checkpoint(folder_, encode_checkpoint(world, key_, encode_run_state(state)));
  }

 private:
  const RunFolder& folder_;
  std::uint64_t key_;
};

// LAMMPS dump frames, one file each: dump/frame.<step>.lammpstrj (OVITO reads the sequence).
class DumpWriter : public Observer {
 public:
  explicit DumpWriter(std::string dir) : dir_(std::move(dir)) { io::make_directories(dir_); }
  void observe(const World& world, const RunState&, double t_star) override {
    char name[64];
    std::snprintf(name, sizeof name, "/frame.%09lld.lammpstrj", static_cast<long long>(world.step_count()));
    io::write_file_atomically(dir_ + name, io::lammps_dump_frame(world, t_star));
  }

 private:
  std::string dir_;
};

// ParaView frames, one VTK PolyData file each (vtk/frame.<step>.vtp), and vtk/frames.pvd, the
// collection that lists every frame with its t*, rewritten after each frame so it always lists
// the frames on disk. A run resumed from an earlier checkpoint (or run on to a later time)
// goes on from the frames already there, staged or published: their times are read back from
// the frames themselves (their TimeValue), so no list is lost with a killed process.
class VtkWriter : public Observer {
 public:
  VtkWriter(std::string dir, const std::string& published, const SceneSetup& setup, double packing)
      : dir_(std::move(dir)), setup_(setup), packing_(packing) {
    io::make_directories(dir_);
    for (const std::string& folder : {published, dir_}) {
      std::error_code ec;
      for (const auto& e : std::filesystem::directory_iterator(folder, ec)) {
        const std::string name = e.path().filename().string();
        long long step = 0;
        char tail[8] = {};
        if (std::sscanf(name.c_str(), "frame.%lld.%7s", &step, tail) != 2 || std::string(tail) != "vtp") continue;
        std::ifstream in(e.path(), std::ios::binary);
        std::string head(1024, '\0');
        in.read(head.data(), static_cast<std::streamsize>(head.size()));
        head.resize(static_cast<std::size_t>(in.gcount()));
        if (const auto t = io::vtk_frame_time(head)) frames_[step] = {*t, name};
      }
    }
  }
  void observe(const World& world, const RunState&, double t_star) override {
    // Basal-layer membership as the measurements and the pictures have it (measure.hpp).
    const std::vector<char> layer =
        basal_layer(world.particles(), world.segments(), setup_.roles, setup_.large_diameter, packing_).member;
    char name[64];
    std::snprintf(name, sizeof name, "frame.%09lld.vtp", static_cast<long long>(world.step_count()));
    io::write_file_atomically(dir_ + "/" + name, io::vtk_polydata_frame(world, t_star, layer));
    frames_[world.step_count()] = {t_star, name};
    std::vector<io::VtkCollectionEntry> list;
    for (const auto& [step, entry] : frames_) list.push_back(entry);
    io::write_file_atomically(dir_ + "/frames.pvd", io::vtk_collection(list));
  }

 private:
  std::string dir_;
  const SceneSetup& setup_;
  double packing_;
  std::map<long long, io::VtkCollectionEntry> frames_;  // by step
};

// The whole state at chosen t*, each a checkpoint (it resumes, renders and decodes like one):
// states/state_t0020.00.bin, for `runout render` and the study's frames (`runout plot`).
class StateWriter : public Observer {
 public:
  StateWriter(std::string dir, std::uint64_t key) : dir_(std::move(dir)), key_(key) {
    io::make_directories(dir_);
  }
  void observe(const World& world, const RunState& run_state, double t_star) override {
    char name[64];
    std::snprintf(name, sizeof name, "/state_t%07.2f.bin", t_star);
    // The flow at t*, not the process: without the wall time of earlier segments, the state of
    // a resumed run is the uninterrupted run's, byte for byte.
    RunState state = run_state;
    state.wall_seconds = 0;
    io::write_file_atomically(dir_ + name, encode_checkpoint(world, key_, encode_run_state(state)));
  }

 private:
  std::string dir_;
  std::uint64_t key_;
};

// Default: every core from 800 discs, one thread below, where the threads' meeting at every
// step costs more than it saves. Whole runs of the examples to rest, one thread against two
// (docs/performance_log.md, forty-eighth session): 250 and 500 discs ran faster on one, 650
// about even to ×1.3 faster on two, 900–1,850 ×1.2–1.6 faster on two.
int resolve_threads(int threads, const SceneSetup& setup) {
  constexpr int kDiscsForEveryCore = 800;
  if (threads > 0) return threads;
  int discs = 0;
  for (int c : setup.counts) discs += c;
  return discs >= kDiscsForEveryCore ? std::max(1, omp_get_num_procs()) : 1;
}

// SIGINT and SIGTERM ask the run to stop after the current step. A signal handler can reach
// nothing but a static, so this one flag is the program's only global; it lives here, and
// only while a run steps (SignalScope).
std::atomic<int> stop_signal{0};
extern "C" void request_stop(int signo) { stop_signal.store(signo); }

class SignalScope {
 public:
  SignalScope() {
    stop_signal.store(0);
    struct sigaction sa = {};
    sa.sa_handler = request_stop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~SignalScope() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  SignalScope(const SignalScope&) = delete;
  SignalScope& operator=(const SignalScope&) = delete;

 private:
  struct sigaction old_int_ = {}, old_term_ = {};
};

// Every picture option a run will use, checked before anything is settled or written.
void check_picture_options(const PictureOptions& o, const SceneDef& scene) {
  // Movie frames stay PNG: a format with no snapshot to apply to is a mistake, not a no-op.
  if (!o.snapshot_format.empty() && o.snapshots.empty())
    throw UsageError("--snapshot-format needs --snapshots (the movie and --frames are always video and PNG)");
  if (!o.wants_pictures()) return;
  parse_frame_size(o.size);
  if (o.camera == "window") parse_window(o.window);
  else if (!o.window.empty()) throw UsageError("--window needs --camera window");
  if (!o.snapshots.empty()) {
    const double last = parse_times(o.snapshots).back();
    // The run goes on to the last snapshot: beyond the time limit it would never end.
    if (last > scene.rest.max_time)
    {
      std::ostringstream msg;
      msg << "--snapshots: t* = " << last << " is beyond rest.max_time = " << scene.rest.max_time
          << " (t*); raise it with --set rest.max_time=... or drop that snapshot";
      throw UsageError(msg.str());
    }
  }
  if (!o.movie.empty()) check_file_writable(o.movie, "--movie");
  if (!o.frames_dir.empty()) check_folder_writable(o.frames_dir, "--frames");
  if (!o.snapshot_dir.empty()) check_folder_writable(o.snapshot_dir, "--snapshot-dir");
}

}  // namespace

int run_command(const RunOptions& o) {
  const std::string source = !o.scene_path.empty() ? o.scene_path
                             : !o.scene_text.empty() ? o.scene_name : "<embedded quick scene>";
  SceneDef scene = load_scene(o.scene_path, o.overrides,
                              o.scene_text.empty() ? io::embedded_quick_scene() : o.scene_text, source);
  if (o.seed >= 0) scene.preparation.seed = static_cast<std::uint64_t>(o.seed);
  if (o.dump_every >= 0) scene.output.dump_every = o.dump_every;
  if (o.vtk_every >= 0) scene.output.vtk_every = o.vtk_every;
  if (o.end_at_last_snapshot) {
    // Nothing else asked for more: the run ends with the last picture (output.end_time, so the
    // resolved scene repeats it).
    if (o.pictures.snapshots.empty())
      throw UsageError("--end-at-last-snapshot needs --snapshots (the times to stop after)");
    const double last = parse_times(o.pictures.snapshots).back();
    if (!(last > 0))
      throw UsageError("--end-at-last-snapshot: the last snapshot must come after t* = 0 (got " +
                       o.pictures.snapshots + ")");
    if (scene.output.end_time <= 0 || scene.output.end_time > last) scene.output.end_time = last;
  }
  const SceneSetup setup = derive_setup(scene, source);
  check_runnable(scene, setup, source);
  check_picture_options(o.pictures, scene);
  const std::vector<double> state_times = o.states.empty() ? std::vector<double>{} : parse_times(o.states, "--states");
  check_folder_writable(o.out_dir, "--out");
  const int threads = resolve_threads(o.threads, setup);

  // What the folder holds decides what this run may do to it; nothing is touched yet.
  const RunFolder folder(o.out_dir);
  const std::uint64_t key = io::physics_key(scene);
  // The run's one World: restored from the checkpoint it resumes from, or prepared afresh.
  std::optional<World> resumed_world;
  std::optional<RunState> resumed;
  const FolderPlan plan = plan_folder(folder, key, o.resume, o.overwrite,
                                      [&](const std::string& bytes, const std::string& path) {
                                        Checkpoint c = read_checkpoint(bytes, key, path);
                                        RunState state = decode_run_state(c.run_state, path);
                                        resumed_world.emplace(restore_world(std::move(c), scene, setup, threads, path));
                                        resumed = std::move(state);
                                      });
  for (const auto& note : plan.notes) std::fprintf(stderr, "runout: %s\n", note.c_str());
  std::optional<PreparedWorld> prepared_world;
  if (plan.resume) {
    prepared_world.emplace(PreparedWorld{std::move(*resumed_world), false, 0.0, std::nullopt});
    if (!o.quiet)
      std::fprintf(stderr, "runout: resuming from %s at t* = %.3f\n", plan.resume->path.c_str(),
                   prepared_world->world.time() / setup.unit_time);
  } else {
    resumed.reset();
    resumed_world.reset();
    prepared_world.emplace(prepare(scene, setup, threads, o.cache_dir.empty() ? default_cache_dir() : o.cache_dir,
                                   !o.no_cache, o.quiet));
  }
  PreparedWorld& prepared = *prepared_world;
  World& world = prepared.world;

  // From here on the folder is this run's: an earlier run's own files go (summary.json first),
  // temporaries of killed runs too, and the scene is written beside the checkpoints.
  io::make_directories(folder.dir);
  if (plan.clear && !plan.resume) clear_own_files(folder);
  io::remove_stale_temporaries(folder.dir);
  std::remove(folder.summary.c_str());
  io::write_file_atomically(folder.scene, io::write_scene(scene));
  if (!plan.resume && prepared.settle)
    io::write_file_atomically(folder.preparation, io::settle_report_json(*prepared.settle));
  else if (plan.resume && io::file_exists(folder.preparation))
    prepared.settle = io::read_settle_report(io::read_file(folder.preparation));

  AvalancheRun run = resumed ? AvalancheRun(world, scene, setup, *resumed)
                             : AvalancheRun(world, scene, setup);
  CheckpointWriter checkpoints(folder, key);
  if (scene.output.checkpoint_every > 0)
    run.add_observer(checkpoints, {scene.output.checkpoint_every, scene.output.checkpoint_every, {}});
  std::optional<DumpWriter> dumps;
  if (scene.output.dump_every > 0) {
    dumps.emplace(folder.staging + "/dump");
    run.add_observer(*dumps, {scene.output.dump_every, 0.0, {}});
  }
  std::optional<VtkWriter> vtk;
  if (scene.output.vtk_every > 0) {
    vtk.emplace(folder.staging + "/vtk", folder.vtk, setup, scene.output.basal_layer_packing);
    run.add_observer(*vtk, {scene.output.vtk_every, 0.0, {}});
  }
  std::optional<StateWriter> states;
  if (!state_times.empty()) {
    states.emplace(folder.staging + "/states", key);
    run.add_observer(*states, {0.0, 0.0, state_times});
  }
  std::unique_ptr<PictureSession> pictures;
  if (o.pictures.wants_pictures()) {
    if (o.pictures.snapshot_dir.empty() && !o.pictures.snapshots.empty()) io::make_directories(folder.staging);
    pictures = open_pictures(o.pictures, world, scene, setup, folder.staging);
    for (const auto& [observer, schedule] : pictures->observers()) run.add_observer(*observer, schedule);
    run.set_min_end_time(pictures->last_time());  // the run goes on to the last snapshot
  }
  if (!o.quiet) {
    std::fprintf(stderr, "runout: %zu discs, dt = %.3e s (%.0f steps per t*), %d thread%s\n",
                 world.particles().size(), setup.dt, setup.unit_time / setup.dt, threads,
                 threads == 1 ? "" : "s");
    run.set_progress([](double t_star, double ratio, double rate) {
      std::fprintf(stderr, "  t* = %8.2f  E_k/Ep0 = %.3e  %8.0f steps/s\n", t_star, ratio, rate);
    });
  }
  // Threads chosen by runout (no --threads) follow the cores the run gets: beside another
  // program fewer, then all again once they are free (ThreadGovernor). An explicit --threads
  // is kept as asked.
  std::optional<ThreadGovernor> governor;
  if (o.threads <= 0 && threads > 1) {
    governor.emplace(threads);
    run.set_thread_governor(&*governor, [quiet = o.quiet, most = threads](double t_star, int now, double cores) {
      if (quiet) return;
      if (now < most)
        std::fprintf(stderr, "runout: t* = %.2f: the run got %.1f of %d cores (other programs hold the rest): %d thread%s\n",
                     t_star, cores, most, now, now == 1 ? "" : "s");
      else
        std::fprintf(stderr, "runout: t* = %.2f: trying %d threads again\n", t_star, now);
    });
  }
  // The handlers stay until summary.json is written: a signal that arrives once the run has
  // ended (while the movie drains, say) lets its results be finished instead of lost.
  const SignalScope signals;
  run.set_stop_request(&stop_signal);
  const RunResult result = run.run();
  if (result.interrupted) {
    // A resumable partial folder: the scene, this step's checkpoint and the staged results. The
    // movie's .part goes with the picture session (a movie cannot be continued).
    write_checkpoint(folder, encode_checkpoint(world, key, encode_run_state(run.state())));
    pictures.reset();
    const int signo = stop_signal.load();
    std::fprintf(stderr, "runout: stopped by %s at t* = %.3f; checkpoint %s written; continue with --resume\n",
                 signo == SIGTERM ? "SIGTERM" : "SIGINT", result.t_star_end, folder.checkpoint.c_str());
    return 128 + signo;
  }
  if (pictures) {
    pictures->finish();
    if (!o.quiet) std::fprintf(stderr, "runout: %s\n", pictures->report().c_str());
  }

  io::SummaryContext ctx;
  ctx.scene_name = scene.name;
  ctx.scene_source = source;
  ctx.unit_length = setup.unit_length;
  ctx.unit_time = setup.unit_time;
  ctx.tau_min = setup.tau_min;
  ctx.threads = threads;
  ctx.seed = scene.preparation.seed;
  ctx.pile_from_cache = prepared.from_cache;
  ctx.preparation_seconds = prepared.seconds;
  ctx.settle = prepared.settle;
  for (const auto& sp : scene.species) {
    ctx.species_names.push_back(sp.name);
    ctx.species_diameters.push_back(sp.diameter);
  }

  // The results together, summary.json last: a folder with a summary is a complete result.
  publish_staged(folder);
  io::write_file_atomically(folder.timeseries, io::timeseries_csv(run.state().series, scene.output.series));
  write_checkpoint(folder, encode_checkpoint(world, key, encode_run_state(run.state())));
  io::write_file_atomically(folder.summary, io::summary_json(result, ctx));
  if (stop_signal.load() != 0)
    std::fprintf(stderr, "runout: a stop signal came after the run had ended; its results are complete\n");

  if (!o.quiet) {
    if (result.at_rest)
      std::fprintf(stderr, "runout: at rest from t* = %.2f, deposit measured at t* = %.2f (run ended at t* = %.2f)",
                   result.t_star_rest, result.final_energy.t_star, result.t_star_end);
    else
      std::fprintf(stderr, "runout: stopped at t* = %.2f, not at rest", result.t_star_end);
    std::fprintf(stderr, "; mu_global = H_cm/L_cm = %s; %.3g particle-steps/s\n",
                 std::isfinite(result.mu_global) ? std::to_string(result.mu_global).c_str() : "undefined (L_cm = 0)",
                 result.particle_steps_per_second);
  }
  if (std::isfinite(result.mu_global)) std::printf("mu_global: %.6f\n", result.mu_global);
  else std::printf("mu_global: null\n");
  if (!result.at_rest && !result.reached_end_time) {
    std::fprintf(stderr,
                 "runout: the mass was not at rest by rest.max_time = %g (t*); summary.json says "
                 "at_rest = false. Raise rest.max_time or rest.ek_threshold.\n",
                 scene.rest.max_time);
    return 3;
  }
  return 0;
}

}  // namespace runout::app
