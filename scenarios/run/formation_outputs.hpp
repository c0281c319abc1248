#pragma once
// What robot groups did (docs/formations.md, docs/outputs.md "Formations"): formation error,
// distances between groups and within them, how far anyone strayed outside its group's cell,
// and the followers' paths. Observed from outside the model between run chunks.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agents/world.hpp"

namespace masnet::scenarios {

/// One row of formation.csv.
struct FormationSample {
  double t_s = 0;
  double error_mean = 0, error_max = 0;  ///< follower to its slot around the leader now
  double scale_mean = 0;                 ///< the formation scale the leaders' cells allow
  /// Nearest two robots of different groups, and of the same group.
  double min_between_groups = 0, min_within_group = 0;
  /// The farthest any follower (any leader) stood outside its group's cell.
  double outside_follower_max = 0, outside_leader_max = 0;
  std::uint32_t followers_outside = 0;  ///< followers outside their group's cell now
  /// The farthest any follower stood outside the cell it last heard from its leader.
  double outside_known_max = 0;
};

class FormationRecorder {
 public:
  explicit FormationRecorder(agents::World& world);

  void sample();            ///< a formation.csv row now
  void sample_positions();  ///< a followers.csv row per follower now
  void write_formation(const std::string& path) const;
  void write_followers(const std::string& path) const;
  /// The `formation` section of summary.json.
  nlohmann::json summary() const;
  const std::vector<FormationSample>& samples() const { return samples_; }

 private:
  struct FollowerRow {
    double t_s;
    std::uint32_t follower, group;
    net::Vec2 position, slot;
  };
  /// The slot of `follower` around its leader's position now, at the scale its cell allows.
  net::Vec2 slot_now(std::size_t follower) const;

  agents::World& world_;
  std::vector<net::Vec2> offsets_;
  std::vector<FormationSample> samples_;
  std::vector<FollowerRow> rows_;
  std::uint64_t follower_samples_ = 0, outside_samples_ = 0;
};

}  // namespace masnet::scenarios
