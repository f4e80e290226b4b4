#include "runout/neighbor_list.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "runout/errors.hpp"

namespace runout {

namespace {

// Discs a thread takes at a time where the rebuild hands out work as threads come free.
constexpr std::int32_t kChunk = 128;

// Copies the history of pairs listed before into the new list, `width` columns per contact.
// Both lists are sorted by (first, second) within a row; rows are per first index. A list of
// another width (a checkpoint of other laws) carries nothing. For the rows [lo, hi).
template <class Key>
void carry_history(const HotArray<std::int32_t>& old_row, const Key& old_second,
                   const HotArray<double>& old_history, int old_width,
                   const HotArray<std::int32_t>& row, const Key& second,
                   HotArray<double>& history, int width, std::int32_t lo, std::int32_t hi) {
  const bool had_old = old_row.size() == row.size() && old_width == width &&
                       old_history.size() == old_second.size() * static_cast<size_t>(width);
  if (width == 0) return;
  // Column m of contact q at history[m * count + q] (SoA, so the kernel loads are contiguous).
  const std::size_t old_count = old_second.size(), new_count = second.size();
  for (std::int32_t k = lo; k < hi; ++k) {
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
                             double skin, int threads, const std::vector<std::int64_t>& blocks,
                             int history_width, PairContacts& pairs, WallContacts& walls,
                             DiscRuns& runs) {
  const auto n = static_cast<std::int32_t>(p.size());
  threads = std::max(1, threads);
  std::swap(old_pairs_, pairs);
  std::swap(old_walls_, walls);
  // Every entry of the lists is written below: resized, never cleared (a clear and a resize
  // zero-filled them on one thread).
  pairs.row_start.resize(static_cast<size_t>(n) + 1);
  walls.row_start.resize(static_cast<size_t>(n) + 1);
  pairs.row_start[0] = walls.row_start[0] = 0;
  largest_radius_ = 0;

  // The distance to a segment's line is at most the distance to the segment: a disc farther
  // from the line than it can reach (wall_candidate: r + skin, and behind a one-sided face
  // behind_reach (2 r + skin)) is not a candidate, found without the projection's division.
  // Most discs are far from most walls' lines. The margin keeps the test conservative.
  const auto ns = static_cast<std::int32_t>(segments.size());
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
  // chunk order, so the list is the same whoever took a chunk.
  const std::int32_t chunks = (n + kChunk - 1) / kChunk;
  chunk_walls_.resize(static_cast<std::size_t>(chunks));
  wall_margin_.resize(static_cast<std::size_t>(n));
  auto find_walls = [&](std::int32_t lo, std::int32_t hi, std::vector<std::int32_t>& out) {
    out.clear();
    for (std::int32_t k = lo; k < hi; ++k) {
      const Eigen::Vector2d c(p.x[k], p.y[k]);
      const double r = p.radius[k];
      double margin = std::numeric_limits<double>::infinity();
      std::int32_t found = 0;
      for (std::int32_t s = 0; s < ns; ++s) {
        if (!segments[s].active) continue;
        const Line& l = lines[s];
        const double reach = std::max(r + skin, l.behind_reach * (behind_depth(r) + skin));
        const double line_distance = std::abs(l.nx * c.x() + l.ny * c.y() - l.offset);
        const bool far = l.usable && line_distance > reach * (1 + 1e-9) + 1e-12;
        if (!far && wall_candidate(segments[s], c, r, skin)) {
          out.push_back(s);
          ++found;
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
      walls.row_start[k + 1] = found;
      wall_margin_[k] = margin;
    }
  };
  thread_j_.resize(threads);
  thread_foreign_.resize(threads);
  thread_count_.resize(threads);
  team_.resize(threads);
  std::exception_ptr grid_failed;
  constexpr std::int32_t L = DiscRuns::kSlice;
  static_assert(DiscRuns::kWindow % L == 0);
  const std::int32_t slices = (n + L - 1) / L;

  // One region for the whole rebuild, each stage's threads meeting at a barrier: a region a
  // stage cost a fork and a join each, and the serial steps between them let the other
  // threads fall asleep (docs/performance_log.md, issue 11, twenty-fourth session).
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), T = omp_get_num_threads();
    // This thread's discs and rows.
    const auto [block_lo, block_hi] = team_block(blocks, n, t, T);
    const auto lo = static_cast<std::int32_t>(block_lo), hi = static_cast<std::int32_t>(block_hi);
    TeamSlot& mine = team_[t];
    // One thread bins the discs into cells while the others take chunks of the walls, then
    // it takes chunks too. A binning by every thread (counts per cell and thread) took 40 us
    // at two threads against ~25 us for one: an inclined flow's box holds ~4 cells a disc
    // (docs/performance_log.md, issue 11, twenty-fourth session).
    if (t == 0 && n > 0) {
      try {
        grid_.build(p, skin);
      } catch (...) {
        grid_failed = std::current_exception();
      }
    }
#pragma omp for schedule(dynamic, 1)
    for (std::int32_t c = 0; c < chunks; ++c)
      find_walls(c * kChunk, std::min(n, (c + 1) * kChunk), chunk_walls_[c]);
    const bool grid_built = n > 0 && !grid_failed;
    if (grid_built) {
      // ---- disc–wall rows, and the fine discs' largest radius ----
      // Discs up to 1.5 times the smallest radius (the fine ones: the small species with
      // its spread) find their fine neighbours with a half stencil (below).
      const CellGrid& g = grid_;
      const double fine_limit = 1.5 * g.rmin;
      double block_fine = g.rmin;
      // A select, not a branch: a bidisperse pile's radii would mispredict it (~10 us).
#pragma omp simd reduction(max : block_fine)
      for (std::int32_t k = lo; k < hi; ++k)
        block_fine = std::max(block_fine, p.radius[k] <= fine_limit ? p.radius[k] : 0.0);
      mine.fine_radius = block_fine;
      // Each row's start: a block's sum, then the blocks before it.
      mine.walls = 0;
      for (std::int32_t k = lo; k < hi; ++k) mine.walls += walls.row_start[k + 1];
#pragma omp barrier
      std::int32_t at = 0;
      double fine_radius = g.rmin;  // the largest fine radius
      for (int u = 0; u < T; ++u) {
        if (u < t) at += team_[u].walls;
        fine_radius = std::max(fine_radius, team_[u].fine_radius);
      }
      for (std::int32_t k = lo; k < hi; ++k) walls.row_start[k + 1] = at += walls.row_start[k + 1];
#pragma omp barrier
#pragma omp single
      {
        const auto nw = static_cast<std::size_t>(walls.row_start[n]);
        walls.segment.resize(nw);
        walls.disc.resize(nw);
        largest_radius_ = g.rmax;
      }
#pragma omp for schedule(static) nowait
      for (std::int32_t c = 0; c < chunks; ++c) {
        const std::int32_t k0 = c * kChunk, k1 = std::min(n, k0 + kChunk);
        std::copy(chunk_walls_[c].begin(), chunk_walls_[c].end(), walls.segment.begin() + walls.row_start[k0]);
        for (std::int32_t k = k0; k < k1; ++k)
          std::fill(walls.disc.begin() + walls.row_start[k], walls.disc.begin() + walls.row_start[k + 1], k);
      }

      // ---- disc pairs ----
      // Each pair is found once. The fine discs all reach as far as the largest fine disc,
      // so of two fine discs the one earlier in the grid's order has the other in its stencil
      // and finds the pair, and scans only the grid after its own place. A pair with a larger
      // disc is found from the larger one (equal radii: the earlier), which searches the
      // cells within its own diameter plus the skin: a small disc does not scan the wide
      // stencil a large neighbour needs (D/d = 8: a fifth of the candidates). The pairs are
      // then put in the rows of their lower index, each row sorted by j, so the list is the
      // same as a search from every i would give, whatever the thread count.
      // Each thread searches from the discs of its own block, and the pairs go to the rows of
      // their lower index, written by the thread whose block holds that row: its pairs from
      // its own search and the few other threads found across its ends (`foreign`). Taken as
      // chunks as threads came free, every row was written by both threads, their counts and
      // cursors crossed between the cores, and a row's lines then went back to its thread in
      // the step (docs/performance_log.md, issue 11, twenty-fourth session).
      const std::int32_t ncy = g.ncy;
      auto& out = thread_j_[t];  // (lower, higher) index pairs of own rows, flattened
      auto& foreign = thread_foreign_[t];  // those of other threads' rows
      std::size_t found = 0;
      foreign.clear();
      // The cells a disc scans: those meeting the square of half-width 2 r + skin around its
      // centre, from its coordinates (a disc near a cell's edge needs two cells, not three).
      // A grid column's cells are contiguous in g.cell_disc, so each column is one run of
      // discs; a fine disc scans its own column from its own place on, and the columns after.
      for (std::int32_t a = lo; a < hi; ++a) {
        const double ra = p.radius[a], xa = p.x[a], ya = p.y[a];
        const bool fine = ra <= fine_limit, coarse = !fine;
        const double reach = 2 * (fine ? fine_radius : ra) + skin;
        const std::int32_t place = g.disc_place[a];
        const std::int32_t gy0 = g.row(ya - reach), gy1 = g.row(ya + reach);
        const std::int32_t gx_own = g.disc_cell[a] / ncy;
        const std::int32_t gx0 = fine ? gx_own : g.column(xa - reach);
        const std::int32_t gx1 = g.column(xa + reach);
        for (std::int32_t gx = gx0; gx <= gx1; ++gx) {
          std::int32_t q_begin = g.cell_start[gx * ncy + gy0];
          const std::int32_t q_end = g.cell_start[gx * ncy + gy1 + 1];
          if (fine && gx == gx_own) q_begin = std::max(q_begin, std::min(place + 1, q_end));
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
      // A pair whose lower index is before this block (the disc found it from a larger or
      // earlier neighbour) is another thread's row: set aside (rare, so the branch is well
      // predicted; the first block has none).
      if (lo > 0) {
        std::int32_t* keep = out.data();
        for (const std::int32_t* kept = keep; kept < out.data() + found; kept += 2) {
          if (kept[0] < lo) {
            foreign.push_back({kept[0], kept[1]});
          } else {
            keep[0] = kept[0];
            keep[1] = kept[1];
            keep += 2;
          }
        }
        found = static_cast<std::size_t>(keep - out.data());
      }
      // Binned by a counting sort over the block's rows: each row's start is the rows' before
      // it, the blocks before this one first.
      auto& count = thread_count_[t];
      count.assign(static_cast<std::size_t>(hi - lo) + 1, 0);
      for (std::size_t q = 0; q < found; q += 2) ++count[out[q] - lo];
#pragma omp barrier
      for (int u = 0; u < T; ++u)
        for (const auto& [i, j] : thread_foreign_[u])
          if (i >= lo && i < hi) ++count[i - lo];
      std::int32_t block_pairs = 0;
      for (std::int32_t r = lo; r < hi; ++r) block_pairs += count[r - lo];
      mine.pairs = block_pairs;
#pragma omp barrier
      at = 0;
      for (int u = 0; u < t; ++u) at += team_[u].pairs;
      for (std::int32_t r = lo; r < hi; ++r) {
        const std::int32_t c = count[r - lo];
        count[r - lo] = at;  // now the cursor in row r
        at += c;
        pairs.row_start[r + 1] = at;
      }
#pragma omp single
      {
        std::int32_t np = 0;
        for (int u = 0; u < T; ++u) np += team_[u].pairs;
        pairs.i.resize(static_cast<std::size_t>(np));
        pairs.j.resize(static_cast<std::size_t>(np));
      }
      for (std::size_t q = 0; q < found; q += 2) pairs.j[count[out[q] - lo]++] = out[q + 1];
      for (int u = 0; u < T; ++u)
        for (const auto& [i, j] : thread_foreign_[u])
          if (i >= lo && i < hi) pairs.j[count[i - lo]++] = j;
      for (std::int32_t i = lo; i < hi; ++i) {
        // Rows are short (a handful of neighbours): insertion sort beats std::sort here.
        std::int32_t* row = pairs.j.data() + pairs.row_start[i];
        const std::int32_t len = pairs.row_start[i + 1] - pairs.row_start[i];
        for (std::int32_t x = 1; x < len; ++x)
          for (std::int32_t y = x; y > 0 && row[y - 1] > row[y]; --y) std::swap(row[y - 1], row[y]);
        std::fill(pairs.i.begin() + pairs.row_start[i], pairs.i.begin() + pairs.row_start[i + 1], i);
      }
    }
#pragma omp single
    {
      if (!grid_built) {  // no discs (or a state gone bad): empty lists
        std::fill(pairs.row_start.begin(), pairs.row_start.end(), 0);
        std::fill(walls.row_start.begin(), walls.row_start.end(), 0);
        pairs.i.clear(); pairs.j.clear(); walls.disc.clear(); walls.segment.clear();
      }
      const auto np = pairs.i.size(), nw = walls.disc.size();
      runs.lane_disc.assign(static_cast<size_t>(slices) * L, -1);
      runs.slice_start.resize(static_cast<size_t>(slices) + 1);
      runs.slice_start[0] = 0;
      lane_of_.resize(static_cast<size_t>(n));
      run_length_.resize(static_cast<size_t>(n));
      runs.incoming.resize(np);
      // carry_history writes every history entry, and the kernel every push but the zero one
      // (and the torques of laws without friction or rolling, zeroed below); the free lines
      // are never read.
      pairs.history_width = history_width;
      pairs.history.resize(np * history_width);
      pairs.fx.resize(pairs.zero_push() + 1); pairs.fy.resize(pairs.zero_push() + 1);
      pairs.torque.resize(pairs.zero_push() + 1);
      pairs.fx[pairs.zero_push()] = pairs.fy[pairs.zero_push()] = pairs.torque[pairs.zero_push()] = 0;
      walls.history_width = history_width;
      walls.history.resize(nw * history_width);
      walls.fx.assign(nw, 0); walls.fy.assign(nw, 0); walls.torque.assign(nw, 0);
    }
    if (grid_built || n == 0) {
      runs_of(pairs, runs, t, T, lo, hi);
      // The pushes of its rows' pairs, on i and on j.
      const std::size_t q0 = pairs.row_start[lo], q1 = pairs.row_start[hi];
      std::fill(pairs.torque.begin() + q0, pairs.torque.begin() + q1, 0.0);
      std::fill(pairs.torque.begin() + pairs.j_offset() + q0, pairs.torque.begin() + pairs.j_offset() + q1, 0.0);
      carry_history(old_pairs_.row_start, old_pairs_.j, old_pairs_.history, old_pairs_.history_width,
                    pairs.row_start, pairs.j, pairs.history, history_width, lo, hi);
      carry_history(old_walls_.row_start, old_walls_.segment, old_walls_.history,
                    old_walls_.history_width, walls.row_start, walls.segment, walls.history,
                    history_width, lo, hi);
    }
  }
  if (grid_failed) std::rethrow_exception(grid_failed);
}

}  // namespace runout
