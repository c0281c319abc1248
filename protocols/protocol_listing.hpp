#pragma once
// What `masnet protocols` prints: every registered protocol with the keys it declares, as text
// for a terminal or as the markdown table of docs/scenario-reference.md (a test keeps the page
// equal to the built-ins' table).
#include <string>
#include <vector>

#include "protocols/registry.hpp"

namespace masnet::protocols {

/// One block per protocol: its name and summary, then one line per key (type, default, allowed
/// values, unit, meaning).
std::string protocol_listing_text();

/// The `protocol:` keys of `protocols` (default: every registered one) as one markdown table:
/// `kind`, then each key once, with the kinds that declare it.
std::string protocol_table_markdown(const std::vector<const ProtocolDefinition*>& protocols);
std::string protocol_table_markdown();

}  // namespace masnet::protocols
