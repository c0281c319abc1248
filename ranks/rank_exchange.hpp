#pragma once
// The processes (MPI ranks) of one partitioned run (docs/decisions/0012-partitioned-runs.md).
// Each rank runs its own parts with sim::WindowedRun; between windows the ranks agree on where
// the next window starts — the earliest pending event of any rank — and swap what crossed.
// Both are collective calls: every rank makes the same calls in the same order.
#include <cstddef>
#include <vector>

#include "sim/plain_bytes.hpp"  // what the exchange carries
#include "sim/time.hpp"

namespace masnet::ranks {

class RankExchange {
 public:
  /// Over every process of MPI_COMM_WORLD (MPI initialised by the caller).
  RankExchange();
  int rank() const { return rank_; }
  int size() const { return size_; }

  /// The earliest of every rank's `earliest_here`: the `agree` of sim::WindowedRun::run_until.
  sim::Time earliest(sim::Time earliest_here) const;

  /// Sends `outbox[r]` to rank r (the own entry is not sent) and returns what each rank sent
  /// here, in rank order (the own entry empty). Valid until the next call.
  const std::vector<std::vector<std::byte>>& exchange(
      const std::vector<std::vector<std::byte>>& outbox);

  /// Bytes this rank has sent to other ranks so far.
  std::size_t bytes_sent() const { return bytes_sent_; }

 private:
  int rank_ = 0, size_ = 1;
  std::vector<int> send_counts_, receive_counts_;
  std::vector<std::vector<std::byte>> inbox_;
  std::size_t bytes_sent_ = 0;
};

}  // namespace masnet::ranks
