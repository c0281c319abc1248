// Large blocks on huge pages (sim/huge_pages.hpp): a block of 4 MiB or more is its own
// 2 MiB-aligned mapping that the kernel is asked to back with huge pages (the `hg` flag of its
// mapping in /proc/self/smaps), and it is unmapped again when freed; smaller blocks stay malloc's,
// whose heap is marked the same way as it grows.
#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sim/huge_pages.hpp"

namespace {
// The VmFlags line of the mapping that holds `address`, from /proc/self/smaps.
std::string mapping_flags(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t first = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> first >> dash >> end && dash == '-' &&
        line.find(':') > line.find(' ')) {
      inside = first <= a && a < end;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return {};
}
}  // namespace

TEST_CASE("A large block is its own aligned mapping marked for huge pages, unmapped when freed",
          "[huge_pages]") {
  if (!masnet::sim::huge_page_blocks_enabled()) {
    // Sanitizer builds keep their own allocator: nothing is mapped here.
    const std::vector<std::byte> large(masnet::sim::kHugePageBlockBytes);
    CHECK(masnet::sim::huge_page_blocks_live() == 0);
    return;
  }
  const std::size_t before = masnet::sim::huge_page_blocks_live();
  {
    std::vector<std::uint64_t> large(masnet::sim::kHugePageBlockBytes / sizeof(std::uint64_t) + 3);
    CHECK(masnet::sim::huge_page_blocks_live() == before + 1);
    CHECK(reinterpret_cast<std::uintptr_t>(large.data()) % (std::size_t{2} << 20) == 0);
    large.back() = 7;  // the tail past the last whole huge page is mapped too
    CHECK(large.back() == 7);
    const std::string flags = mapping_flags(large.data());
    REQUIRE(!flags.empty());
    CHECK(flags.find(" hg") != std::string::npos);
    const auto array = std::make_unique<char[]>(masnet::sim::kHugePageBlockBytes);
    CHECK(masnet::sim::huge_page_blocks_live() == before + 2);
  }
  CHECK(masnet::sim::huge_page_blocks_live() == before);
  // Below the threshold: malloc's, not counted, from a heap that is marked as it grows.
  const std::vector<std::byte> small(masnet::sim::kHugePageBlockBytes - 1);
  CHECK(masnet::sim::huge_page_blocks_live() == before);
  CHECK(mapping_flags(small.data()).find(" hg") != std::string::npos);
}
