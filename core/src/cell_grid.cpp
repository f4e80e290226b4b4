#include "runout/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "runout/errors.hpp"

namespace runout {

std::int32_t CellGrid::clamped(double cells_from_edge, std::int32_t cells) {
  return static_cast<std::int32_t>(std::clamp(std::floor(cells_from_edge), 0.0, cells - 1.0));
}

void CellGrid::build(const Particles& p, double skin) {
  const auto n = static_cast<std::int32_t>(p.size());
  double xmax = p.x[0], ymax = p.y[0];
  xmin = p.x[0]; ymin = p.y[0];
  rmin = p.radius[0]; rmax = p.radius[0];
  bool finite = true;  // std::min and std::max pass over a NaN, so it is looked for
  for (std::int32_t k = 0; k < n; ++k) {
    finite = finite && std::isfinite(p.x[k]) && std::isfinite(p.y[k]) && std::isfinite(p.radius[k]);
    xmin = std::min(xmin, p.x[k]); xmax = std::max(xmax, p.x[k]);
    ymin = std::min(ymin, p.y[k]); ymax = std::max(ymax, p.y[k]);
    rmin = std::min(rmin, p.radius[k]); rmax = std::max(rmax, p.radius[k]);
  }
  // Cells sized for the small discs; large discs search a wider stencil, so bidisperse piles
  // with D/d = 8 do not put hundreds of small discs in one cell.
  // The world checks its state after every step; this is the last line against a state that
  // would make the grid meaningless (a NaN or a coordinate beyond ~1e300 m loops or overflows).
  if (!finite || !std::isfinite(xmax - xmin) || !std::isfinite(ymax - ymin) || !(rmin > 0))
    throw NumericalError("neighbour search: disc positions or radii are not finite");
  double cell = std::max(2 * rmin + skin, 1e-12);
  // Counted in floating point: a stray disc far away must neither overflow nor blow memory.
  auto cells_along = [&](double lo, double hi) { return std::floor((hi - lo) / cell) + 1; };
  const double max_cells = std::max(16.0 * n, 1048576.0);
  while (cells_along(xmin, xmax) * cells_along(ymin, ymax) > max_cells) cell *= 1.5;
  ncx = static_cast<std::int32_t>(cells_along(xmin, xmax));
  ncy = static_cast<std::int32_t>(cells_along(ymin, ymax));
  inv_cell = 1.0 / cell;

  disc_cell.resize(n);
  cell_start.assign(static_cast<size_t>(ncx) * ncy + 1, 0);
  for (std::int32_t k = 0; k < n; ++k) {
    const auto cx = std::min(ncx - 1, static_cast<std::int32_t>((p.x[k] - xmin) * inv_cell));
    const auto cy = std::min(ncy - 1, static_cast<std::int32_t>((p.y[k] - ymin) * inv_cell));
    disc_cell[k] = cx * ncy + cy;
    ++cell_start[disc_cell[k] + 1];
  }
  std::partial_sum(cell_start.begin(), cell_start.end(), cell_start.begin());
  cell_disc.resize(n);
  disc_place.resize(n);
  cursor_.assign(cell_start.begin(), cell_start.end() - 1);
  for (std::int32_t k = 0; k < n; ++k) {
    disc_place[k] = cursor_[disc_cell[k]]++;
    cell_disc[disc_place[k]] = k;
  }
}

}  // namespace runout
