#pragma once
// What a radio is built with: its level of realism, range, timing, loss, energy model, frame
// sizes, propagation and MAC parameters (docs/radio-and-energy.md).
#include <cstdint>
#include <limits>

#include "net/csma.hpp"
#include "net/energy.hpp"
#include "net/messages.hpp"
#include "net/propagation.hpp"

namespace masnet::net {

/// `ideal`: no contention. `airtime`: a transmitter sends one frame at a time (its frames
/// queue behind each other); receivers are never contended. `collision`: as airtime, and two
/// receptions that overlap at a receiver are both lost (unless one is captured). `csma`: as
/// collision, with IEEE 802.15.4 unslotted CSMA-CA, acknowledgements and retries.
enum class RadioLevel { ideal, airtime, collision, csma };

struct RadioParams {
  double max_range = 1.5;          ///< world units; every range is capped here
  double meters_per_unit = 100.0;  ///< converts ranges to metres for the energy model
  double latency_s = 50e-6;        ///< fixed per-frame delay (processing + propagation)
  double bitrate_bps = 1e6;        ///< airtime = bytes·8 / bitrate
  double jitter_s = 0.0;           ///< extra delay per reception, uniform in [0, jitter)
  RadioLevel level = RadioLevel::airtime;
  double loss = 0.0;  ///< probability that a reception is lost
  /// Book the overhearing of bulk unicasts (row runs into the difference words) on a
  /// second thread. Results are identical (integer sums, in any order, read only after it has
  /// caught up); `masnet run` sets it when the process may run on two processors or more. Not a
  /// scenario key.
  bool overhearing_thread = false;
  /// ... from this many static nodes on: below, the bookkeeping is light and stays inline (the
  /// acoustic scenario's 1 600 sensors ran 3 % slower with the thread).
  std::uint32_t overhearing_thread_min_nodes = 50000;
  EnergyParams energy;
  MessageSizes sizes;
  PropagationParams propagation;  ///< `log_distance` needs level collision or csma
  CsmaParams csma;
  /// Capture (levels collision and csma, log_distance): an overlapped reception survives when
  /// its SINR reaches this many dB. Off when not finite.
  double capture_threshold_db = std::numeric_limits<double>::infinity();

  bool contended() const { return level == RadioLevel::collision || level == RadioLevel::csma; }
};

}  // namespace masnet::net
