#pragma once
// What every command prints and returns: exit codes, and loader diagnostics on stderr.
#include <vector>

#include "scenarios/loader/reader.hpp"

namespace masnet::cli {

inline constexpr int kBadInput = 2;
inline constexpr int kInternalError = 1;

/// Each warning as "LOCATION: warning: MESSAGE" on stderr.
void print_warnings(const std::vector<scenarios::Diagnostic>& warnings);
/// Each diagnostic on stderr; returns kBadInput.
int print_diagnostics(const std::vector<scenarios::Diagnostic>& diagnostics);

}  // namespace masnet::cli
