// Robot groups in formation (`robots.groups`; docs/formations.md, docs/scenario-reference.md).
#include <cmath>
#include <string>

#include "scenarios/loader/scenario_parts.hpp"

namespace masnet::scenarios {

agents::FormationDef read_groups(Section s, std::size_t leaders, const NodeCaps& caps) {
  agents::FormationDef def;
  const std::int64_t size = s.integer("size", 3, 1, kMaxGroupSize);
  if (static_cast<double>(size) * static_cast<double>(leaders) > static_cast<double>(caps.robots)) {
    s.error_at("size", std::to_string(leaders) + " groups of " + std::to_string(size) +
                           " make more than " + std::to_string(caps.robots) + " robots");
    return def;
  }
  def.group_size = static_cast<std::size_t>(size);
  def.shape = s.choice<agents::FormationShape>("shape", agents::FormationShape::wedge,
                                               {{"line", agents::FormationShape::line},
                                                {"wedge", agents::FormationShape::wedge},
                                                {"circle", agents::FormationShape::circle},
                                                {"offsets", agents::FormationShape::offsets}});
  def.spacing_m = s.number("spacing", def.spacing_m, Range::positive());
  if (def.shape == agents::FormationShape::offsets) {
    def.offsets = s.points("offsets");
    const std::size_t wanted = def.followers_per_group();
    if (def.offsets.size() != wanted)
      s.error_at("offsets", "shape offsets needs one offset per follower: size - 1 = " +
                                std::to_string(wanted) + ", got " +
                                std::to_string(def.offsets.size()));
    for (std::size_t k = 0; k < def.offsets.size(); ++k)
      if (def.offsets[k].norm() == 0.0)
        s.error_at("offsets", "offset " + std::to_string(k) +
                                  " is (0, 0): a follower would stand on its leader");
  } else {
    s.reject("offsets", "'offsets' applies to shape offsets");
  }
  def.state_period_s = s.number("state_period", def.state_period_s, Range::time());
  def.range_m = s.number("range", def.range_m, Range::positive());
  def.leader_weight = s.number("leader_weight", def.leader_weight, Range::positive());
  def.neighbour_weight = s.number("neighbour_weight", def.neighbour_weight, Range::non_negative());
  def.margin_m = s.number("margin", def.margin_m, Range::non_negative());
  def.stale_after_s = s.number("stale_after", def.stale_after_s, Range::time());
  s.finish();
  return def;
}

}  // namespace masnet::scenarios
