#pragma once
// The radio's energy (docs/radio-and-energy.md). `first_order` (Heinzelman et al.):
//   E_tx(k, d) = E_elec·k + ε_fs·k·d²   for d <  d0
//              = E_elec·k + ε_mp·k·d⁴   for d >= d0,    d0 = sqrt(ε_fs / ε_mp)
//   E_rx(k)    = E_elec·k
// with k in bits and d the *transmission range* in metres. At d0 both branches agree, so the
// cost is continuous in d. `states` (a CC2420-like transceiver): power per radio state,
//   E_tx(k) = V·I_tx·k/R,  E_rx(k) = V·I_rx·k/R,  E_idle = V·I_idle·(time alive − time sending
// or receiving), with R the bitrate and I_tx the current of the transmit power level in use.
#include <cmath>
#include <cstdint>

namespace masnet::net {

enum class EnergyModel { first_order, states };

struct EnergyParams {
  EnergyModel model = EnergyModel::first_order;
  double electronics_j_per_bit = 50e-9;        ///< E_elec
  double free_space_j_per_bit_m2 = 10e-12;     ///< ε_fs
  double multipath_j_per_bit_m4 = 0.0013e-12;  ///< ε_mp
  double idle_power_w = 0.0;                   ///< drawn continuously while a node is alive
  double battery_j = 0.0;                      ///< initial battery; 0 means unlimited
  // `states` (CC2420 datasheet figures; idle is its idle mode, the oscillator running).
  double voltage_v = 3.0;
  double tx_level_dbm = 0.0;     ///< the transmit power level in use
  double tx_current_a = 0.0174;  ///< ... and its current
  double rx_current_a = 0.0197;
  double idle_current_a = 0.000426;
  double sleep_current_a = 20e-6;  ///< no protocol puts its radio to sleep yet
  double seconds_per_bit = 1e-6;   ///< 1 / bitrate, set by the radio

  /// Crossover distance d0 = sqrt(ε_fs / ε_mp), metres (≈ 87.7 m with the defaults).
  double crossover_m() const { return std::sqrt(free_space_j_per_bit_m2 / multipath_j_per_bit_m4); }
};

/// Energy to transmit `bits` with range `range_m` metres, joules; `crossover_m` is
/// p.crossover_m(), which a caller sending many frames computes once.
inline double tx_energy_j(const EnergyParams& p, double bits, double range_m, double crossover_m) {
  if (p.model == EnergyModel::states)
    return p.voltage_v * p.tx_current_a * bits * p.seconds_per_bit;
  const double d2 = range_m * range_m;
  const double amplifier =
      range_m < crossover_m ? p.free_space_j_per_bit_m2 * d2 : p.multipath_j_per_bit_m4 * d2 * d2;
  return p.electronics_j_per_bit * bits + amplifier * bits;
}
inline double tx_energy_j(const EnergyParams& p, double bits, double range_m) {
  return tx_energy_j(p, bits, range_m, p.crossover_m());
}

/// Energy to receive `bits`, joules.
inline double rx_energy_j(const EnergyParams& p, double bits) {
  if (p.model == EnergyModel::states)
    return p.voltage_v * p.rx_current_a * bits * p.seconds_per_bit;
  return p.electronics_j_per_bit * bits;
}

}  // namespace masnet::net
