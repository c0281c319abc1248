#include "agents/formation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace masnet::agents {

using protocols::ConvexPolygon;

std::vector<Vec2> formation_offsets(const FormationDef& def) {
  const std::size_t n = def.followers_per_group();
  const double d = def.spacing_m;
  std::vector<Vec2> offsets;
  offsets.reserve(n);
  switch (def.shape) {
    case FormationShape::line:
    case FormationShape::wedge: {
      const double half = std::numbers::sqrt2 / 2.0;  // the wedge's arms at 45° from −y
      for (std::size_t k = 0; k < n; ++k) {
        const double rank = static_cast<double>(k / 2 + 1);
        const double side = k % 2 == 0 ? -1.0 : 1.0;
        offsets.push_back(def.shape == FormationShape::line
                              ? Vec2{side * rank * d, 0.0}
                              : Vec2{side * rank * d * half, -rank * d * half});
      }
      break;
    }
    case FormationShape::circle: {
      // Neighbours on the circle `spacing` apart, and never nearer the leader than that.
      const double chord = n >= 2 ? 2.0 * std::sin(std::numbers::pi / static_cast<double>(n)) : 1;
      const double radius = std::max(d, d / chord);
      for (std::size_t k = 0; k < n; ++k) {
        const double angle = std::numbers::pi / 2.0 + 2.0 * std::numbers::pi *
                                                          static_cast<double>(k) /
                                                          static_cast<double>(n);
        offsets.push_back(Vec2{radius * std::cos(angle), radius * std::sin(angle)});
      }
      break;
    }
    case FormationShape::offsets:
      offsets = def.offsets;
      break;
  }
  return offsets;
}

namespace {

// Outward normal of the edge a → b of a counter-clockwise polygon (not unit).
Vec2 outward_normal(const Vec2& a, const Vec2& b) {
  return Vec2{b.y() - a.y(), a.x() - b.x()};
}

Vec2 nearest_on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  if (length2 == 0.0) return a;
  const double t = std::clamp((p - a).dot(ab) / length2, 0.0, 1.0);
  return a + t * ab;
}

}  // namespace

ConvexPolygon inset(const ConvexPolygon& cell, double margin) {
  if (margin <= 0.0 || cell.vertices.size() < 3) return cell;
  ConvexPolygon region = cell;
  const std::size_t n = cell.vertices.size();
  for (std::size_t i = 0; i < n && !region.empty(); ++i) {
    const Vec2& a = cell.vertices[i];
    const Vec2& b = cell.vertices[(i + 1) % n];
    const Vec2 normal = outward_normal(a, b);
    const double length = normal.norm();
    if (length == 0.0) continue;
    region = protocols::clip(region, {normal, normal.dot(a) - margin * length});
  }
  return region;
}

double fit_scale(const ConvexPolygon& region, const Vec2& anchor,
                 const std::vector<Vec2>& offsets) {
  if (region.vertices.size() < 3 || !protocols::contains(region, anchor)) return 0.0;
  double scale = 1.0;
  const std::size_t n = region.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = region.vertices[i];
    const Vec2 normal = outward_normal(a, region.vertices[(i + 1) % n]);
    const double room = normal.dot(a) - normal.dot(anchor);  // >= 0: the anchor is inside
    for (const Vec2& d : offsets) {
      const double toward = normal.dot(d);
      if (toward > 0.0) scale = std::min(scale, room / toward);
    }
  }
  return std::max(scale, 0.0);
}

FormationFit fit_formation(const ConvexPolygon& cell, const Vec2& leader,
                           const std::vector<Vec2>& offsets, double margin) {
  if (cell.vertices.size() < 3) return {};
  const ConvexPolygon room = inset(cell, margin);
  if (room.empty()) return {0.0, nearest_point_in(cell, leader) - leader};
  const Vec2 centre = nearest_point_in(room, leader);
  return {fit_scale(room, centre, offsets), centre - leader};
}

