#pragma once
// Pools of records addressed by index (event slots, frames in flight, delivery batches): a freed
// index is reused before the pool grows, so steady traffic allocates nothing.
#include <cstdint>
#include <vector>

namespace masnet::sim {

/// The index of a free record of `pool`: the last one freed (its old contents left for the
/// caller to overwrite), else a new default-constructed one at the end.
template <class Pool>
std::uint32_t reuse_or_append(std::vector<std::uint32_t>& freed, Pool& pool) {
  if (!freed.empty()) {
    const std::uint32_t index = freed.back();
    freed.pop_back();
    return index;
  }
  pool.emplace_back();
  return static_cast<std::uint32_t>(pool.size() - 1);
}

}  // namespace masnet::sim
