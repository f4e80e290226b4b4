// The cell grid of the contact search (SPEC §5): every disc binned into square cells by a
// counting sort, each grid column's cells one run of places, the discs of a cell in index order.
// Columns, not rows: the discs are numbered along x (World::reorder_discs), so a column's discs are
// a narrow range of indices and the search reads fewer lines of their state (a rebuild ~25 us
// faster at two threads in 8 of 8 alternated pairs; docs/performance_log.md, thirty-sixth session).
#pragma once

#include <cstdint>
#include <vector>

#include "runout/particles.hpp"

namespace runout {

struct CellGrid {
  double xmin = 0, ymin = 0, inv_cell = 0;
  std::int32_t ncx = 0, ncy = 0;
  double rmin = 0, rmax = 0;
  std::vector<std::int32_t> cell_start;  // cell cx * ncy + cy: places [cell_start[c], cell_start[c + 1])
  std::vector<std::int32_t> cell_disc;   // place -> disc
  std::vector<std::int32_t> disc_cell;   // disc -> cell
  std::vector<std::int32_t> disc_place;  // disc -> place

  // Cells of 2 r_min + skin (grown where the flow spans too many), for the discs of `p`
  // (at least one). Throws NumericalError for a position or radius that is not finite.
  void build(const Particles& p, double skin);

  // The column and row of the cells holding x and y, clamped to the grid.
  std::int32_t column(double x) const { return clamped((x - xmin) * inv_cell, ncx); }
  std::int32_t row(double y) const { return clamped((y - ymin) * inv_cell, ncy); }

 private:
  static std::int32_t clamped(double cells_from_edge, std::int32_t cells);
  std::vector<std::int32_t> cursor_;
};

}  // namespace runout
