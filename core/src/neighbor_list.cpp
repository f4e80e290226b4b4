#include "runout/neighbor_list.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>

#include "runout/errors.hpp"

namespace runout {

namespace {

// Discs a thread takes at a time where the rebuild hands out work as threads come free.
constexpr std::int32_t kChunk = 128;

// Contiguous block of [0, n) for thread t of T: concatenating blocks in thread order gives the
// same list for any thread count.
inline std::pair<std::int32_t, std::int32_t> block(std::int32_t n, int t, int T) {
  return {static_cast<std::int32_t>(std::int64_t(n) * t / T),
          static_cast<std::int32_t>(std::int64_t(n) * (t + 1) / T)};
}

// body(t) for each of `blocks` blocks, on a team of up to as many threads. OpenMP may give a
// smaller team than asked (OMP_THREAD_LIMIT, a nested region): each member then takes the
// blocks t = its number, + team, ..., so every block's buffers are filled whatever the team.
template <class Body>
void each_block(int blocks, const Body& body) {
#pragma omp parallel num_threads(blocks)
  for (int t = omp_get_thread_num(); t < blocks; t += omp_get_num_threads()) body(t);
}

// Copies the history of pairs listed before into the new list, `width` columns per contact.
// Both lists are sorted by (first, second) within a row; rows are per first index. A list of
// another width (a checkpoint of other laws) carries nothing.
template <class Key>
void carry_history(const HotArray<std::int32_t>& old_row, const Key& old_second,
                   const HotArray<double>& old_history, int old_width,
                   const HotArray<std::int32_t>& row, const Key& second,
                   HotArray<double>& history, int width, std::int32_t rows, int threads) {
  const bool had_old = old_row.size() == row.size() && old_width == width &&
                       old_history.size() == old_second.size() * static_cast<size_t>(width);
  if (width == 0) return;
  // Column m of contact q at history[m * count + q] (SoA, so the kernel loads are contiguous).
  const std::size_t old_count = old_second.size(), new_count = second.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int32_t k = 0; k < rows; ++k) {
    std::int32_t a = had_old ? old_row[k] : 0;
    const std::int32_t a_end = had_old ? old_row[k + 1] : 0;
    for (std::int32_t p = row[k]; p < row[k + 1]; ++p) {
      while (a < a_end && old_second[a] < second[p]) ++a;
      const bool found = a < a_end && old_second[a] == second[p];
      for (int m = 0; m < width; ++m)
        history[m * new_count + p] = found ? old_history[m * old_count + a] : 0.0;
    }
  }
}

}  // namespace

