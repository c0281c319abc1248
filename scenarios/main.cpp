#include "scenarios/cli/command_line.hpp"
#include "sim/huge_pages.hpp"

int main(int argc, char** argv) {
  // Links in the huge-page allocation of large blocks (docs/performance.md, "Huge pages").
  static_cast<void>(masnet::sim::huge_page_blocks_enabled());
  return masnet::cli::main(argc, argv);
}
