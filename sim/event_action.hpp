#pragma once
// The work an event does: a small callable stored inline, so scheduling never allocates
//. Captures must be trivially copyable and at most kCapacity bytes: capture
// ids, indices and a pointer to the owning object, not containers.
#include <cstddef>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

namespace masnet::sim {

class EventAction {
 public:
  static constexpr std::size_t kCapacity = 32;

  EventAction() = default;

  template <class F>
  static EventAction make(F&& f) {
    using Fn = std::decay_t<F>;
    static_assert(sizeof(Fn) <= kCapacity,
                  "event captures more than 32 bytes: capture ids or one pointer instead");
    static_assert(alignof(Fn) <= alignof(std::max_align_t) && alignof(Fn) <= 8,
                  "event capture is over-aligned");
    static_assert(std::is_trivially_copyable_v<Fn> && std::is_trivially_destructible_v<Fn>,
                  "event captures must be trivially copyable (ids, numbers, pointers)");
    EventAction action;
    ::new (static_cast<void*>(action.storage_)) Fn(std::forward<F>(f));
    action.invoke_ = [](void* storage) { (*std::launder(static_cast<Fn*>(storage)))(); };
    return action;
  }

  explicit operator bool() const { return invoke_ != nullptr; }
  void operator()() { invoke_(storage_); }
  void clear() { invoke_ = nullptr; }

 private:
  using Invoke = void (*)(void*);
  Invoke invoke_ = nullptr;
  alignas(8) std::byte storage_[kCapacity];
};

}  // namespace masnet::sim
