#include "sim/assert.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace masnet::sim {
namespace {
std::atomic<AssertionMode> g_mode{AssertionMode::abort};
}

void set_assertion_mode(AssertionMode mode) {
  g_mode.store(mode);
}

void assertion_failed(const char* condition, const std::string& message, const char* file,
                      int line) {
  std::string text = std::string(file) + ":" + std::to_string(line) + ": assertion `" + condition +
                     "` failed: " + message;
  if (g_mode.load() == AssertionMode::throw_exception) throw AssertionFailure(text);
  std::fprintf(stderr, "masnet: internal error: %s\n", text.c_str());
  std::abort();
}

}  // namespace masnet::sim
