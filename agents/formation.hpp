#pragma once
// Robot groups in formation (the paper's hierarchical network; docs/formations.md): in each
// Voronoi cell a leader runs the cell protocol and heads for the centroid like a lone robot,
// and followers keep a formation around it with a distributed consensus law — using only the
// FORMATION messages they hear — scaled down to fit inside the leader's cell. This file holds the
// pure parts (shapes, the fit, the control law), testable without a world.
#include <cstdint>
#include <optional>
#include <vector>

#include "agents/robot_motion.hpp"
#include "net/messages.hpp"
#include "protocols/geometry.hpp"

namespace masnet::agents {

enum class FormationShape { line, wedge, circle, offsets };

struct FormationDef {
  std::size_t group_size = 1;  ///< robots per group, the leader included; 1 = no groups
  FormationShape shape = FormationShape::wedge;
  double spacing_m = 0.05;    ///< distance between neighbouring slots at full scale (world units)
  std::vector<Vec2> offsets;  ///< shape `offsets`: one per follower, from the leader
  double state_period_s = 0.05;   ///< every group member broadcasts its state this often
  double range_m = 0.25;          ///< range of those broadcasts (world units)
  double leader_weight = 1.0;     ///< consensus weight of the leader's slot
  double neighbour_weight = 1.0;  ///< consensus weight of each fellow follower heard
  double margin_m = 0.01;         ///< slots keep this clearance from the cell's edges (world units)
  double stale_after_s = 0.25;    ///< a fellow's state older than this is not used

  bool enabled() const { return group_size > 1; }
  std::size_t followers_per_group() const { return group_size - 1; }
};

/// The followers' offsets from the leader at full scale, in the world frame (the formation does
/// not turn with the leader): `line` alternates left and right of the leader, `wedge` is a V
/// opening downwards (−y), `circle` spreads them evenly on a circle of radius spacing.
std::vector<Vec2> formation_offsets(const FormationDef& def);

/// `cell` shrunk by `margin` (every edge moved inwards); empty if nothing is left.
protocols::ConvexPolygon inset(const protocols::ConvexPolygon& cell, double margin);

/// The largest s in [0, 1] with anchor + s·d inside `region` for every offset d (a ray cast
/// per offset; 0 when the anchor itself is outside). `region` is convex, so every slot at a
/// smaller scale is inside too.
double fit_scale(const protocols::ConvexPolygon& region, const Vec2& anchor,
                 const std::vector<Vec2>& offsets);

/// Where a group's formation goes in its leader's cell: centred on the leader (shifted to the
/// nearest point at least `margin` inside the cell when the leader stands nearer its edge) at
/// the largest scale that keeps every slot that far inside.
struct FormationFit {
  double scale = 1.0;
  Vec2 shift{0, 0};  ///< from the leader to the formation's centre
};
FormationFit fit_formation(const protocols::ConvexPolygon& cell, const Vec2& leader,
                           const std::vector<Vec2>& offsets, double margin);

/// The point of `polygon` nearest to `point` (`point` itself when inside).
Vec2 nearest_point_in(const protocols::ConvexPolygon& polygon, const Vec2& point);

/// How far `point` lies outside `polygon` (0 inside or on the boundary).
double distance_outside(const protocols::ConvexPolygon& polygon, const Vec2& point);

/// The body of a FORMATION message: a group member's state. A leader's also carries its cell
/// (the region its followers must stay in).
struct FormationState {
  std::uint32_t group = 0;
  std::int32_t slot = -1;  ///< -1: the leader; else the follower's slot, 0-based
  Vec2 position{0, 0}, velocity{0, 0};
  Vec2 target{0, 0};  ///< a leader's: the centroid it heads for (the virtual leader)
  protocols::ConvexPolygon cell;
};

/// The FORMATION message type, registered on first use.
net::MessageType formation_message_type();
/// Its size on the air without the frame header.
std::uint32_t formation_body_bytes(const FormationState& state, const net::MessageSizes& sizes);

/// One follower's controller: it keeps the latest state heard from its leader and fellows and
/// turns them into the target c of its own motion p̈ = −k(p − c) − k_v ṗ. The leader moves by
/// the same law toward its centroid c_L (the virtual leader), so c = c_L + (q − p_L) +
/// (k_v/k)·ṡ·d, with q the consensus of the slots, makes the follower's law the consensus law
/// with a reference for second-order agents, p̈ = −k(p − q) − k_v(ṗ − v_q) + a_L, whose error
/// does not depend on how the leader moves (docs/decisions/0011-formation-control.md).
class FollowerController {
 public:
  FollowerController(const FormationDef& def, const MotionParams& motion, std::size_t slot);

  void hear(double t_s, const FormationState& state);
  /// The target for a follower in state `self` at `now_s`, confined so that the motion toward
  /// it stays inside the leader's cell; nothing before the leader was first heard.
  std::optional<Vec2> target(double now_s, const MotionState& self) const;
  /// The scale of the formation the leader's last cell allows (1 before it was heard).
  double scale() const { return scale_; }
  bool heard_leader() const { return leader_.has_value(); }
  const protocols::ConvexPolygon& cell() const { return cell_; }
  /// The slot the follower aims at now: the leader's slot estimate, before consensus.
  std::optional<Vec2> leader_slot(double now_s) const;

 private:
  struct Heard {
    double t_s;
    Vec2 position, velocity, target;
  };
  Vec2 predicted(const Heard& heard, double now_s) const;
  /// True if the motion from `self` toward `goal` stays inside the cell over the horizon.
  bool stays_inside(double now_s, const MotionState& self, const Vec2& goal) const;

  FormationDef def_;
  MotionParams motion_;
  std::size_t slot_;
  std::vector<Vec2> offsets_;
  std::optional<Heard> leader_;
  std::vector<std::optional<Heard>> fellows_;  // [slot]
  protocols::ConvexPolygon cell_, inner_;      // the leader's cell and its inset by the margin
  double scale_ = 1.0;
  Vec2 shift_{0, 0};
  double scale_rate_per_s_ = 0.0;  // from the last two leader messages: the cell's breathing
};

}  // namespace masnet::agents
