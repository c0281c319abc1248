#pragma once
// IEEE 802.15.4 unslotted CSMA-CA (docs/radio-and-energy.md, "Medium access"): the knobs, with
// the standard's defaults for the 2.4 GHz O-QPSK PHY (62.5 ksymbol/s, 250 kbit/s).
#include <cstdint>

namespace masnet::net {

struct CsmaParams {
  std::uint32_t min_be = 3;             ///< macMinBE
  std::uint32_t max_be = 5;             ///< macMaxBE
  std::uint32_t max_backoffs = 4;       ///< macMaxCSMABackoffs
  std::uint32_t max_frame_retries = 3;  ///< macMaxFrameRetries (acknowledged unicasts)
  double symbol_s = 16e-6;
  std::uint32_t unit_backoff_symbols = 20;  ///< aUnitBackoffPeriod
  std::uint32_t cca_symbols = 8;            ///< clear-channel assessment
  std::uint32_t turnaround_symbols = 12;    ///< aTurnaroundTime (RX↔TX)
  std::uint32_t ack_wait_symbols = 54;      ///< macAckWaitDuration
  std::uint32_t ack_bytes = 11;             ///< an ACK on the air: 6 PHY + 5 MAC bytes
  std::uint32_t sifs_symbols = 12;          ///< macSIFSPeriod
  std::uint32_t lifs_symbols = 40;          ///< macLIFSPeriod
  std::uint32_t max_sifs_frame_bytes = 18;  ///< aMaxSIFSFrameSize
  std::uint32_t queue_frames = 32;          ///< a node's queue; frames beyond are dropped
  /// Unit disk: a node senses transmitters within this range (0: the radio's max_range).
  double carrier_sense_range = 0.0;
  /// Log-distance: the channel is busy at or above this received power (CC2420's default).
  double cca_threshold_dbm = -77.0;
};

/// Per message type (or per sending node): what contention did to the frames. Filled by the
/// `collision` and `csma` levels; a reception is an intended one (the addressee of a unicast,
/// any hearer of a broadcast).
struct ContentionCounters {
  std::uint64_t transmissions = 0;    ///< frames on the air: first attempts and retries
  std::uint64_t delivered = 0;        ///< receptions handed to a node (duplicates excluded)
  std::uint64_t collided = 0;         ///< receptions lost to an overlapping frame
  std::uint64_t channel_lost = 0;     ///< receptions lost to the packet error rate or `loss`
  std::uint64_t dropped = 0;          ///< frames given up: no ACK, channel busy, queue full
  std::uint64_t access_failures = 0;  ///< ... of which the channel stayed busy
  std::uint64_t queue_drops = 0;      ///< ... of which the queue was full
  std::uint64_t retries = 0;          ///< retransmissions after a missing ACK
  std::uint64_t backoffs = 0;         ///< random backoffs drawn
  std::uint64_t acks = 0;             ///< acknowledgements sent
  double latency_sum_s = 0.0;         ///< send → delivery, summed over `delivered`

  ContentionCounters& operator+=(const ContentionCounters& o);
};

}  // namespace masnet::net
