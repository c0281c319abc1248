#include "scenarios/cli/command_output.hpp"

#include <cstdio>

namespace masnet::cli {
using scenarios::Diagnostic;

void print_warnings(const std::vector<Diagnostic>& warnings) {
  for (const Diagnostic& w : warnings)
    std::fprintf(stderr, "%s: warning: %s\n", w.location.c_str(), w.message.c_str());
}

int print_diagnostics(const std::vector<Diagnostic>& diagnostics) {
  for (const Diagnostic& d : diagnostics)
    std::fprintf(stderr, "%s\n", d.text().c_str());
  return kBadInput;
}

}  // namespace masnet::cli
