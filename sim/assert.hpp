#pragma once
// Assertions for bugs: kernel invariants such as "time never goes back"
// stay on in optimised test builds (MASNET_ASSERTIONS). User errors never come here; they
// are reported at the scenarios/ boundary with a file position.
#include <stdexcept>
#include <string>

namespace masnet::sim {

/// Thrown instead of aborting when a test installs `throw_on_assertion_failure`.
struct AssertionFailure : std::logic_error {
  using std::logic_error::logic_error;
};

/// What happens on a failed assertion: print and abort (default) or throw
/// `AssertionFailure` (tests that check an invariant is enforced).
enum class AssertionMode { abort, throw_exception };
void set_assertion_mode(AssertionMode mode);

/// `file` and `line` come from __FILE__ and __LINE__: std::source_location is not available to
/// clang 14 with libstdc++ 12 (the fuzz preset's compiler).
[[noreturn]] void assertion_failed(const char* condition, const std::string& message,
                                   const char* file, int line);

}  // namespace masnet::sim

#if defined(MASNET_ASSERTIONS) && MASNET_ASSERTIONS
#define MASNET_ASSERT(cond, message)                                         \
  do {                                                                       \
    if (!(cond)) [[unlikely]]                                                \
      ::masnet::sim::assertion_failed(#cond, (message), __FILE__, __LINE__); \
  } while (false)
#else
#define MASNET_ASSERT(cond, message) \
  do {                               \
    (void)sizeof(cond);              \
  } while (false)
#endif
