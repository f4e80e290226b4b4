// A pass of forces and motion over the threads' blocks of discs, and the verdict on each
// (World::forces_and_motion, world.hpp): one OpenMP region for as many steps as the lists and
// the blocks allow, the crossing rows handed to the later threads (handoff.hpp), the next
// step's forces started before the verdict where that is safe (docs/internals.md).
#include <omp.h>

#include "runout/world.hpp"
#include "step_phases.hpp"

namespace runout {

namespace {

// Waits until `flag` reaches `pass` (an earlier thread may already be a pass further).
void wait_for(const std::atomic<std::int64_t>& flag, std::int64_t pass) {
  spin_until([&] { return flag.load(std::memory_order_acquire) >= pass; });
}

}  // namespace

World::Verdict World::judge(const PassSums& sums, const phases::Motion& motion, bool watched,
                            const ListDrift::Partial& blocks, int slot) const {
  // The whole flow's bound (the spread of all displacements for pairs, the largest one for
  // walls) is cheap; once it is spent, the groups' bound (ListDrift) often is not. It assumes
  // fixed radii, so not while discs grow.
  Verdict v;
  v.list_drift = std::max(motion.spread(), motion.largest());
  v.spent = v.list_drift + 2 * max_growth_ >= settings_.skin && max_growth_ == 0;
  if (v.spent && watched) v.list_drift = drift_.bound(motion.spread(), blocks, slot);
  v.closing = v.spent && !watched;
  v.go_on = !v.closing && !beyond_guard(sums.worst) && motion.finite && v.list_drift + 2 * max_growth_ < settings_.skin;
  return v;
}

std::int64_t World::forces_and_motion(bool forces, double kick, double drift, std::int64_t passes) {
  const phases::StepContext ctx{settings_, segments_, laws_};
  const auto n = static_cast<std::int64_t>(particles_.size());
  const bool ledger = forces && settings_.track_energy;
  if (ledger)
    for (auto& blocks : ledger_blocks_) blocks.size_for(pairs_, wall_contacts_);
  const int T = settings_.threads;
  constexpr int S = ListDrift::kSlots;  // passes in turn (outcomes, ledger blocks, drift boxes)
  // With several threads, pass k of the call reads the history from buffer k % 2 and writes
  // it to the other; one thread computes nothing ahead and keeps one buffer (a second one
  // cost it ~1.5 % in cache misses).
  // A pass writes every contact's history, so the other buffer is never cleared.
  const bool turns = T > 1 && forces;
  if (turns) {
    pair_history_next_.resize(pairs_.history.size());
    wall_history_next_.resize(wall_contacts_.history.size());
  }
  double* const pair_history[2] = {pairs_.history.data(), turns ? pair_history_next_.data() : pairs_.history.data()};
  double* const wall_history[2] = {wall_contacts_.history.data(), turns ? wall_history_next_.data() : wall_contacts_.history.data()};
  const phases::HistoryTurn turn[2] = {{pair_history[0], pair_history[1], wall_history[0], wall_history[1]},
                                       {pair_history[1], pair_history[0], wall_history[1], wall_history[0]}};
  auto contacts = [&](const ContactRange& range, std::int64_t pass, std::int64_t k) {
    return phases::contact_forces(ctx, particles_, pairs_, wall_contacts_, range,
                                  ledger_blocks_[pass % S], turn[k & 1]);
  };
  // Where block t's accelerations go: the discs' arrays with one thread, or where velocity
  // Verlet keeps them for its next call; else the block's own pages from its first disc.
  const bool keep_accelerations = T == 1 || settings_.integrator == IntegratorKind::velocity_verlet;
  auto accelerations_of = [&](int t) {
    if (keep_accelerations)
      return phases::Accelerations{particles_.ax.data(), particles_.ay.data(), particles_.alpha.data(), 0};
    BlockAccelerations& own = block_accelerations_[t];
    return phases::Accelerations{own.x.data(), own.y.data(), own.angular.data(), own.first};
  };
  auto motion_of = [&](int t, std::int64_t lo, std::int64_t hi) {
    const phases::Accelerations a = accelerations_of(t);
    return phases::advance(ctx, particles_, pairs_, wall_contacts_, runs_, x_at_rebuild_,
                           y_at_rebuild_, lo, hi, forces, kick, drift, a);
  };
  // Each block's outcome on a cache line of its own, by pass in turn (a thread may write a
  // later pass's while another still reads this one's), a handful on the stack: arrays of
  // kMaxThreads (20 KB set every pass) pushed the step's own data out of L1.
  struct alignas(64) Outcome {
    PassSums sums;
    phases::Motion motion;
    ListDrift::Partial drift;
  };
  constexpr int kOnStack = 8;
  Outcome on_stack[S * kOnStack];
  std::vector<Outcome> on_heap(T > kOnStack ? S * static_cast<std::size_t>(T) : 0);
  Outcome* const out = T > kOnStack ? on_heap.data() : on_stack;
  // With the ledger, block t's partial of each pass (the pass's losses up to its last contact),
  // by pass in turn like the outcomes but on lines of their own: a pass without the ledger
  // reads the outcomes' lines as before.
  struct alignas(64) Carried {
    LedgerBlocks::Partial ledger;
  };
  Carried carried_on_stack[S * kOnStack];
  std::vector<Carried> carried_on_heap(T > kOnStack ? S * static_cast<std::size_t>(T) : 0);
  Carried* const carried = T > kOnStack ? carried_on_heap.data() : carried_on_stack;
  // What thread 0 keeps of each pass (the last outcome, the region's totals, the verdicts) sits
  // on cache lines of its own and goes back into the World once the region ends. Written
  // every pass into World members and this frame's locals, it shared lines with what the
  // other threads read every pass (the discs' array pointers, the closures below,
  // max_growth_): such a line may cross the cores twice a pass (docs/performance_log.md, issue 11
  // thirtieth session).
  struct alignas(64) Kept {
    PassSums last_sums;
    phases::Motion last_motion;
    std::int64_t done = 0;
    double forces_seconds = 0;  // thread 0's
    Verdict recent[2];
    std::int64_t recent_count = 0;
    double peak_impact = 0;
    std::int64_t ahead = 0, dropped = 0;
  } kept;
  // The ledger, kept by the last thread: its partial of a pass is the pass's total.
  struct alignas(64) {
    Dissipation ledger;
  } last_kept;
  kept.recent[0] = recent_[0];
  kept.recent[1] = recent_[1];
  kept.recent_count = recent_count_;
  kept.peak_impact = peak_impact_overlap_;
  last_kept.ledger = ledger_;
  const auto t0 = Clock::now();
  // What thread 0 keeps of each pass, once every block's outcome is out.
  auto settle = [&](const Verdict& v, const PassSums& sums, const phases::Motion& m) {
    if (forces) kept.peak_impact = std::max(kept.peak_impact, sums.worst * guard_radius_scale_);
    kept.recent[0] = kept.recent[1];
    kept.recent[1] = v;
    ++kept.recent_count;
    kept.last_sums = sums;
    kept.last_motion = m;
    ++kept.done;
  };
  auto book = [&](const LedgerBlocks::Partial& pass_total) {
    const PassSums total = pass_total.total();
    last_kept.ledger.normal += total.loss_normal;
    last_kept.ledger.friction += total.loss_friction;
    last_kept.ledger.rolling += total.loss_rolling;
  };
  std::int64_t taken = 0;  // flag values used: the passes done, and one computed ahead and dropped
  if (T == 1) {
    handoff_.release(pairs_, runs_, lists_version_);
    const std::int64_t pass = passes_ + 1;
    const ContactRange all{0, static_cast<std::int64_t>(pairs_.size()), 0,
                           static_cast<std::int64_t>(wall_contacts_.size())};
    PassSums sums;
    if (forces) sums = contacts(all, pass, 0);
    kept.forces_seconds = seconds_since(t0);
    const phases::Motion motion = motion_of(0, 0, n);
    if (ledger) book(ledger_blocks_[pass % S].carry({}, all));
    settle(judge(sums, motion, false, {}, static_cast<int>(pass % S)), sums, motion);
    taken = 1;
  } else {
    // Thread t takes the discs of block t for the whole step: the contacts of their rows, then
    // their sums, kick and drift. A disc's sum reads only rows of its own or earlier blocks
    // (i < j), so block t waits for nothing later; it waits for earlier threads only where
    // their rows reach its discs (the handoff), and each thread computes those rows first.
    blocks_.prepare(pairs_, wall_contacts_, runs_, n, T);
    const std::vector<std::int64_t>& b = blocks_.bounds();
    if (!keep_accelerations) {
      block_accelerations_.resize(static_cast<std::size_t>(T));
      for (int t = 0; t < T; ++t) {
        const auto size = static_cast<std::size_t>(b[t + 1] - b[t]);
        BlockAccelerations& own = block_accelerations_[t];
        own.first = b[t];
        if (own.x.size() < size) {
          own.x.resize(size);
          own.y.resize(size);
          own.angular.resize(size);
        }
      }
    }
    const ContactGrain grain = contact_grain(settings_.track_energy);
    if (!handoff_.current(lists_version_, blocks_.version(), grain, T))
      handoff_.find(pairs_, wall_contacts_, runs_, b, lists_version_, blocks_.version(), grain);
    passes = std::min<std::int64_t>(passes, blocks_.steps_before_turn());
    const std::int64_t first_pass = passes_ + 1;
    // Once the whole flow's bound is spent, each thread measures its own groups' displacements
    // for the groups' bound (ListDrift; a block is whole groups).
    static_assert(DiscRuns::kWindow % ListDrift::kGroup == 0);
    const bool groups_found = drift_.found();
    if (groups_found) drift_.split(b);
    // In a region's first step each thread's time is counted from the region's start, so the
    // balancer also weighs how late a thread starts (waking the team costs the later threads a
    // few microseconds): it then evens out when the threads finish, not only how long they
    // compute. Later steps count from each thread's own start.
    const auto region_start = Clock::now();
    // Thread t's contacts of a pass: first the rows that reach later blocks, then its flag,
    // then the rest. Those rows read the discs of later blocks as moved in the pass before.
    auto wait_reached = [&](int t, std::int64_t pass) {
      for (int u = t + 1; u < T; ++u)
        if (handoff_.first_free[u] > b[u]) wait_for(ready_.flag[u].moved, pass - 1);
    };
    auto forces_of = [&](int t, std::int64_t pass, std::int64_t k) {
      Outcome& mine = out[(pass % S) * T + t];
      const ContactRange& r = handoff_.range[t];
      const std::int64_t split = handoff_.boundary_pair[t];
      if (forces) {
        mine.sums = contacts({split, r.pair_hi, r.wall_lo, r.wall_hi}, pass, k);
        handoff_.publish(t, pairs_);
      }
      ready_.flag[t].pass.store(pass, std::memory_order_release);
      if (forces) mine.sums.worst = std::max(mine.sums.worst, contacts({r.pair_lo, split, 0, 0}, pass, k).worst);
    };
    // Thread t's sums, kick and drift: first (once the earlier threads' boundary pairs are
    // done) the discs their contacts reach, then the rest. The reached discs' lines, which the
    // earlier thread read, then come back to this core while the rest move, not while the
    // pass's end waits for them (docs/performance_log.md, twenty-first session). The earlier
    // thread's crossing pushes are nearly always ready by now.
    auto wait_earlier = [&](int t, std::int64_t pass) {
      if (forces && t > 0 && ready_.flag[t - 1].pass.load(std::memory_order_acquire) == pass)
        handoff_.prefetch(t - 1, pairs_);
      for (int u = 0; u < t; ++u) wait_for(ready_.flag[u].pass, pass);
    };
    // The ledger's partial of a pass, carried on from block t - 1's over block t's contacts
    // (LedgerBlocks::Partial). Block 0 carries before its `done`, so the next block's wait for
    // that flag covers it; later blocks carry at their verdict. The last block's partial is the
    // pass's total: whoever carries it books the pass, once.
    auto carry = [&](int t, std::int64_t pass) {
      const int slot = static_cast<int>(pass % S);
      LedgerBlocks::Partial from;
      if (t > 0) {
        wait_for(ready_.flag[t - 1].carried, pass);
        from = carried[slot * T + t - 1].ledger;
      }
      carried[slot * T + t].ledger = ledger_blocks_[slot].carry(from, handoff_.range[t]);
      ready_.flag[t].carried.store(pass, std::memory_order_release);
      if (t == T - 1) book(carried[slot * T + t].ledger);
    };
    auto move_block = [&](int t, std::int64_t pass, bool watched) {
      Outcome& mine = out[(pass % S) * T + t];
      const std::int64_t mid = handoff_.first_free[t];
      const phases::Motion reached = motion_of(t, b[t], mid);
      ready_.flag[t].moved.store(pass, std::memory_order_release);
      mine.motion = phases::Motion::merge(reached, motion_of(t, mid, b[t + 1]));
      if (watched) mine.drift = drift_.measure(particles_.x, particles_.y, x_at_rebuild_, y_at_rebuild_, t, static_cast<int>(pass % S));
      if (ledger && t == 0) carry(0, pass);
      ready_.flag[t].done.store(pass, std::memory_order_release);
    };
    // Every block's outcome of the pass, merged in block order: each thread judges it alike.
    auto verdict_on = [&](int me, std::int64_t pass, bool watched) {
      const int slot = static_cast<int>(pass % S);
      if (ledger && me > 0) carry(me, pass);
      PassSums sums;
      phases::Motion motion;
      ListDrift::Partial blocks;
      for (int t = 0; t < T; ++t) {
        wait_for(ready_.flag[t].done, pass);
        const Outcome& o = out[slot * T + t];
        sums.worst = std::max(sums.worst, o.sums.worst);
        motion = t == 0 ? o.motion : phases::Motion::merge(motion, o.motion);
        blocks = ListDrift::Partial::merge(blocks, o.drift);
      }
      const Verdict v = judge(sums, motion, watched, blocks, slot);
      if (me == 0) settle(v, sums, motion);
      return v;
    };
    // Whether the next pass's forces may start before this pass's verdict: only where the
    // bound that ends the region (list_drift: the whole flow's, or once spent the groups'),
    // grown three times as much as over the last pass, still holds. A pass computed ahead
    // and dropped costs its forces (about half a two-thread step on the bench pile, against
    // the ~1 us the verdict's wait took); no result depends on it.
    const double skin = settings_.skin - 2 * max_growth_;
    auto ahead = [&](const Verdict& v, const Verdict& before) {
      if (settings_.ahead != StepSettings::Ahead::when_safe) return settings_.ahead == StepSettings::Ahead::always;
      const double grown = std::max(0.0, v.list_drift - before.list_drift);
      return v.spent == before.spent && v.list_drift + 3 * grown < skin;
    };
#pragma omp parallel num_threads(T)
    {
      const int team = omp_get_num_threads(), me = omp_get_thread_num();
      bool watched = watch_groups_ && groups_found;
      if (team == T) {
        // The forces of pass k + 1 overlap the wait for pass k's verdict where it is safe to
        // drop them (the history's two buffers; `ahead`); the region's last pass is judged at
        // once.
        // The last two verdicts, since the lists were built: a region goes on from where the
        // one before it ended (a turn of the blocks, a reordering, the caller's steps). Thread 0
        // writes recent_ only after the region.
        Verdict v = recent_[1], before = recent_[0];
        std::int64_t verdicts = recent_count_;
        bool pending = false;
        for (std::int64_t k = 0; k < passes; ++k) {
          const std::int64_t pass = first_pass + k;
          if (k > 0) wait_reached(me, pass);
          const auto start = Clock::now();
          const auto counted_from = k == 0 ? region_start : start;
          forces_of(me, pass, k);
          if (me == 0) kept.forces_seconds += seconds_since(start);
          const double busy = seconds_since(counted_from);
          if (pending) {
            pending = false;
            before = v;
            v = verdict_on(me, pass - 1, watched);
            ++verdicts;
            if (!v.go_on) {  // this pass's forces are dropped
              if (me == 0) ++kept.dropped;
              break;
            }
            watched = v.spent && groups_found;
          }
          wait_earlier(me, pass);
          const auto resumed = Clock::now();
          move_block(me, pass, watched);
          blocks_.record(me, busy + seconds_since(resumed));
          if (k + 1 < passes && verdicts >= 2 && ahead(v, before)) {
            if (me == 0) ++kept.ahead;
            pending = true;
            continue;
          }
          before = v;
          v = verdict_on(me, pass, watched);
          ++verdicts;
          if (!v.go_on) break;
          watched = v.spent && groups_found;
        }
      } else if (me == 0) {
        // A smaller team than asked (an OpenMP limit) cannot hand off between its own blocks
        // in this order: one thread then takes every block in turn, each pass judged at once.
        for (std::int64_t k = 0; k < passes; ++k) {
          const std::int64_t pass = first_pass + k;
          for (int t = 0; t < T; ++t) forces_of(t, pass, k);
          for (int t = 0; t < T; ++t) {
            wait_earlier(t, pass);
            move_block(t, pass, watched);
          }
          if (ledger)
            for (int t = 1; t < T; ++t) carry(t, pass);
          const Verdict v = verdict_on(me, pass, watched);
          if (!v.go_on) break;
          watched = v.spent && groups_found;
        }
      }
    }
    // A pass computed ahead and dropped used its flag values: they are not used again.
    taken = kept.done + 1;
    for (std::int64_t s = 0; s < kept.done; ++s) blocks_.after_step(pairs_, wall_contacts_, runs_);
  }
  recent_[0] = kept.recent[0];
  recent_[1] = kept.recent[1];
  recent_count_ = kept.recent_count;
  peak_impact_overlap_ = kept.peak_impact;
  ledger_ = last_kept.ledger;
  profile_.steps_ahead += kept.ahead;
  profile_.steps_dropped += kept.dropped;
  const std::int64_t done = kept.done;
  passes_ += taken;
  if (turns && done % 2 == 1) {
    std::swap(pairs_.history, pair_history_next_);
    std::swap(wall_contacts_.history, wall_history_next_);
  }
  const Verdict& last = recent_[1];
  list_drift_ = last.closing ? drift_.closing(particles_.x, particles_.y, x_at_rebuild_, y_at_rebuild_,
                                              search_.wall_margin(), kept.last_motion.spread())
                             : last.list_drift;
  watch_groups_ = last.spent;
  finite_ = kept.last_motion.finite;
  profile_.contact_forces += kept.forces_seconds;
  profile_.integrate += seconds_since(t0) - kept.forces_seconds;
  if (forces) check_overlap(kept.last_sums.worst);
  return done;
}

}  // namespace runout
