// shrink_if_oversized (sim/buffer_capacity.hpp): a burst's storage is given back, a steady
// buffer's is kept, and the elements stay either way.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "sim/buffer_capacity.hpp"

using masnet::sim::shrink_if_oversized;

TEST_CASE("A buffer left far larger than its contents by a burst gives its storage back", "[sim]") {
  std::vector<std::uint64_t> buffer;
  buffer.reserve(1'000'000);  // 8 MB
  buffer.assign({7, 8, 9});
  shrink_if_oversized(buffer);
  CHECK(buffer.capacity() < 1000);
  CHECK(buffer == std::vector<std::uint64_t>{7, 8, 9});
}

TEST_CASE("A buffer within four times its contents, or small, keeps its storage", "[sim]") {
  std::vector<std::uint64_t> steady;
  steady.reserve(1'000'000);
  steady.resize(300'000);  // capacity 3.3 × the contents: a window's usual swing
  shrink_if_oversized(steady);
  CHECK(steady.capacity() == 1'000'000);
  CHECK(steady.size() == 300'000);

  std::vector<std::uint64_t> small;
  small.reserve(100'000);  // 800 kB: below the 1 MiB kept whatever the contents
  small.push_back(1);
  shrink_if_oversized(small);
  CHECK(small.capacity() == 100'000);
}
