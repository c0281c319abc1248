#pragma once
// `masnet protocols`: every protocol this program knows — the built-ins and those it registered
// itself (docs/protocol-api.md) — with the keys each declares.
namespace CLI {
class App;
}

namespace masnet::cli {

struct ProtocolsArgs {
  bool markdown = false;
};

CLI::App* add_protocols_subcommand(CLI::App& app, ProtocolsArgs& args);
int run_protocols_command(const ProtocolsArgs& args);

}  // namespace masnet::cli
