#pragma once
// The first-order radio energy model (Heinzelman et al.; docs/radio-and-energy.md):
//   E_tx(k, d) = E_elec·k + ε_fs·k·d²   for d <  d0
//              = E_elec·k + ε_mp·k·d⁴   for d >= d0,    d0 = sqrt(ε_fs / ε_mp)
//   E_rx(k)    = E_elec·k
// with k in bits and d the *transmission range* in metres. At d0 both branches agree, so the
// cost is continuous in d.
#include <cmath>
#include <cstdint>

namespace masnet::net {

struct EnergyParams {
  double electronics_j_per_bit = 50e-9;        ///< E_elec
  double free_space_j_per_bit_m2 = 10e-12;     ///< ε_fs
  double multipath_j_per_bit_m4 = 0.0013e-12;  ///< ε_mp
  double idle_power_w = 0.0;                   ///< drawn continuously while a node is alive
  double battery_j = 0.0;                      ///< initial battery; 0 means unlimited

  /// Crossover distance d0 = sqrt(ε_fs / ε_mp), metres (≈ 87.7 m with the defaults).
  double crossover_m() const { return std::sqrt(free_space_j_per_bit_m2 / multipath_j_per_bit_m4); }
};

/// Energy to transmit `bits` with range `range_m` metres, joules; `crossover_m` is
/// p.crossover_m(), which a caller sending many frames computes once.
inline double tx_energy_j(const EnergyParams& p, double bits, double range_m, double crossover_m) {
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
  return p.electronics_j_per_bit * bits;
}

}  // namespace masnet::net
