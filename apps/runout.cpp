// runout: 2D soft-disc DEM of bidisperse granular avalanches (SPEC.md). Command line.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <exception>

#include <unistd.h>

#include "cli_checks.hpp"
#include "pictures.hpp"
#include "run_command.hpp"
#include "runout/errors.hpp"

namespace {

// GCC's OpenMP runtime spins about 300,000 times at each join before it sleeps. With another
// program on the cores, a 2-thread run then waits for a parked thread at every step: two
// 2-thread benches at once ran 0.5-0.7 M particle-steps/s each, against 95 M alone. With 2,000
// spins they ran 16 M each, and alone 95.7 M against 95.2 M (docs/performance_log.md). libgomp
// reads the setting when it loads, before main, so runout sets it and starts itself once more,
// unless the user chose the spins or a wait policy. If that start fails, it goes on as it is.
// Nor where the user binds threads: libgomp has then already pinned this first thread to the
// first place, the new start would inherit that one CPU as its whole mask, and every thread
// would run on it (OMP_PROC_BIND=spread gave two threads on CPU 0 and half the speed).
void prefer_short_openmp_spins(char** argv) {
  for (const char* chosen : {"GOMP_SPINCOUNT", "OMP_WAIT_POLICY", "OMP_PROC_BIND", "OMP_PLACES", "GOMP_CPU_AFFINITY"})
    if (std::getenv(chosen)) return;
  if (setenv("GOMP_SPINCOUNT", "2000", 1) != 0) return;
  execv("/proc/self/exe", argv);
}

}  // namespace

