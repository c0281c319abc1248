#include "protocols/heard_cell.hpp"

#include <algorithm>

namespace masnet::protocols {

std::vector<NodeId> heard_neighbours(const Vec2& position, std::span<const HeardRobot> heard,
                                     const ConvexPolygon& domain) {
  // Reused across calls on this thread: a recorder calls this once per update.
  thread_local std::vector<HeardRobot> by_distance;
  thread_local std::vector<Vec2> sites;
  thread_local std::vector<std::uint32_t> candidates;
  by_distance.assign(heard.begin(), heard.end());
  std::sort(by_distance.begin(), by_distance.end(), [&](const HeardRobot& a, const HeardRobot& b) {
    const double da = (a.position - position).squaredNorm();
    const double db = (b.position - position).squaredNorm();
    return da < db || (da == db && a.robot < b.robot);
  });
  sites.assign(1, position);
  candidates.clear();
  for (const HeardRobot& h : by_distance) {
    candidates.push_back(static_cast<std::uint32_t>(sites.size()));
    sites.push_back(h.position);
  }
  const Cell cell = voronoi_cell(0, sites, candidates, domain);
  std::vector<NodeId> neighbours;
  for (std::uint32_t i : cell.neighbours)
    neighbours.push_back(by_distance[i - 1].robot);
  std::sort(neighbours.begin(), neighbours.end());
  return neighbours;
}

}  // namespace masnet::protocols
