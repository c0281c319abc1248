#include "net/spatial_grid.hpp"

#include <algorithm>

#include "sim/assert.hpp"

namespace masnet::net {

void SpatialGrid::build(std::span<const Vec2> positions, std::span<const sim::NodeId> ids,
                        double cell_size) {
  MASNET_ASSERT(positions.size() == ids.size(), "one id per position");
  const std::size_t n = positions.size();
  xs_.assign(n, 0.0);
  ys_.assign(n, 0.0);
  ids_.assign(n, sim::kNoNode);
  if (n == 0) {
    nx_ = ny_ = 1;
    cell_start_.assign(2, 0);
    return;
  }
  double x1 = positions[0].x(), y1 = positions[0].y();
  x0_ = x1;
  y0_ = y1;
  for (const Vec2& p : positions) {
    x0_ = std::min(x0_, p.x());
    y0_ = std::min(y0_, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
  const double width = std::max(x1 - x0_, 1e-9), height = std::max(y1 - y0_, 1e-9);
  cell_ = cell_size > 0.0 ? cell_size : std::sqrt(width * height * 4.0 / static_cast<double>(n));
  cell_ = std::max(cell_, 1e-9);
  // Cap the number of cells so that a degenerate layout cannot allocate a huge table.
  const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
  while ((width / cell_ + 1.0) * (height / cell_ + 1.0) > max_cells)
    cell_ *= 1.5;
  inv_cell_ = 1.0 / cell_;
  nx_ = static_cast<int>(width / cell_) + 1;
  ny_ = static_cast<int>(height / cell_) + 1;

  auto cell_of = [&](const Vec2& p) {
    return static_cast<std::size_t>(row_of(p.y()) * nx_ + col_of(p.x()));
  };
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (const Vec2& p : positions)
    ++cell_start_[cell_of(p) + 1];
  for (std::size_t c = 1; c < cell_start_.size(); ++c)
    cell_start_[c] += cell_start_[c - 1];
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {  // stable: ids keep their input order inside a cell
    const std::uint32_t k = fill[cell_of(positions[i])]++;
    xs_[k] = positions[i].x();
    ys_[k] = positions[i].y();
    ids_[k] = ids[i];
  }
}

}  // namespace masnet::net
