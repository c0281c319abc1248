#include "scenarios/cli/protocols_command.hpp"

#include <cstdio>

#include <CLI/CLI.hpp>

#include "protocols/protocol_listing.hpp"

namespace masnet::cli {

CLI::App* add_protocols_subcommand(CLI::App& app, ProtocolsArgs& args) {
  CLI::App* protocols = app.add_subcommand(
      "protocols", "list every protocol (protocol.kind) with its keys, defaults and ranges");
  protocols->add_flag("--markdown", args.markdown,
                      "one table of every key, as in docs/scenario-reference.md");
  return protocols;
}

int run_protocols_command(const ProtocolsArgs& args) {
  const std::string text =
      args.markdown ? protocols::protocol_table_markdown() : protocols::protocol_listing_text();
  std::fputs(text.c_str(), stdout);
  return 0;
}

}  // namespace masnet::cli