void NeighborSearch::rebuild(const Particles& p, const std::vector<Segment>& segments,
                             double skin, int threads, int history_width,
                             PairContacts& pairs, WallContacts& walls, DiscRuns& runs) {
  const auto n = static_cast<std::int32_t>(p.size());
  threads = std::max(1, threads);

  std::swap(old_pairs_, pairs);
  std::swap(old_walls_, walls);
  pairs.row_start.assign(static_cast<size_t>(n) + 1, 0);
  walls.row_start.assign(static_cast<size_t>(n) + 1, 0);
  pairs.i.clear(); pairs.j.clear();
  walls.disc.clear(); walls.segment.clear();
  largest_radius_ = 0;

  if (n > 0) {
    // ---- the cell grid, and meanwhile the disc–wall pairs (they need no grid) ----
    const auto ns = static_cast<std::int32_t>(segments.size());
    // The distance to a segment's line is at most the distance to the segment: a disc farther
    // from the line than it can reach (wall_candidate: r + skin, and behind a one-sided face
    // behind_reach (2 r + skin)) is not a candidate, found without the projection's division.
    // Most discs are far from most walls' lines. The margin keeps the test conservative.
    struct Line { double nx, ny, offset, behind_reach; bool usable; };
    std::vector<Line> lines(static_cast<std::size_t>(ns));
    for (std::int32_t s = 0; s < ns; ++s) {
      const Eigen::Vector2d ab = segments[s].b - segments[s].a;
      const double len = ab.norm();
      const Eigen::Vector2d normal = len > 0 ? Eigen::Vector2d(-ab.y() / len, ab.x() / len) : Eigen::Vector2d(0, 0);
      lines[s] = {normal.x(), normal.y(), normal.dot(segments[s].a),
                  segments[s].one_sided() ? segments[s].behind_reach : 0.0, len > 0};
    }
    // The discs' walls in chunks of discs, each chunk's found segments kept apart and joined in
    // chunk order, so the list is the same whoever took a chunk. One thread bins the discs
    // into cells while the others take chunks, then it takes chunks too: the grid alone kept
    // the other threads idle long enough to fall asleep before the pair search (docs/performance.md).
    const std::int32_t chunks = (n + kChunk - 1) / kChunk;
    chunk_walls_.resize(static_cast<std::size_t>(chunks));
    wall_margin_.resize(static_cast<std::size_t>(n));
    auto find_walls = [&](std::int32_t lo, std::int32_t hi, std::vector<std::int32_t>& out) {
      out.clear();
      for (std::int32_t k = lo; k < hi; ++k) {
        const Eigen::Vector2d c(p.x[k], p.y[k]);
        const double r = p.radius[k];
        double margin = std::numeric_limits<double>::infinity();
        for (std::int32_t s = 0; s < ns; ++s) {
          if (!segments[s].active) continue;
          const Line& l = lines[s];
          const double reach = std::max(r + skin, l.behind_reach * (behind_depth(r) + skin));
          const double line_distance = std::abs(l.nx * c.x() + l.ny * c.y() - l.offset);
          const bool far = l.usable && line_distance > reach * (1 + 1e-9) + 1e-12;
          if (!far && wall_candidate(segments[s], c, r, skin)) {
            out.push_back(s);
            ++walls.row_start[k + 1];
            continue;
          }
          // Unlisted: a contact needs the centre within r of the segment, or within
          // behind_reach * behind_depth(r) behind a one-sided face. A centre on the inside of
          // a one-sided face touches it only within r, or once behind its line (its line
          // distance away). Moving less than that (the line's distance stands for the
          // segment's when far; with a rounding margin) touches nothing; the skin always holds
          // (wall_candidate).
          const Segment& seg = segments[s];
          const double distance = far ? line_distance : std::sqrt(squared_distance_to(seg, c));
          const double inside = seg.one_sided() ? seg.inside.dot(c - seg.a) : 0.0;
          const double clear = inside > 0 ? std::min(distance - r, inside)
                                          : distance - std::max(r, l.behind_reach * behind_depth(r));
          const double beyond = clear * (1 - 1e-9) - 1e-12;
          margin = std::min(margin, std::max(skin, beyond));
        }
        wall_margin_[k] = margin;
      }
    };
    std::exception_ptr grid_failed;
#pragma omp parallel num_threads(threads)
    {
      if (omp_get_thread_num() == 0) {
        try {
          grid_.build(p, skin);
        } catch (...) {
          grid_failed = std::current_exception();
        }
      }
#pragma omp for schedule(dynamic, 1)
      for (std::int32_t c = 0; c < chunks; ++c)
        find_walls(c * kChunk, std::min(n, (c + 1) * kChunk), chunk_walls_[c]);
    }
    if (grid_failed) std::rethrow_exception(grid_failed);
    std::partial_sum(walls.row_start.begin(), walls.row_start.end(), walls.row_start.begin());
    walls.segment.clear();
    for (const auto& found : chunk_walls_) walls.segment.insert(walls.segment.end(), found.begin(), found.end());
    walls.disc.resize(walls.segment.size());
    for (std::int32_t k = 0; k < n; ++k)
      std::fill(walls.disc.begin() + walls.row_start[k], walls.disc.begin() + walls.row_start[k + 1], k);
    largest_radius_ = grid_.rmax;

    // ---- disc pairs ----
    // Each pair is found once. Discs up to 1.5 times the smallest radius (the fine ones: the
    // small species with its spread) find their fine neighbours with a half stencil: all reach
    // as far as the largest fine disc, so of two fine discs the one earlier in the grid's order
    // has the other in its stencil and finds the pair, and scans only the grid after its own
    // place. A pair with a larger disc is found from the larger one (equal radii: the earlier),
    // which searches the cells within its own diameter plus the skin: a small disc does not
    // scan the wide stencil a large neighbour needs (D/d = 8: a fifth of the candidates). The
    // pairs are then put in the rows of their lower index, each row sorted by j, so the list is
    // the same as a search from every i would give, whatever the thread count.
    const CellGrid& g = grid_;
    const std::int32_t ncx = g.ncx;
    const double fine_limit = 1.5 * g.rmin;
    double fine_radius = g.rmin;  // the largest fine radius
    // A select, not a branch: a bidisperse pile's radii would mispredict it (~10 us a rebuild).
#pragma omp simd reduction(max : fine_radius)
    for (std::int32_t k = 0; k < n; ++k)
      fine_radius = std::max(fine_radius, p.radius[k] <= fine_limit ? p.radius[k] : 0.0);
    // Chunks of discs taken as threads come free (a block's share of large discs, which scan
    // wide stencils, differs between blocks), each thread's pairs in a buffer of its own:
    // the binning and the rows' sort below make the list the same whoever found a pair.
    thread_j_.resize(threads);
    thread_found_.assign(threads, 0);
#pragma omp parallel num_threads(threads)
    {
      auto& out = thread_j_[omp_get_thread_num()];  // (lower, higher) index pairs, flattened
      std::size_t found = 0;
      // The cells a disc scans: those meeting the square of half-width 2 r + skin around its
      // centre, from its coordinates (a disc near a cell's edge needs two cells, not three).
      // A grid row's cells are contiguous in g.cell_disc, so each row is one run of discs.
#pragma omp for schedule(dynamic, 1)
      for (std::int32_t chunk = 0; chunk < chunks; ++chunk) {
        const std::int32_t lo = chunk * kChunk, hi = std::min(n, lo + kChunk);
        for (std::int32_t a = lo; a < hi; ++a) {
          const double ra = p.radius[a], xa = p.x[a], ya = p.y[a];
          const bool fine = ra <= fine_limit, coarse = !fine;
          const double reach = 2 * (fine ? fine_radius : ra) + skin;
          const std::int32_t place = g.disc_place[a];
          const std::int32_t gx0 = g.column(xa - reach), gx1 = g.column(xa + reach);
          const std::int32_t gy_own = g.disc_cell[a] / ncx;
          const std::int32_t gy0 = fine ? gy_own : g.row(ya - reach);
          const std::int32_t gy1 = g.row(ya + reach);
          for (std::int32_t gy = gy0; gy <= gy1; ++gy) {
            std::int32_t q_begin = g.cell_start[gy * ncx + gx0];
            if (fine && gy == gy_own) q_begin = std::max(q_begin, std::min(place + 1, g.cell_start[gy * ncx + gx1 + 1]));
            const std::int32_t q_end = g.cell_start[gy * ncx + gx1 + 1];
            if (out.size() < found + 2 * static_cast<std::size_t>(q_end - q_begin))
              out.resize(2 * out.size() + 2 * static_cast<std::size_t>(q_end - q_begin));
            std::int32_t* __restrict next = out.data() + found;
            // Every candidate is written and kept or overwritten by the next one: no branch on
            // the outcome (about half the candidates are kept, so a branch mispredicts often).
            for (std::int32_t q = q_begin; q < q_end; ++q) {
              const std::int32_t b = g.cell_disc[q];
              const double rb = p.radius[b];
              // Bitwise, so no branch (a bidisperse pile would mispredict it half the time); a
              // fine disc scans only places after its own.
              const bool from_here = (fine & (rb <= fine_limit)) |
                                     (coarse & ((rb < ra) | ((rb == ra) & (q > place))));  // else from b
              const double dx = p.x[b] - xa, dy = p.y[b] - ya;
              const double cut = ra + rb + skin;
              next[0] = std::min(a, b);
              next[1] = std::max(a, b);
              next += 2 * (from_here & (dx * dx + dy * dy < cut * cut));
            }
            found = static_cast<std::size_t>(next - out.data());
          }
        }
      }
      thread_found_[omp_get_thread_num()] = found;
    }
    // Binned by a counting sort in parallel: each thread counts its pairs per row, each row's
    // start is the sum over threads, and each thread writes its pairs from its own offset in
    // the row (the rows are sorted after, so the order of the writes does not matter).
    thread_count_.resize(threads);
    each_block(threads, [&](int t) {
      auto& count = thread_count_[t];
      count.assign(static_cast<std::size_t>(n), 0);
      const auto& found = thread_j_[t];
      for (std::size_t q = 0; q < thread_found_[t]; q += 2) ++count[found[q]];
    });
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int32_t r = 0; r < n; ++r) {
      std::int32_t len = 0;
      for (int t = 0; t < threads; ++t) len += thread_count_[t][r];
      pairs.row_start[r + 1] = len;
    }
    std::partial_sum(pairs.row_start.begin(), pairs.row_start.end(), pairs.row_start.begin());
    const auto np = pairs.row_start[n];
    pairs.i.resize(np);
    pairs.j.resize(np);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int32_t r = 0; r < n; ++r) {
      std::int32_t at = pairs.row_start[r];
      for (int t = 0; t < threads; ++t) {
        const std::int32_t c = thread_count_[t][r];
        thread_count_[t][r] = at;  // now the thread's cursor in row r
        at += c;
      }
    }
    each_block(threads, [&](int t) {
      auto& cursor = thread_count_[t];
      const auto& found = thread_j_[t];
      for (std::size_t q = 0; q < thread_found_[t]; q += 2) pairs.j[cursor[found[q]]++] = found[q + 1];
    });
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int32_t i = 0; i < n; ++i) {
      // Rows are short (a handful of neighbours): insertion sort beats std::sort here.
      std::int32_t* row = pairs.j.data() + pairs.row_start[i];
      const std::int32_t len = pairs.row_start[i + 1] - pairs.row_start[i];
      for (std::int32_t x = 1; x < len; ++x)
        for (std::int32_t y = x; y > 0 && row[y - 1] > row[y]; --y) std::swap(row[y - 1], row[y]);
      std::fill(pairs.i.begin() + pairs.row_start[i], pairs.i.begin() + pairs.row_start[i + 1], i);
    }

  }

  // ---- each disc's run: its row, then the pairs where it is j (in pair order, so by i) ----
  // Built in parallel, the layout a function of the lists alone: each thread counts the
  // incoming pairs of its own rows, so disc k's incoming pairs from thread t's rows (smaller
  // i) follow those from the threads before it, which is pair order.
  const auto np = static_cast<std::int32_t>(pairs.i.size());
  const auto on_j = static_cast<std::int32_t>(pairs.j_offset());
  const auto zero = static_cast<std::int32_t>(pairs.zero_push());
  constexpr std::int32_t L = DiscRuns::kSlice, W = DiscRuns::kWindow;
  static_assert(W % L == 0);
  const std::int32_t slices = (n + L - 1) / L, windows = (n + W - 1) / W;
  const std::int32_t* row_start = pairs.row_start.data();
  runs.lane_disc.assign(static_cast<size_t>(slices) * L, -1);
  runs.slice_start.assign(static_cast<size_t>(slices) + 1, 0);
  lane_of_.resize(static_cast<size_t>(n));
  run_length_.resize(static_cast<size_t>(n));
  runs.incoming.resize(static_cast<size_t>(np));
  thread_count_.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), T = omp_get_num_threads();
    const auto [lo, hi] = block(n, t, T);  // this thread's rows
    auto& from_here = thread_count_[t];  // its rows' pairs per j, then its cursors in j's runs
    from_here.assign(static_cast<size_t>(n), 0);
    for (std::int32_t q = row_start[lo]; q < row_start[hi]; ++q) ++from_here[pairs.j[q]];
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int32_t k = 0; k < n; ++k) {
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
    std::vector<std::int32_t> by_length;  // a counting sort's buckets, longest first
#pragma omp for schedule(static)
    for (std::int32_t w = 0; w < windows; ++w) {
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
#pragma omp for schedule(static)
    for (std::int32_t g = 0; g < slices; ++g) {
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

  // ---- history and per-step buffers ----
  pairs.history_width = history_width;
  // carry_history writes every history entry, and the kernel every push but the zero one (and
  // the torques of laws without friction or rolling); the free lines are never read.
  pairs.history.resize(np * history_width);
  pairs.fx.resize(pairs.zero_push() + 1); pairs.fy.resize(pairs.zero_push() + 1);
  pairs.fx[pairs.zero_push()] = pairs.fy[pairs.zero_push()] = 0;
  pairs.torque.assign(pairs.zero_push() + 1, 0);
  carry_history(old_pairs_.row_start, old_pairs_.j, old_pairs_.history, old_pairs_.history_width,
                pairs.row_start, pairs.j, pairs.history, history_width, n, threads);
  const size_t nw = walls.disc.size();
  walls.history_width = history_width;
  walls.history.resize(nw * history_width);
  walls.fx.assign(nw, 0); walls.fy.assign(nw, 0); walls.torque.assign(nw, 0);
  carry_history(old_walls_.row_start, old_walls_.segment, old_walls_.history,
                old_walls_.history_width, walls.row_start, walls.segment, walls.history,
                history_width, n, threads);
}

}  // namespace runout
