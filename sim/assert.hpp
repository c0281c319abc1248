#pragma once
// Assertions for bugs: kernel invariants such as "time never goes back"
// stay on in optimised test builds (MASNET_ASSERTIONS). User errors never come here; they
// are reported at the scenarios/ boundary with a file position.
#include <source_location>
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

[[noreturn]] void assertion_failed(const char* condition, const std::string& message,
                                   std::source_location where);

}  // namespace masnet::sim

#if defined(MASNET_ASSERTIONS) && MASNET_ASSERTIONS
#define MASNET_ASSERT(cond, message)                                               \
  do {                                                                             \
    if (!(cond)) [[unlikely]]                                                      \
      ::masnet::sim::assertion_failed(#cond, (message), std::source_location::current()); \
  } while (false)
#else
#define MASNET_ASSERT(cond, message) \
  do {                               \
    (void)sizeof(cond);              \
  } while (false)
#endif
