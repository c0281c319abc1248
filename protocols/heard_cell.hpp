#pragma once
// The cell an update should have built from what it heard: the judge of
// `protocol.cell_correctness_heard` (docs/decisions/0010-cell-correctness.md).
#include <span>
#include <vector>

#include "protocols/geometry.hpp"
#include "protocols/host.hpp"

namespace masnet::protocols {

/// The robots whose bisectors bound the Voronoi cell of `position` in `domain` among `heard`
/// (each at the position its reply carried), ascending. Built as the oracle builds the true cell
/// (World::oracle_cell): the same clipping and tolerances, candidates nearest first, ties by id,
/// so the answer does not depend on the order the replies came in.
std::vector<NodeId> heard_neighbours(const Vec2& position, std::span<const HeardRobot> heard,
                                     const ConvexPolygon& domain);

}  // namespace masnet::protocols
