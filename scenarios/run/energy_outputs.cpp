#include "scenarios/run/energy_outputs.hpp"

#include <string>

namespace masnet::scenarios {

nlohmann::json energy_by_type(const net::Radio& radio) {
  nlohmann::json by_type = nlohmann::json::object();
  for (std::size_t t = 0; t < net::message_type_count(); ++t) {
    const auto type = static_cast<net::MessageType>(t);
    const double tx = radio.type_tx_energy_j(type), rx = radio.type_rx_energy_j(type);
    if (tx == 0 && rx == 0) continue;
    by_type[std::string(net::name_of(type))] = {{"radio_tx", tx}, {"radio_rx", rx}};
  }
  return by_type;
}

}  // namespace masnet::scenarios
