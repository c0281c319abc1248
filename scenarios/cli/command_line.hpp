#pragma once
// The `masnet` command line: run, validate, render, sweep and protocols
// (docs/scenario-reference.md, docs/outputs.md, docs/sweeps.md). A program of one's own registers
// its protocols first and then hands over to masnet::cli::main, which serves them like the built-in
// ones.
namespace masnet::cli {

/// Parses the arguments and runs the command. Exit codes: 0 success, 2 bad input, 1 internal
/// error or a failed write; `sweep` adds its own (docs/sweeps.md).
int main(int argc, char** argv);

}  // namespace masnet::cli
