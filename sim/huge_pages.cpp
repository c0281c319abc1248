#include "sim/huge_pages.hpp"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <vector>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MASNET_SANITIZED_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define MASNET_SANITIZED_ALLOCATOR 1
#endif
#endif

namespace masnet::sim {
namespace {

constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
constexpr std::size_t kSmallPageBytes = 4096;

struct Block {
  std::uintptr_t start;
  std::size_t length_bytes;
};
// The live large blocks. Few (tens to hundreds) and looked up only for 2 MiB-aligned pointers,
// which malloc almost never returns: a plain list under a lock.
struct Registry {
  std::mutex mutex;
  std::vector<Block> blocks;
};
Registry& registry() {
  // Never destroyed: a static object's destructor may free a large block after exit begins.
  static Registry* const instance = new Registry;
  return *instance;
}

bool enabled_here() {
#ifdef MASNET_SANITIZED_ALLOCATOR
  return false;
#else
  static const bool enabled = [] {
    const char* value = std::getenv("MASNET_HUGE_PAGES");
    return value == nullptr || std::strcmp(value, "0") != 0;
  }();
  return enabled;
#endif
}

std::size_t page_rounded(std::size_t bytes) {
  return (bytes + kSmallPageBytes - 1) & ~(kSmallPageBytes - 1);
}

// A 2 MiB-aligned zeroed mapping of `length` bytes (a multiple of the small page), marked for
// huge pages when `huge`.
void* map_aligned(std::size_t length, bool huge) {
  // One huge page more than needed, then the unaligned head and the surplus tail cut off.
  void* raw = ::mmap(nullptr, length + kHugePageBytes, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) return nullptr;
  const auto base = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t start = (base + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t end = base + length + kHugePageBytes;
  if (start > base) ::munmap(raw, start - base);
  if (end > start + length) ::munmap(reinterpret_cast<void*>(start + length), end - start - length);
  // Refused where the kernel has no transparent huge pages: the block is still good memory.
  if (huge) ::madvise(reinterpret_cast<void*>(start), length, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(start);
}

// The small blocks: malloc's heap marked for huge pages as it grows, which is what glibc's own
// `glibc.malloc.hugetlb` tunable does, but that one can only be set before the process starts.
// The heap grows and shrinks in large steps so that its growth is rare and whole huge pages fit,
// and blocks below the large ones come from the heap, not from mappings of their own.
std::atomic<std::uintptr_t> heap_marked_end{0};

[[maybe_unused]] bool configure_heap() {
  ::mallopt(M_MMAP_THRESHOLD, static_cast<int>(kHugePageBlockBytes));
  ::mallopt(M_TOP_PAD, 64 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 128 << 20);
  heap_marked_end.store(reinterpret_cast<std::uintptr_t>(::sbrk(0)), std::memory_order_relaxed);
  return true;
}

[[maybe_unused]] void mark_heap_growth() {
  static const bool configured = configure_heap();
  static_cast<void>(configured);
  const auto end = reinterpret_cast<std::uintptr_t>(::sbrk(0));  // no system call
  std::uintptr_t marked = heap_marked_end.load(std::memory_order_relaxed);
  if (end == marked || !heap_marked_end.compare_exchange_strong(marked, end)) return;
  if (end < marked) return;  // trimmed: what grows again is marked then
  const std::uintptr_t from = marked & ~(kSmallPageBytes - 1);
  ::madvise(reinterpret_cast<void*>(from), end - from, MADV_HUGEPAGE);
}

[[maybe_unused]] void* map_block(std::size_t bytes) {
  const std::size_t length = page_rounded(bytes);
  void* mapped = map_aligned(length, true);
  if (mapped == nullptr) return nullptr;
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  Registry& r = registry();
  try {
    const std::lock_guard lock(r.mutex);
    r.blocks.push_back({start, length});
  } catch (const std::bad_alloc&) {
    ::munmap(reinterpret_cast<void*>(start), length);
    return nullptr;
  }
  return reinterpret_cast<void*>(start);
}

/// Unmaps `p` if it is one of the large blocks; false if it came from malloc.
[[maybe_unused]] bool unmap_block(void* p) {
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  if ((address & (kHugePageBytes - 1)) != 0) return false;  // every large block is aligned
  std::size_t length = 0;
  {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    for (Block& block : r.blocks)
      if (block.start == address) {
        length = block.length_bytes;
        block = r.blocks.back();
        r.blocks.pop_back();
        break;
      }
  }
  if (length == 0) return false;
  ::munmap(p, length);
  return true;
}

}  // namespace

bool huge_page_blocks_enabled() {
  return enabled_here();
}

void* map_zeroed_region(std::size_t bytes) {
  return map_aligned(page_rounded(bytes), enabled_here());
}

void unmap_zeroed_region(void* p, std::size_t bytes) {
  ::munmap(p, page_rounded(bytes));
}

std::size_t huge_page_blocks_live() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  return r.blocks.size();
}

}  // namespace masnet::sim

#ifndef MASNET_SANITIZED_ALLOCATOR
// The replaceable allocation functions (the array and nothrow forms call these).
void* operator new(std::size_t bytes) {
  const bool huge = masnet::sim::enabled_here();
  if (huge && bytes >= masnet::sim::kHugePageBlockBytes)
    if (void* p = masnet::sim::map_block(bytes)) return p;
  for (;;) {
    if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) {
      if (huge) masnet::sim::mark_heap_growth();
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

void operator delete(void* p) noexcept {
  if (p != nullptr && !masnet::sim::unmap_block(p)) std::free(p);
}

void operator delete(void* p, std::size_t) noexcept {
  operator delete(p);
}
#endif
