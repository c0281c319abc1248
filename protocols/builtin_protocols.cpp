// The built-in protocols, registered exactly as a user's protocol is (docs/protocol-api.md).
// The order is the order `protocol.kind` lists them in messages.
#include <memory>

#include "protocols/ground_truth.hpp"
#include "protocols/oracle_protocol.hpp"
#include "protocols/registry.hpp"
#include "protocols/voronoi_protocol.hpp"

namespace masnet::protocols {

void register_builtin(ProtocolDefinition definition,
                      TruthfulRobotFactory truthful);  // registry.cpp

ParamSpec update_period_param() {
  return ParamSpec::real("period", 0.01, ParamRange::time(), "s",
                         "Δt between a robot's updates (seeded phase)");
}
ParamSpec reply_timeout_param() {
  return ParamSpec::real("reply_timeout", 0.002, ParamRange::time(), "s",
                         "how long a round waits for replies (default per radio level)");
}
ParamSpec reply_jitter_param() {
  return ParamSpec::real("reply_jitter", 0.0, ParamRange::non_negative(), "s",
                         "sensors delay each reply by a uniform draw in [0, J)");
}

namespace {

using net::MessageType;

ParamSpec period() {
  return update_period_param();
}
ParamSpec reply_timeout() {
  return reply_timeout_param();
}
ParamSpec reply_jitter() {
  return reply_jitter_param();
}

// Every built-in hears the same types, so a run's radio counters do not depend on the kind.
ProtocolDefinition builtin(std::string name, std::string summary, std::vector<ParamSpec> params) {
  ProtocolDefinition d;
  d.name = std::move(name);
  d.summary = std::move(summary);
  d.params = std::move(params);
  d.robots_hear = {MessageType::discover, MessageType::neighbor, MessageType::reading,
                   MessageType::report};
  d.sensors_hear = {MessageType::position, MessageType::sense};
  d.make_sensor = paper_sensors();
  return d;
}

ProtocolParams voronoi_params(VoronoiVariant variant, const ParamValues& v) {
  ProtocolParams p;
  p.variant = variant;
  p.period_s = v.real("period");
  p.reply_timeout_s = v.real("reply_timeout");
  if (variant == VoronoiVariant::radius_doubling) {
    p.growth = v.choice("growth") == "double" ? Growth::doubling : Growth::to_2d;
    p.criterion =
        v.choice("criterion") == "vertices" ? StopCriterion::vertices : StopCriterion::sensors;
    p.shrink_on_stop = v.boolean("shrink_on_stop");
    p.decay.patience = static_cast<std::uint32_t>(v.integer("decay.patience"));
    p.decay.step = v.real("decay.step");
    p.decay.min = v.real("decay.min");
  }
  if (variant == VoronoiVariant::fixed_radius) p.fixed_radius = v.real("radius");
  return p;
}

RobotFactory voronoi(VoronoiVariant variant) {
  return [variant](const RobotSetup& s) -> std::unique_ptr<RobotProtocol> {
    const ProtocolParams params = voronoi_params(variant, s.params);
    const double phase_s = s.random.uniform(0.0, params.period_s);
    return std::make_unique<VoronoiProtocol>(s.host, params, s.context, phase_s, s.log);
  };
}

}  // namespace

void register_builtin_protocols() {
  ProtocolDefinition none = builtin("none", "robots never update (demo scenarios)", {});
  none.make_robot = [](const RobotSetup&) -> std::unique_ptr<RobotProtocol> {
    return std::make_unique<IdleProtocol>();
  };
  register_builtin(std::move(none), {});

  ProtocolDefinition doubling = builtin(
      "radius_doubling",
      "the paper's protocol: DISCOVER rounds with a growing radius until R >= 2d, range decay",
      {period(), reply_timeout(), reply_jitter(),
       ParamSpec::choice("growth", "to_2d", {"to_2d", "double"},
                         "R ← 2d (the paper) or R ← 2R (Cortés)"),
       ParamSpec::choice("criterion", "sensors", {"sensors", "vertices"},
                         "d = farthest reading sensor (paper) or farthest cell vertex (Cortés)"),
       ParamSpec::boolean("shrink_on_stop", false, "on stop set R ← 2d exactly (Cortés)"),
       ParamSpec::integer("decay.patience", 3, 0, 1000000, "updates",
                          "unchanged updates before R shrinks; 0 = never"),
       ParamSpec::real("decay.step", 0.02, ParamRange::non_negative(), "world units", "Δr"),
       ParamSpec::real("decay.min", 0.02, ParamRange::positive(), "world units",
                       "R_min: the floor, and R when nobody reports")});
  doubling.make_robot = voronoi(VoronoiVariant::radius_doubling);
  register_builtin(std::move(doubling), {});

  ProtocolDefinition oracle = builtin(
      "oracle", "the exact cell from true positions, zero messages (the reference)", {period()});
  register_builtin(std::move(oracle),
                   [](const RobotSetup& s, GroundTruth& truth) -> std::unique_ptr<RobotProtocol> {
                     const double period_s = s.params.real("period");
                     const double phase_s = s.random.uniform(0.0, period_s);
                     return std::make_unique<OracleProtocol>(s.host, truth, s.robot, s.context,
                                                             period_s, phase_s, s.log);
                   });

  ProtocolDefinition fixed = builtin(
      "fixed_radius", "one DISCOVER round with a constant radius",
      {period(), reply_timeout(), reply_jitter(),
       ParamSpec::real("radius", 0.3, ParamRange::positive(), "world units", "the constant R")});
  fixed.make_robot = voronoi(VoronoiVariant::fixed_radius);
  register_builtin(std::move(fixed), {});

  ProtocolDefinition gabriel =
      builtin("gabriel", "one round at max range; only Gabriel neighbours bound the cell",
              {period(), reply_timeout(), reply_jitter()});
  gabriel.make_robot = voronoi(VoronoiVariant::gabriel);
  register_builtin(std::move(gabriel), {});
}

}  // namespace masnet::protocols
