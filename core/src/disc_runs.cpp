// The runs of the disc sums (DiscRuns, neighbor_list.hpp), laid out at each rebuild by the
// threads of NeighborSearch::rebuild's team.
#include <algorithm>
#include <numeric>

#include "runout/neighbor_list.hpp"

namespace runout {

// Each disc's run: its row, then the pairs where it is j (in pair order, so by i). Called by
// every thread of the rebuild's team, thread t of T with the rows [lo, hi). The layout is a
// function of the lists alone: each thread counts the incoming pairs of its own rows, so disc
// k's incoming pairs from thread t's rows (smaller i) follow those from the threads before
// it, which is pair order.
void NeighborSearch::runs_of(const PairContacts& pairs, DiscRuns& runs, int t, int T,
                             std::int32_t lo, std::int32_t hi) {
  const auto n = static_cast<std::int32_t>(pairs.row_start.size() - 1);
  const auto on_j = static_cast<std::int32_t>(pairs.j_offset());
  const auto zero = static_cast<std::int32_t>(pairs.zero_push());
  constexpr std::int32_t L = DiscRuns::kSlice, W = DiscRuns::kWindow;
  const std::int32_t* row_start = pairs.row_start.data();
  auto& from_here = thread_count_[t];  // its rows' pairs per j, then its cursors in j's runs
  from_here.assign(static_cast<size_t>(n), 0);
  for (std::int32_t q = row_start[lo]; q < row_start[hi]; ++q) ++from_here[pairs.j[q]];
#pragma omp barrier
  for (std::int32_t k = lo; k < hi; ++k) {
    std::int32_t at = row_start[k + 1] - row_start[k];
    for (int u = 0; u < T; ++u) {
      const std::int32_t c = thread_count_[u][k];
      thread_count_[u][k] = at;
      at += c;
    }
    run_length_[k] = at;
  }
  // Lanes: each window's discs by run length, longest first (ties by index); each slice's
  // length is its longest lane's.
  // A window (and a slice) is the thread's whose block holds its first disc.
  auto first_from = [](std::int32_t k, std::int32_t size) { return (k + size - 1) / size; };
  std::vector<std::int32_t> by_length;  // a counting sort's buckets, longest first
#pragma omp barrier
  for (std::int32_t w = first_from(lo, W); w < first_from(hi, W); ++w) {
    const std::int32_t w0 = w * W, count = std::min(W, n - w0);
    std::int32_t* lanes = runs.lane_disc.data() + w0;
    std::int32_t longest = 0;
    for (std::int32_t k = w0; k < w0 + count; ++k) longest = std::max(longest, run_length_[k]);
    by_length.assign(static_cast<std::size_t>(longest) + 2, 0);
    for (std::int32_t k = w0; k < w0 + count; ++k) ++by_length[longest - run_length_[k] + 1];
    std::partial_sum(by_length.begin(), by_length.end(), by_length.begin());
    for (std::int32_t k = w0; k < w0 + count; ++k) lanes[by_length[longest - run_length_[k]]++] = k;
    for (std::int32_t m = 0; m < count; ++m) lane_of_[lanes[m]] = w0 + m;
    for (std::int32_t g = w0 / L; g < (w0 + count + L - 1) / L; ++g)
      runs.slice_start[g + 1] = L * run_length_[runs.lane_disc[g * L]];  // lane 0 is longest
  }
#pragma omp barrier
#pragma omp single
  {
    std::partial_sum(runs.slice_start.begin(), runs.slice_start.end(), runs.slice_start.begin());
    runs.source.resize(static_cast<size_t>(runs.slice_start.back()));
  }
  auto slot = [&](std::int32_t k, std::int32_t s) {
    const std::int32_t lane = lane_of_[k];
    return runs.slice_start[lane / L] + L * s + lane % L;
  };
  // Each lane's own row, then padding past its run, which reads the push that is always
  // zero (the kernel never writes it); the incoming pairs are written by the threads of
  // their rows.
  for (std::int32_t g = first_from(lo, L); g < first_from(hi, L); ++g) {
    const std::int32_t longest = (runs.slice_start[g + 1] - runs.slice_start[g]) / L;
    for (std::int32_t l = 0; l < L; ++l) {
      const std::int32_t k = runs.lane_disc[g * L + l];
      std::int32_t* lane = runs.source.data() + runs.slice_start[g] + l;
      const std::int32_t row = k >= 0 ? row_start[k + 1] - row_start[k] : 0;
      const std::int32_t end = k >= 0 ? run_length_[k] : 0;
      for (std::int32_t s = 0; s < row; ++s) lane[L * s] = row_start[k] + s;
      for (std::int32_t s = end; s < longest; ++s) lane[L * s] = zero;
    }
  }
  for (std::int32_t q = row_start[lo]; q < row_start[hi]; ++q) {
    const std::int32_t k = pairs.j[q], at = slot(k, from_here[k]++);
    runs.source[at] = on_j + q;
    runs.incoming[q] = at;
  }
}

}  // namespace runout
