#pragma once
// A fixed-size array of plain values that starts all zero without writing them. Large arrays are
// mapped anonymous memory: the kernel hands out a page (2 MiB where it gives huge ones:
// sim/huge_pages.hpp) when it is first touched, so the parts a run never writes cost no memory as
// long as nobody reads them either (WrittenSpan, below). A tile's radio keeps counters for every
// node of the network and books only its own band; a run in one piece never books most message
// types at its sensors.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <type_traits>
#include <utility>

#include "sim/huge_pages.hpp"

namespace masnet::sim {

template <class T>
class ZeroedArray {
  // Values whose bytes are the value: zeroed storage holds zeros.
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  /// From this size on the storage is mapped pages; below, calloc's.
  static constexpr std::size_t kMappedBytes = std::size_t{1} << 20;

  ZeroedArray() = default;
  explicit ZeroedArray(std::size_t size) : size_(size) {
    if (size == 0) return;
    if (bytes() >= kMappedBytes) {
      void* p = map_zeroed_region(bytes());
      if (p == nullptr) throw std::bad_alloc();
      data_ = static_cast<T*>(p);
    } else {
      data_ = static_cast<T*>(std::calloc(size, sizeof(T)));
      if (data_ == nullptr) throw std::bad_alloc();
    }
  }
  ~ZeroedArray() { release(); }
  ZeroedArray(const ZeroedArray&) = delete;
  ZeroedArray& operator=(const ZeroedArray&) = delete;
  ZeroedArray(ZeroedArray&& other) noexcept
      : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}
  ZeroedArray& operator=(ZeroedArray&& other) noexcept {
    if (this != &other) {
      release();
      data_ = std::exchange(other.data_, nullptr);
      size_ = std::exchange(other.size_, 0);
    }
    return *this;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  /// Sets element i, which holds zero, to `value`; writes nothing when `value` is zero too, so
  /// copying counters in leaves the pages of those that stayed zero unwritten.
  void fill_in(std::size_t i, const T& value) {
    static constexpr T kZero{};
    if (std::memcmp(&value, &kZero, sizeof(T)) != 0) data_[i] = value;
  }
  /// Zeroes [first, last) (and writes nothing else).
  void zero(std::size_t first, std::size_t last) {
    std::fill(data_ + first, data_ + std::max(first, last), T{});
  }

 private:
  std::size_t bytes() const { return size_ * sizeof(T); }
  void release() {
    if (data_ == nullptr) return;
    if (bytes() >= kMappedBytes)
      unmap_zeroed_region(data_, bytes());
    else
      std::free(data_);
    data_ = nullptr;
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
};

/// The indices [first, end) of a ZeroedArray (or of one row of it) that may hold values other
/// than zero. A pass over every element reads only these: on kernels that map no shared zero
/// page (this project's machine is one), reading a never-written page costs a page as writing
/// it does (docs/performance.md, "Reading costs memory too").
struct WrittenSpan {
  std::uint32_t first = std::numeric_limits<std::uint32_t>::max(), end = 0;

  void add(std::size_t i) {
    first = std::min(first, static_cast<std::uint32_t>(i));
    end = std::max(end, static_cast<std::uint32_t>(i + 1));
  }
  void add(std::size_t from, std::size_t to) {  // [from, to), not empty
    first = std::min(first, static_cast<std::uint32_t>(from));
    end = std::max(end, static_cast<std::uint32_t>(to));
  }
  bool covers(std::size_t i) const { return i >= first && i < end; }
};

}  // namespace masnet::sim
