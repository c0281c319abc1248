#include "scenarios/cli/command_line.hpp"

int main(int argc, char** argv) {
  return masnet::cli::main(argc, argv);
}