int main(int argc, char** argv) {
  prefer_short_openmp_spins(argv);
  CLI::App cli{"runout: 2D discrete-element simulation of granular avalanches"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "runout 0.1.0");

  runout::app::RunOptions run;
  auto* run_cmd = cli.add_subcommand("run", "simulate a scene until the mass is at rest");
  run_cmd->add_option("scene", run.scene_path, "scene file (TOML); default: the embedded quick pile")
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--out,-o", run.out_dir, "output folder")->required();
  run_cmd->add_option("--set", run.overrides, "override a scene key, e.g. --set contact.normal_model=hertz")
      ->take_all()->allow_extra_args(false);
  run_cmd->add_option("--threads", run.threads, "OpenMP threads (default: all cores from 800 discs, else 1)")
      ->check(CLI::Range(1, 256));
  run_cmd->add_option("--seed", run.seed, "preparation seed (overrides preparation.seed)")
      ->check(CLI::Range(0LL, 9000000000000000000LL));
  run_cmd->add_option("--dump-every", run.dump_every,
                      "write LAMMPS dump frames every DT_STAR (0: off; default: output.dump_every)")
      ->check(runout::app::real_in(0.0, 1e7));
  run_cmd->add_option("--vtk-every", run.vtk_every,
                      "write VTK PolyData frames (ParaView: OUT/vtk/frames.pvd) every DT_STAR (0: off; default: "
                      "output.vtk_every)")
      ->check(runout::app::real_in(0.0, 1e7));
  run_cmd->add_flag("--resume", run.resume, "continue from OUT/checkpoint.bin (or the one before it) if present");
  run_cmd->add_flag("--overwrite", run.overwrite, "replace the results of another scene in OUT (runout's own files only)");
  run_cmd->add_option("--cache-dir", run.cache_dir, "settled-pile cache (default ~/.cache/runout)");
  run_cmd->add_flag("--no-cache", run.no_cache, "always settle the pile afresh");
  run_cmd->add_flag("--quiet,-q", run.quiet, "no progress on stderr");
  run_cmd->add_flag("--end-at-last-snapshot", run.end_at_last_snapshot,
                    "stop at the last --snapshots time even before rest (the summary then says at_rest = false)");
  run_cmd->add_option("--states", run.states,
                      "save the whole state at these t*, e.g. 0,20,40 (OUT/states/state_t*.bin: checkpoints for "
                      "`runout render` and `runout plot`; times after the run's end are not reached)");
  runout::app::add_picture_options(run_cmd, run.pictures, true);
  run_cmd->add_option("--snapshot-format", run.pictures.snapshot_format, "png | pdf | svg: the snapshots' format (default png)")
      ->check(CLI::IsMember({"png", "pdf", "svg"}));

  runout::app::BenchOptions bench;
  auto* bench_cmd = cli.add_subcommand("bench", "measure particle-steps per second on a flowing pile");
  bench_cmd->add_option("--scene", bench.scene_path, "scene (default: thesis D/d = 4, %A_p = 40)")
      ->check(CLI::ExistingFile);
  bench_cmd->add_option("--steps", bench.steps, "timed steps")->check(CLI::Range(1LL, 100000000LL));
  bench_cmd->add_option("--warmup-steps", bench.warmup_steps, "steps after release before timing (default: to t* = 5)")
      ->check(CLI::Range(0LL, 100000000LL));
  bench_cmd->add_option("--threads", bench.threads, "OpenMP threads")->check(CLI::Range(1, 256));
  auto* against = bench_cmd->add_option("--against-threads", bench.against_threads,
                                        "also time this thread count, taking turns with --threads in the same run (prints speedup)")
                      ->check(CLI::Range(1, 256));
  auto* ceiling = bench_cmd->add_flag(
      "--ceiling", bench.ceiling,
      "also time --threads copies of the pile, each stepped by its own thread at one thread, side by side against one "
      "after another: the speed-up this host gives threads that share nothing (prints ceiling_*)");
  bench_cmd->add_option("--ceiling-halo", bench.ceiling_halo,
                        "with --ceiling, also time the copies side by side reading this many discs' positions and "
                        "velocities of each other's every step, between two meetings (prints ceiling_halo_*; 0 times the "
                        "meetings alone)")
      ->check(CLI::Range(0LL, 100000000LL))
      ->needs(ceiling);
  bench_cmd->add_option("--ahead", bench.ahead,
                        "when_safe | always | never: when a step of several threads starts its forces before the verdict on "
                        "the step before (--against-threads keeps when_safe; no result depends on it)")
      ->check(CLI::IsMember(runout::app::kAheadNames));
  bench_cmd->add_flag("--ledger", bench.ledger,
                      "keep the energy ledger in the pair pass, as runs do whose output.series has \"energy\" (the "
                      "default); without it the step runs as LAMMPS's deck does, with no dissipation counters");
  auto* turns = bench_cmd->add_option("--turn-steps", bench.turn_steps,
                                      "steps of one turn with --against-threads or --ceiling (default 1000)")
                    ->check(CLI::Range(1LL, 100000000LL));
  bench_cmd->add_option("--turn-log", bench.turn_log,
                        "with --against-threads, write each turn's seconds at both thread counts, the host's line "
                        "round trip before and after it and, with --ceiling, the copies' seconds alone and in lockstep "
                        "to this CSV file")
      ->check(runout::app::file_to_write())
      ->needs(against);
  bench_cmd->callback([&bench, turns, against, ceiling] {
    if (turns->count() > 0 && against->count() == 0 && ceiling->count() == 0)
      throw CLI::ValidationError("--turn-steps requires --against-threads or --ceiling");
    if (bench.ceiling && bench.threads < 2)
      throw CLI::ValidationError("--ceiling needs --threads 2 or more (the copies stepped side by side)");
  });
  bench_cmd->add_option("--set", bench.overrides, "override a scene key")->take_all();
  bench_cmd->add_option("--cache-dir", bench.cache_dir, "settled-pile cache (default ~/.cache/runout)");
  bench_cmd->add_option("--frames", bench.frames, "time drawing, PNG and video of this many frames instead")
      ->check(CLI::Range(1LL, 100000LL))
      ->excludes(against)
      ->excludes(ceiling);
  runout::app::add_picture_options(bench_cmd, bench.picture, false);
  bench_cmd->add_option("--preset", bench.picture.preset, "x264 preset for --frames");
  bench_cmd->add_option("--crf", bench.picture.crf, "x264 crf for --frames")->check(CLI::Range(0, 51));

  runout::app::StudyOptions study;
  auto* study_cmd = cli.add_subcommand("study", "speed against accuracy over the knobs: study accuracy [SCENE] --out DIR");
  auto* accuracy_cmd = study_cmd->add_subcommand("accuracy", "run one scene over dt fraction, stiffness, integrator and model");
  study_cmd->require_subcommand(1);
  accuracy_cmd->add_option("scene", study.scene_path, "scene (default: the embedded quick pile)")->check(CLI::ExistingFile);
  accuracy_cmd->add_option("--out,-o", study.out_dir, "output folder")->required();
  accuracy_cmd->add_option("--seeds", study.seeds, "piles (preparation.seed, +1, ...) each variant runs on")
      ->check(CLI::Range(1, 1000));
  accuracy_cmd->add_flag("--resume", study.resume, "keep the runs already in OUT/runs.csv");
  accuracy_cmd->add_option("--threads", study.threads, "OpenMP threads")->check(CLI::Range(1, 256));
  accuracy_cmd->add_option("--set", study.overrides, "override a scene key")->take_all();
  accuracy_cmd->add_option("--cache-dir", study.cache_dir, "settled-pile cache (default ~/.cache/runout)");

  runout::app::SweepOptions sweep;
  auto* sweep_cmd = cli.add_subcommand("sweep", "run a scene over axes (D/d, %A_p, seed, any key): sweep SWEEP.toml --out DIR");
  sweep_cmd->add_option("sweep", sweep.sweep_path, "sweep file (TOML)")->required()->check(CLI::ExistingFile);
  sweep_cmd->add_option("--out,-o", sweep.out_dir, "output folder (cases in DIR/cases/NAME)")->required();
  sweep_cmd->add_option("--jobs,-j", sweep.jobs, "cases side by side")->check(CLI::Range(1, 1024));
  sweep_cmd->add_option("--threads-per-job", sweep.threads_per_job, "OpenMP threads per case")->check(CLI::Range(1, 256));
  sweep_cmd->add_option("--case", sweep.one_case, "run only this case (index from 0, or its name)");
  sweep_cmd->add_option("--emit", sweep.emit, "write DIR/sweep.sbatch (slurm) or DIR/jobs.txt (parallel) and stop")
      ->check(CLI::IsMember({"slurm", "parallel"}));
  sweep_cmd->add_flag("--gather", sweep.gather, "only collect DIR/results.csv and points.csv");
  sweep_cmd->add_option("--cache-dir", sweep.cache_dir, "settled-pile cache (default ~/.cache/runout)");

  runout::app::PlotOptions plot;
  auto* plot_cmd = cli.add_subcommand("plot", "the thesis's figures (PNG and PDF, matplotlib) from a sweep folder");
  plot_cmd->add_option("dir", plot.dir, "sweep folder (with points.csv)")->required()->check(CLI::ExistingDirectory);
  plot_cmd->add_option("--out,-o", plot.out, "folder for the figures (default DIR/figures)");
  plot_cmd->add_flag("!--no-frames", plot.frames, "skip the study's frames (the flow strip and the deposits)");

  runout::app::DeriveOptions derive;
  auto* derive_cmd = cli.add_subcommand("derive", "print a scene's derived stiffnesses, collision periods, time step and disc counts");
  derive_cmd->add_option("scene", derive.scene_path, "scene file (TOML); default: the embedded quick pile")
      ->check(CLI::ExistingFile);
  derive_cmd->add_option("--set", derive.overrides, "override a scene key")->take_all()->allow_extra_args(false);
  derive_cmd->add_flag("--json", derive.json, "print JSON instead of the table");

  runout::app::KeysOptions keys;
  auto* keys_cmd = cli.add_subcommand("keys", "list every scene key with what it allows, its default and its meaning");
  keys_cmd->add_flag("--json", keys.json, "print JSON instead of the table");

  runout::app::RenderOptions render;
  auto* render_cmd = cli.add_subcommand("render", "draw a checkpoint (e.g. OUT/checkpoint.bin) as a PNG, PDF or SVG");
  render_cmd->add_option("checkpoint", render.checkpoint, "checkpoint file")->required()->check(CLI::ExistingFile);
  render_cmd->add_option("-o,--output", render.output, "picture to write (.png, .pdf, .svg)")->required();
  render_cmd->add_option("--scene", render.scene, "scene (default: scene.resolved.toml beside the checkpoint, or above it for OUT/states/)")
      ->check(CLI::ExistingFile);
  runout::app::add_picture_options(render_cmd, render.picture, false);
  render_cmd->add_option("--snapshot-format", render.picture.snapshot_format,
                         "png | pdf | svg (default: from the -o name's extension, else png)")
      ->check(CLI::IsMember({"png", "pdf", "svg"}));

  runout::app::CompareOptions compare;
  auto* compare_cmd = cli.add_subcommand(
      "compare", "compare two PNGs: exit 0 within tolerance, 1 not, 2 on bad input");
  compare_cmd->add_option("expected", compare.expected, "reference PNG")->required();
  compare_cmd->add_option("actual", compare.actual, "PNG to check")->required();
  compare_cmd->add_option("--tolerance", compare.tolerance, "a pixel differs if a channel differs by more (0-255)")
      ->check(CLI::Range(0, 255));
  compare_cmd->add_option("--max-share", compare.max_share, "largest share of differing pixels that still matches")
      ->check(runout::app::real_in(0.0, 1.0));
  compare_cmd->add_option("--diff", compare.diff, "write a diff image (differing pixels red)");

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (*run_cmd) return runout::app::run_command(run);
    if (*bench_cmd) return runout::app::bench_command(bench);
    if (*render_cmd) return runout::app::render_command(render);
    if (*derive_cmd) return runout::app::derive_command(derive);
    if (*keys_cmd) return runout::app::keys_command(keys);
    if (*study_cmd) return runout::app::study_command(study);
    if (*plot_cmd) {
      plot.self = std::filesystem::canonical("/proc/self/exe").string();
      return runout::app::plot_command(plot);
    }
    if (*sweep_cmd) {
      sweep.self = std::filesystem::canonical("/proc/self/exe").string();  // the cases run this binary
      return runout::app::sweep_command(sweep);
    }
    if (*compare_cmd) return runout::app::compare_command(compare);
  } catch (const runout::UsageError& e) {
    std::fprintf(stderr, "runout: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "runout: error: %s\n", e.what());
    return 1;
  }
  return 2;
}
