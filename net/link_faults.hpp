#pragma once
// Faults of the links rather than the nodes (docs/faults-and-lifetime.md): a line no frame
// crosses (a partition) and areas where receptions are lost more often (a degraded region).
// The world switches them on and off at their times; the radio asks them per reception while
// any is on, and books frames in bulk again once none is.
#include <cstdint>
#include <vector>

#include "net/vec2.hpp"

namespace masnet::net {

/// A disk or a simple polygon (convex or not) of the plane.
struct Region {
  enum class Shape { disk, polygon };
  Shape shape = Shape::disk;
  Vec2 center{0, 0};
  double radius = 0.0;        ///< world units
  std::vector<Vec2> polygon;  ///< vertices in order, either orientation, not closed

  bool contains(const Vec2& p) const;
  /// Area of the region (world units²); 0 for a degenerate one.
  double area() const;
};

/// A segment no frame crosses: the segment from sender to hearer meets it (touching counts).
struct LineCut {
  Vec2 a{0, 0}, b{0, 0};
  bool separates(const Vec2& p, const Vec2& q) const;
};

/// Receptions whose sender or hearer stands in `region` are lost with probability `loss`
/// (on top of the radio's own loss: both draws must spare a frame).
struct DegradedArea {
  Region region;
  double loss = 0.0;
};

/// The link faults in force now. `id`s name a scripted fault so that it can be lifted again.
class LinkFaults {
 public:
  void add_cut(std::uint32_t id, const LineCut& cut) { cuts_.push_back({id, cut}); }
  void add_degraded(std::uint32_t id, const DegradedArea& area) { areas_.push_back({id, area}); }
  /// Lifts every cut and degraded area of `id`.
  void remove(std::uint32_t id);
  bool any() const { return !cuts_.empty() || !areas_.empty(); }
  /// No frame from `from` reaches `to`.
  bool cut(const Vec2& from, const Vec2& to) const;
  /// The probability that a reception from `from` at `to` is lost to degraded areas (0 if none).
  double loss(const Vec2& from, const Vec2& to) const;

 private:
  std::vector<std::pair<std::uint32_t, LineCut>> cuts_;
  std::vector<std::pair<std::uint32_t, DegradedArea>> areas_;
};

/// Every state the link faults have been in, numbered from 0 (none): a tile of a partitioned run
/// judges another tile's frame under the faults in force when it was sent, not when it arrives
/// here (docs/decisions/0012-partitioned-runs.md).
class LinkFaultHistory {
 public:
  LinkFaultHistory() : states_(1) {}
  void record(const LinkFaults& now) { states_.push_back(now); }
  std::uint32_t epoch() const { return static_cast<std::uint32_t>(states_.size() - 1); }
  const LinkFaults& at(std::uint32_t epoch) const { return states_.at(epoch); }

 private:
  std::vector<LinkFaults> states_;
};

}  // namespace masnet::net
