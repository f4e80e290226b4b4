#include "runout/load_balance.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace runout {

namespace {
constexpr std::int64_t kContactCost = 6;  // slots a contact's force costs (Work::step)
}  // namespace

void LoadBalance::estimate(const PairContacts& pairs, const WallContacts& walls, const DiscRuns& runs) {
  constexpr std::int64_t W = DiscRuns::kWindow, L = DiscRuns::kSlice, S = W / L;
  const std::int64_t n = n_, windows = (n + W - 1) / W;
  const auto slices = static_cast<std::int64_t>(runs.slices());
  const auto rows = static_cast<std::size_t>(n) + 1;
  // Before the first list (or without one) every disc counts the same.
  const bool lists = slices == (n + L - 1) / L && pairs.row_start.size() == rows && walls.row_start.size() == rows;
  work_before_.resize(static_cast<std::size_t>(windows) + 1);
  for (std::int64_t w = 0; w <= windows; ++w) {
    const std::int64_t disc = std::min(n, w * W), g = std::min(slices, w * S);
    const std::int64_t contacts = lists ? pairs.row_start[disc] + walls.row_start[disc] : 0;
    const std::int64_t sums = lists ? runs.slice_start[g] + L * g : 0;
    work_before_[w] = !lists                  ? disc
                      : work_ == Work::contacts ? contacts
                      : work_ == Work::sums     ? sums
                                                : kContactCost * contacts + sums;
  }
}

void LoadBalance::prepare(const PairContacts& pairs, const WallContacts& walls,
                          const DiscRuns& runs, std::int64_t n, int threads) {
  if (n == n_ && threads == threads_) return;
  n_ = n;
  threads_ = threads;
  steps_ = 0;
  busy_.assign(static_cast<std::size_t>(threads), Busy{});
  speed_.assign(static_cast<std::size_t>(threads), 1.0);
  estimate(pairs, walls, runs);
  place();
}

void LoadBalance::place() {
  const std::vector<std::int64_t> before = bounds_;
  const double total_speed = std::accumulate(speed_.begin(), speed_.end(), 0.0);
  const double total_work = static_cast<double>(work_before_.back());
  bounds_.assign(static_cast<std::size_t>(threads_) + 1, n_);
  bounds_[0] = 0;
  double speed_before = 0;
  for (int t = 1; t < threads_; ++t) {
    speed_before += speed_[t - 1];
    const double goal = total_work * speed_before / total_speed;
    // The first window whose work before it reaches the goal.
    const auto w = std::lower_bound(work_before_.begin(), work_before_.end(), goal,
                                    [](std::int64_t a, double g) { return static_cast<double>(a) < g; }) -
                   work_before_.begin();
    bounds_[t] = std::min(n_, DiscRuns::kWindow * static_cast<std::int64_t>(w));
  }
  // Moving an end costs more than the window it gains: the hand-off is found again (~11 us)
  // and the next pass is 3-6 us slower while the moved discs' lines change cores, against a
  // window's share of a step's work (32 of the bench pile's 3,500 discs, ~0.7 us of a ~75 us
  // step; docs/performance_log.md, eighteenth session). The measured speeds jitter by about a
  // window from one period to the next, so ends that would each move by a window at most stay.
  const bool jitter = before.size() == bounds_.size() && before.back() == bounds_.back() &&
                      std::equal(before.begin(), before.end(), bounds_.begin(), [](std::int64_t a, std::int64_t b) {
                        return std::abs(a - b) <= DiscRuns::kWindow;
                      });
  if (jitter) bounds_ = before;
  if (bounds_ != before) ++version_;
}

void LoadBalance::after_step(const PairContacts& pairs, const WallContacts& walls, const DiscRuns& runs) {
  if (threads_ < 2 || ++steps_ < kPeriod) return;
  steps_ = 0;
  // The work each block held, by the lists now (they change rarely within a period).
  estimate(pairs, walls, runs);
  auto work_at = [&](std::int64_t disc) {
    return static_cast<double>(work_before_[static_cast<std::size_t>((disc + DiscRuns::kWindow - 1) / DiscRuns::kWindow)]);
  };
  std::vector<double> measured(static_cast<std::size_t>(threads_), 0.0);
  double sum = 0;
  for (int t = 0; t < threads_; ++t) {
    const double work = work_at(bounds_[t + 1]) - work_at(bounds_[t]);
    const double busy = busy_[static_cast<std::size_t>(t)].seconds;
    measured[t] = work > 0 && busy > 0 ? work / busy : 0.0;
    sum += measured[t];
  }
  const bool all_measured = std::all_of(measured.begin(), measured.end(), [](double m) { return m > 0; });
  std::fill(busy_.begin(), busy_.end(), Busy{});
  if (!all_measured) return;  // an empty block tells nothing of its thread's speed
  // Speeds relative to their mean, halfway from the last estimate to this period's.
  const double mean = sum / threads_;
  for (int t = 0; t < threads_; ++t) speed_[t] = 0.5 * speed_[t] + 0.5 * (measured[t] / mean);
  place();
}

}  // namespace runout
