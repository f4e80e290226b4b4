// `runout bench`: particle-steps per second of a settled pile and where the step's time goes
// (docs/performance.md), or with --frames the cost of drawing them.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "host_probes.hpp"
#include "pictures.hpp"
#include "prepare.hpp"
#include "run_command.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/setup.hpp"
#include "runout/timing.hpp"

namespace runout::app {

namespace {

// The host's ceiling (--ceiling): `count` copies of `world`, each stepped at one thread, first
// one after another, then side by side by as many threads that never meet ("apart"), then side
// by side meeting after every step as the blocks of a step do ("lockstep"). They share nothing,
// so what side by side falls short of `count` times is the host's, not runout's
// (docs/performance.md, issue 11). Each mode starts from `world`'s state, so all of them time the
// same stretch of the flow as the turn of `world` that follows.
// With a halo (--ceiling-halo), a fourth mode: side by side, each copy after its step reading
// `halo` discs' positions and velocities that the next copy's thread wrote in that step, as a
// step's threads read the discs their rows reach in the next block (docs/performance_log.md, issue
// 11 thirty-seventh session). Its two meetings a step (after the steps; after the reads, before
// the next step writes again) keep the copies race-free; with `halo` 0 it times them alone.
struct Ceiling {
  long long steps = 0;  // of each copy in each mode
  double alone = 0, apart = 0, lockstep = 0, halo = 0;  // seconds
  Ceiling& operator+=(const Ceiling& t) {
    steps += t.steps; alone += t.alone; apart += t.apart; lockstep += t.lockstep; halo += t.halo;
    return *this;
  }
};

// The halo's discs: `halo` of them from the middle of the pile on (where a step's second block
// starts), as many as there are.
std::size_t halo_discs(std::size_t n, long long halo) {
  return std::min(n - n / 2, static_cast<std::size_t>(halo));
}

double read_halo(const Particles& p, long long halo) {
  const std::size_t lo = p.size() / 2, hi = lo + halo_discs(p.size(), halo);
  double sum = 0;
  for (std::size_t k = lo; k < hi; ++k) sum += p.x[k] + p.y[k] + p.vx[k] + p.vy[k] + p.omega[k];
  return sum;
}

Ceiling ceiling_turn(const World& world, int count, long long steps, long long halo) {
  std::vector<World> copies;
  auto fresh_copies = [&] {
    copies.assign(static_cast<std::size_t>(count), world);
    for (World& c : copies) c.set_threads(1);
  };
  // read < 0: no halo.
  auto side_by_side = [&](bool meet, long long read) {
    fresh_copies();
    std::exception_ptr failed;
    std::vector<double> sums(static_cast<std::size_t>(count));
    const auto start = Clock::now();
#pragma omp parallel num_threads(count)
    {
      // A smaller team than asked (an OpenMP limit): each member takes every team-th copy.
      const int team = omp_get_num_threads(), me = omp_get_thread_num();
      double sum = 0;
      for (long long s = 0; s < steps; ++s) {
        try {
          for (int c = me; c < count; c += team) copies[c].step();
        } catch (...) {
#pragma omp critical
          if (!failed) failed = std::current_exception();
        }
        if (meet) {
#pragma omp barrier
        }
        if (read >= 0) {
          for (int c = me; c < count; c += team) sum += read_halo(copies[(c + 1) % count].particles(), read);
#pragma omp barrier
        }
      }
      // Stored where the caller could read it, so the reads are made (a volatile local was not
      // enough: GCC 12 dropped the reads).
      sums[static_cast<std::size_t>(me)] = sum;
    }
    if (failed) std::rethrow_exception(failed);
    return seconds_since(start);
  };
  Ceiling turn;
  turn.steps = steps;
  fresh_copies();
  const auto start = Clock::now();
  for (World& c : copies) c.advance(steps);
  turn.alone = seconds_since(start);
  turn.apart = side_by_side(false, -1);
  turn.lockstep = side_by_side(true, -1);
  if (halo >= 0) turn.halo = side_by_side(true, halo);
  return turn;
}

// `name`_reads and `name``unit`_min, _median and _max of `values`, if any were read.
void print_spread(const char* name, const char* unit, const char* format, std::vector<double> values) {
  if (values.empty()) return;
  std::sort(values.begin(), values.end());
  const std::size_t k = values.size();
  const auto line = [&](const char* what, double v) {
    std::printf("%s%s_%s: ", name, unit, what);
    std::printf(format, v);
    std::printf("\n");
  };
  std::printf("%s_reads: %zu\n", name, k);
  line("min", values.front());
  line("median", (values[(k - 1) / 2] + values[k / 2]) / 2);
  line("max", values.back());
}

}  // namespace

int bench_command(const BenchOptions& o) {
  const std::string source = o.scene_path.empty() ? "<embedded bench scene>" : o.scene_path;
  SceneDef scene = load_scene(o.scene_path, o.overrides, io::embedded_bench_scene(), source);
  const SceneSetup setup = derive_setup(scene, source);
  PreparedWorld prepared = prepare(scene, setup, std::max(o.threads, omp_get_num_procs()),
                                   o.cache_dir.empty() ? default_cache_dir() : o.cache_dir, true, false);
  World& world = prepared.world;
  world.set_threads(o.threads);
  world.set_track_energy(o.ledger);
  const long long warmup = o.warmup_steps >= 0 ? o.warmup_steps
                                              : static_cast<long long>(std::ceil(5.0 * setup.unit_time / setup.dt));
  world.advance(warmup);
  if (o.frames > 0) return bench_frames(world, scene, setup, o.picture, o.frames, 20);
  const double t_star_start = world.time() / setup.unit_time;
  // Each thread count's steps, time and profile. With --against-threads the two counts (and
  // with --ceiling the copies) take turns of turn_steps steps until each has run o.steps, so
  // all sample the same stretch of the flow and the same minutes of the host (the physics is
  // the same bits at any count).
  struct Tally {
    int threads = 1;
    StepSettings::Ahead ahead = StepSettings::Ahead::when_safe;
    long long steps = 0;
    double seconds = 0;
    StepProfile profile;
  };
  Tally mine, other;
  mine.threads = o.threads;
  mine.ahead = kAheadNames.at(o.ahead);
  other.threads = o.against_threads;
  auto run_turn = [&](Tally& tally, long long steps) {
    world.set_threads(tally.threads);
    world.set_ahead(tally.ahead);
    const StepProfile before = world.profile();
    const auto t0 = Clock::now();
    world.advance(steps);
    tally.seconds += seconds_since(t0);
    tally.steps += steps;
    const StepProfile& after = world.profile();
    tally.profile.contact_forces += after.contact_forces - before.contact_forces;
    tally.profile.integrate += after.integrate - before.integrate;
    tally.profile.rebuild += after.rebuild - before.rebuild;
    tally.profile.rebuilds += after.rebuilds - before.rebuilds;
    tally.profile.steps_ahead += after.steps_ahead - before.steps_ahead;
    tally.profile.steps_dropped += after.steps_dropped - before.steps_dropped;
  };
  Ceiling ceiling;
  const bool turns = o.against_threads > 0 || o.ceiling;
  // The host's state before every turn and after the last, at two threads or more (NaN where
  // not read, and then not kept): the line round trip (on the 2-vCPU VMs of issue 11 it swings
  // between ~100 and ~600 ns as the host moves the vCPUs; a two-thread step moves a hundred-odd
  // lines between its threads each pass) and what two threads' arithmetic gains over one's
  // (about 1 while the host keeps both on one core; docs/performance.md).
  struct HostState {
    double pair_speedup, trip_ns;
  };
  const double nan = std::nan("");
  const bool read_host = std::max(o.threads, o.against_threads) >= 2;
  // About a millisecond a loop on issue 11's hosts: long against the clock's resolution and a
  // thread's wake-up, short against a turn (six loops a read, outside every timing).
  constexpr long kArithmeticRounds = 400000;
  std::vector<double> trips_ns, pair_speedups;
  auto read_host_state = [&] {
    // The arithmetic first: the round trip's region leaves the other thread spinning.
    const HostState h{read_host ? arithmetic_pair_speedup(kArithmeticRounds) : nan,
                      read_host ? line_round_trip_ns(2000) : nan};
    if (!std::isnan(h.trip_ns)) trips_ns.push_back(h.trip_ns);
    if (!std::isnan(h.pair_speedup)) pair_speedups.push_back(h.pair_speedup);
    return h;
  };
  // --turn-log: a row per turn, so the speed-up can be read against the host's state turn by turn
  // and, with --ceiling, against what the host gave copies that share nothing in that turn.
  const bool log_turns = !o.turn_log.empty();
  std::ostringstream turn_log;
  if (log_turns)
    turn_log << "turn,steps,threads,seconds,against_threads,against_seconds,speedup,"
                "line_round_trip_ns_before,line_round_trip_ns_after,"
                "ceiling_alone_seconds,ceiling_lockstep_seconds,ceiling_lockstep_speedup,"
                "arithmetic_pair_speedup_before,arithmetic_pair_speedup_after\n";
  auto csv = [](const char* format, double v) {
    char text[32] = "";
    if (!std::isnan(v)) std::snprintf(text, sizeof text, format, v);
    return std::string(text);
  };
  HostState before = read_host_state();
  for (long long k = 0; mine.steps < o.steps; ++k) {
    const long long turn = turns ? std::min(o.turn_steps, o.steps - mine.steps) : o.steps;
    const Ceiling copies = o.ceiling ? ceiling_turn(world, o.threads, turn, o.ceiling_halo) : Ceiling{};
    ceiling += copies;
    const double mine_before = mine.seconds, other_before = other.seconds;
    run_turn(mine, turn);
    if (o.against_threads > 0) run_turn(other, turn);
    const HostState after = read_host_state();
    const double t_mine = mine.seconds - mine_before, t_other = other.seconds - other_before;
    if (log_turns)
      turn_log << k << ',' << turn << ',' << mine.threads << ',' << csv("%.9g", t_mine) << ','
               << other.threads << ',' << csv("%.9g", t_other) << ',' << csv("%.4f", t_other / t_mine) << ','
               << csv("%.0f", before.trip_ns) << ',' << csv("%.0f", after.trip_ns) << ','
               << csv("%.9g", o.ceiling ? copies.alone : nan) << ','
               << csv("%.9g", o.ceiling ? copies.lockstep : nan) << ','
               << csv("%.4f", o.ceiling ? copies.alone / copies.lockstep : nan) << ','
               << csv("%.3f", before.pair_speedup) << ',' << csv("%.3f", after.pair_speedup) << '\n';
    before = after;
  }
  if (log_turns) io::write_file_atomically(o.turn_log, turn_log.str());
  const double n = static_cast<double>(world.particles().size());
  const double secs = mine.seconds;
  std::printf("scene: %s\n", scene.name.c_str());
  std::printf("discs: %.0f\n", n);
  std::printf("threads: %d\n", o.threads);
  std::printf("ahead: %s\n", o.ahead.c_str());
  std::printf("ledger: %s\n", o.ledger ? "on" : "off");
  std::printf("t_star_start: %.3f\n", t_star_start);
  std::printf("steps: %lld\n", o.steps);
  std::printf("seconds: %.4f\n", secs);
  std::printf("pairs_listed_per_disc: %.3f\n", world.pairs().size() / n);
  std::printf("rebuilds: %lld\n", static_cast<long long>(mine.profile.rebuilds));
  std::printf("share_contact_forces: %.3f\n", mine.profile.contact_forces / secs);
  std::printf("share_integrate: %.3f\n", mine.profile.integrate / secs);
  std::printf("share_rebuild: %.3f\n", mine.profile.rebuild / secs);
  std::printf("steps_ahead: %lld\n", static_cast<long long>(mine.profile.steps_ahead));
  std::printf("steps_dropped: %lld\n", static_cast<long long>(mine.profile.steps_dropped));
  if (o.ledger) {  // what the ledger booked from the warm-up's start on: it did run
    const Dissipation& lost = world.dissipation();
    std::printf("ledger_dissipated_joules: %.6g\n", lost.normal + lost.friction + lost.rolling);
  }
  std::printf("particle_steps_per_second: %.0f\n", n * o.steps / secs);
  if (o.against_threads > 0) {
    std::printf("turn_steps: %lld\n", o.turn_steps);
    std::printf("against_threads: %d\n", other.threads);
    std::printf("against_steps: %lld\n", other.steps);
    std::printf("against_seconds: %.4f\n", other.seconds);
    std::printf("against_particle_steps_per_second: %.0f\n", n * other.steps / other.seconds);
    std::printf("against_rebuilds: %lld\n", static_cast<long long>(other.profile.rebuilds));
    std::printf("against_share_contact_forces: %.3f\n", other.profile.contact_forces / other.seconds);
    std::printf("against_share_integrate: %.3f\n", other.profile.integrate / other.seconds);
    std::printf("against_share_rebuild: %.3f\n", other.profile.rebuild / other.seconds);
    // The rate at --threads over the rate at --against-threads.
    std::printf("speedup: %.3f\n", other.seconds / secs);
  }
  if (o.ceiling) {
    std::printf("ceiling_copies: %d\n", o.threads);
    std::printf("ceiling_steps: %lld\n", ceiling.steps);
    std::printf("ceiling_alone_seconds: %.4f\n", ceiling.alone);
    std::printf("ceiling_apart_seconds: %.4f\n", ceiling.apart);
    std::printf("ceiling_lockstep_seconds: %.4f\n", ceiling.lockstep);
    // The copies' steps one after another over side by side: at most `ceiling_copies`.
    std::printf("ceiling_apart_speedup: %.3f\n", ceiling.alone / ceiling.apart);
    std::printf("ceiling_lockstep_speedup: %.3f\n", ceiling.alone / ceiling.lockstep);
    if (o.ceiling_halo >= 0) {
      std::printf("ceiling_halo_discs: %zu\n", halo_discs(world.particles().size(), o.ceiling_halo));
      std::printf("ceiling_halo_seconds: %.4f\n", ceiling.halo);
      std::printf("ceiling_halo_speedup: %.3f\n", ceiling.alone / ceiling.halo);
    }
  }
  print_spread("line_round_trip", "_ns", "%.0f", trips_ns);
  print_spread("arithmetic_pair_speedup", "", "%.3f", pair_speedups);
  return 0;
}

}  // namespace runout::app
