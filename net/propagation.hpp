#pragma once
// Who hears a frame and how well (docs/radio-and-energy.md, "Propagation"):
//   unit_disk     every node within the frame's range hears it, perfectly;
//   log_distance  P_rx = P_tx − PL(d0) − 10·n·log10(d/d0) − X_σ (dBm), X_σ a log-normal
//                 shadowing term fixed per link, and the frame survives with the O-QPSK 2.4 GHz
//                 success probability (1 − BER(SINR))^bits of IEEE 802.15.4 annex E.
#include <cmath>
#include <cstdint>

namespace masnet::net {

enum class PropagationModel { unit_disk, log_distance };

struct PropagationParams {
  PropagationModel model = PropagationModel::unit_disk;
  double exponent = 3.0;             ///< path-loss exponent n
  double reference_loss_db = 40.05;  ///< PL(d0) at d0 = 1 m: free space at 2.4 GHz
  double tx_power_dbm = 0.0;         ///< CC2420's highest level
  double noise_floor_dbm = -100.0;
  double shadowing_sigma_db = 0.0;  ///< σ of the per-link log-normal shadowing
  double sensitivity_dbm = -95.0;   ///< weaker signals are neither heard nor paid for
};

/// Mean path loss at `distance_m` (≥ the 1 m reference distance; closer counts as 1 m), dB.
double path_loss_db(const PropagationParams& p, double distance_m);

/// The shadowing of the link {a, b} (order does not matter) in a run seeded with `seed`: a
/// normal deviate of standard deviation σ, the same for every frame on the link, dB.
double shadowing_db(const PropagationParams& p, std::uint64_t seed, std::uint64_t key_a,
                    std::uint64_t key_b);

/// Bit error rate of IEEE 802.15.4's 2.4 GHz O-QPSK at `sinr` (a power ratio, not dB):
///   BER = 8/15 · 1/16 · Σ_{k=2..16} (−1)^k C(16, k) exp(20·SINR·(1/k − 1)).
double oqpsk_bit_error_rate(double sinr);

/// Probability that a frame of `bits` survives at `sinr`: (1 − BER)^bits.
double oqpsk_frame_success(double sinr, double bits);

inline double dbm_to_mw(double dbm) {
  return std::pow(10.0, dbm / 10.0);
}
inline double mw_to_dbm(double mw) {
  return 10.0 * std::log10(mw);
}

}  // namespace masnet::net
