#pragma once
// The sensors' definitions of a world, shared by every copy of it. A million sensors are 32 MB
// a copy, and a run holds its scenario, its world and, cut into tiles, one world per tile: they
// all read one list. Writing through a copy that shares its list gives that copy its own first
// (copy on write), so a copy never sees another's edits.

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "net/vec2.hpp"

namespace masnet::agents {

struct SensorDef {
  net::Vec2 position{0, 0};
  double area = 0.0;       ///< the part of Ω this sensor stands for (world units²)
  double battery_j = 0.0;  ///< its own battery; 0: the sensors' battery (WorldDef)
};

class SensorList {
 public:
  SensorList() = default;
  SensorList(std::vector<SensorDef> sensors)  // NOLINT(google-explicit-constructor): a list
      : list_(std::make_shared<std::vector<SensorDef>>(std::move(sensors))) {}

  std::size_t size() const { return list_ ? list_->size() : 0; }
  bool empty() const { return size() == 0; }
  const SensorDef* begin() const { return list_ ? list_->data() : nullptr; }
  const SensorDef* end() const { return begin() + size(); }
  const SensorDef* data() const { return begin(); }
  const SensorDef& operator[](std::size_t i) const { return (*list_)[i]; }
  const SensorDef& front() const { return list_->front(); }
  /// Whether this list and `other` read the same storage (no copy between them).
  bool shares_with(const SensorList& other) const { return list_ && list_ == other.list_; }

  // Writers: each detaches this copy first when another copy shares its list. Reading needs no
  // writer, so there is no non-const operator[] that would detach on a mere read.
  SensorDef& edit(std::size_t i) { return own()[i]; }
  void push_back(const SensorDef& sensor) { own().push_back(sensor); }
  void clear() { list_.reset(); }

 private:
  std::vector<SensorDef>& own() {
    if (!list_)
      list_ = std::make_shared<std::vector<SensorDef>>();
    else if (list_.use_count() > 1)
      list_ = std::make_shared<std::vector<SensorDef>>(*list_);
    return *list_;
  }

  // Shared and never written while shared: copies on any thread may read it at once.
  std::shared_ptr<std::vector<SensorDef>> list_;
};

}  // namespace masnet::agents
