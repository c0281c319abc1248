#pragma once
// Buffers reused window after window (the frames a tile exchanges) keep their capacity, so that
// a steady stream of windows touches no fresh pages; but one burst — a million frames sent at
// one instant — must not pin its memory for the rest of the run.
#include <cstddef>
#include <vector>

namespace masnet::sim {

/// Gives back `buffer`'s spare storage, keeping its elements, if it could hold more than four
/// times as many and more than `keep_bytes`. Call after filling it for this round.
template <class T>
void shrink_if_oversized(std::vector<T>& buffer, std::size_t keep_bytes = std::size_t{1} << 20) {
  const std::size_t capacity = buffer.capacity();
  if (capacity > 4 * buffer.size() && capacity * sizeof(T) > keep_bytes) buffer.shrink_to_fit();
}

}  // namespace masnet::sim
