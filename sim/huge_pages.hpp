#pragma once
// Large blocks on huge pages. A network of a million nodes keeps its per-node records, its
// event queue and its frames in arrays of tens to hundreds of megabytes, read in an order the
// caches cannot follow: with 4 KiB pages nearly every such read also misses the address
// translation cache. A program that links this file (it replaces `operator new` and `operator
// delete`) gets every block of 4 MiB or more as its own mapping, 2 MiB-aligned and marked for
// transparent huge pages (madvise), which the kernel backs with 2 MiB pages where it can; the
// tail of a block past its last whole 2 MiB stays on small pages, so no memory is wasted.
// Smaller blocks are malloc's, from a heap marked the same way as it grows. Off under the
// address and thread sanitizers (they bring their own allocator) and when the environment sets
// MASNET_HUGE_PAGES=0.
// Measured in docs/performance.md, "Huge pages".
#include <cstddef>

namespace masnet::sim {

/// Blocks from this size on are huge-page mappings.
inline constexpr std::size_t kHugePageBlockBytes = std::size_t{4} << 20;

/// Whether this program's large blocks go to huge-page mappings (false under sanitizers and
/// with MASNET_HUGE_PAGES=0). Calling it also links the replacement into a program.
bool huge_page_blocks_enabled();

/// How many large blocks are mapped now (tests).
std::size_t huge_page_blocks_live();

/// A zeroed mapping of `bytes` (sim::ZeroedArray's storage), 2 MiB-aligned and marked for huge
/// pages like the large blocks; nullptr if the system has no memory for it.
void* map_zeroed_region(std::size_t bytes);
void unmap_zeroed_region(void* p, std::size_t bytes);

}  // namespace masnet::sim