Vec2 nearest_point_in(const ConvexPolygon& polygon, const Vec2& point) {
  if (polygon.empty() || protocols::contains(polygon, point)) return point;
  Vec2 best = polygon.vertices.front();
  double best_d2 = std::numeric_limits<double>::infinity();
  const std::size_t n = polygon.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 q = nearest_on_segment(polygon.vertices[i], polygon.vertices[(i + 1) % n], point);
    const double d2 = (q - point).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

double distance_outside(const ConvexPolygon& polygon, const Vec2& point) {
  if (polygon.empty()) return 0.0;
  return (nearest_point_in(polygon, point) - point).norm();
}

net::MessageType formation_message_type() {
  static const net::MessageType type = net::register_message_type("FORMATION");
  return type;
}

std::uint32_t formation_body_bytes(const FormationState& state, const net::MessageSizes& sizes) {
  // Group and slot, position and velocity, then the cell (a vertex count and the vertices).
  std::uint32_t bytes = sizes.id_bytes + sizes.counter_bytes + 2 * sizes.position_bytes;
  if (state.slot < 0)  // a leader's target, and its cell
    bytes += sizes.position_bytes + sizes.counter_bytes +
             static_cast<std::uint32_t>(state.cell.vertices.size()) * sizes.vertex_bytes;
  return bytes;
}

// ---- The follower's controller ---------------------------------------------------------------

FollowerController::FollowerController(const FormationDef& def, const MotionParams& motion,
                                       std::size_t slot)
    : def_(def), motion_(motion), slot_(slot), offsets_(formation_offsets(def)) {
  fellows_.resize(offsets_.size());
}

void FollowerController::hear(double t_s, const FormationState& state) {
  const Heard heard{t_s, state.position, state.velocity, state.target};
  if (state.slot < 0) {
    const std::optional<Heard> previous = leader_;
    leader_ = heard;
    if (state.cell.vertices.size() >= 3) {
      cell_ = state.cell;
      inner_ = inset(cell_, def_.margin_m);
      // Every follower of the group fits the same formation to the same message.
      const FormationFit fit = fit_formation(cell_, state.position, offsets_, def_.margin_m);
      scale_rate_per_s_ = previous && t_s > previous->t_s && !cell_.empty()
                              ? (fit.scale - scale_) / (t_s - previous->t_s)
                              : 0.0;
      scale_ = fit.scale;
      shift_ = fit.shift;
    }
    return;
  }
  const auto slot = static_cast<std::size_t>(state.slot);
  if (slot != slot_ && slot < fellows_.size()) fellows_[slot] = heard;
}

Vec2 FollowerController::predicted(const Heard& heard, double now_s) const {
  // Dead reckoning over a bounded time: a lost leader is not extrapolated out of sight.
  const double dt = std::clamp(now_s - heard.t_s, 0.0, 2.0 * def_.state_period_s);
  return heard.position + dt * heard.velocity;
}

std::optional<Vec2> FollowerController::leader_slot(double now_s) const {
  if (!leader_) return std::nullopt;
  return predicted(*leader_, now_s) + shift_ + scale_ * offsets_[slot_];
}

std::optional<Vec2> FollowerController::target(double now_s, const MotionState& self) const {
  if (!leader_) return std::nullopt;
  const Vec2 leader = predicted(*leader_, now_s);
  const Vec2& mine = offsets_[slot_];
  Vec2 sum = def_.leader_weight * (leader + shift_ + scale_ * mine);
  double weight = def_.leader_weight;
  for (std::size_t j = 0; j < fellows_.size(); ++j) {
    const std::optional<Heard>& fellow = fellows_[j];
    if (j == slot_ || !fellow || now_s - fellow->t_s > def_.stale_after_s) continue;
    sum += def_.neighbour_weight * (predicted(*fellow, now_s) + scale_ * (mine - offsets_[j]));
    weight += def_.neighbour_weight;
  }
  // The slot relative to the leader, carried to where the leader is heading: the leader's own
  // motion is fed forward, so a follower in its slot stays there however the leader moves. The
  // formation shrinking or growing with the cell is fed forward too.
  Vec2 goal = leader_->target + (sum / weight - leader);
  if (motion_.k > 0.0) goal += (motion_.k_v / motion_.k) * scale_rate_per_s_ * mine;
  if (cell_.empty()) return goal;
  const ConvexPolygon& room = inner_.empty() ? cell_ : inner_;
  goal = nearest_point_in(room, goal);
  if (stays_inside(now_s, self, goal)) return goal;
  // Pull the goal toward the leader (inside the cell) until the motion toward it stays inside.
  const Vec2 anchor = nearest_point_in(room, leader);
  if (!stays_inside(now_s, self, anchor)) return anchor;
  double safe = 0.0, unsafe = 1.0;
  for (int i = 0; i < 6; ++i) {
    const double mid = 0.5 * (safe + unsafe);
    (stays_inside(now_s, self, anchor + mid * (goal - anchor)) ? safe : unsafe) = mid;
  }
  return anchor + safe * (goal - anchor);
}

bool FollowerController::stays_inside(double now_s, const MotionState& self,
                                      const Vec2& goal) const {
  if (motion_.jump_to_target) return protocols::contains(cell_, goal);
  // The closed-form motion sampled over a horizon of three decay times (the law damps as
  // e^{−k_v t/2}); what is left of an overshoot by then is within the margin.
  constexpr int kSamples = 48;
  const double horizon_s = motion_.k_v > 0.0 ? std::min(6.0 / motion_.k_v, 12.0) : 12.0;
  const MotionSegment segment(motion_, now_s, self, goal);
  for (int i = 1; i <= kSamples; ++i) {
    const double t = now_s + horizon_s * static_cast<double>(i) / kSamples;
    if (!protocols::contains(cell_, segment.state_at(t).position)) return false;
  }
  return true;
}

}  // namespace masnet::agents
