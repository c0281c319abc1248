#include "ranks/rank_exchange.hpp"

#include <mpi.h>

#include <cstdint>
#include <limits>

#include "sim/assert.hpp"
#include "sim/buffer_capacity.hpp"

namespace masnet::ranks {
namespace {
constexpr int kBytesTag = 0x6d61;  // the exchange's messages; nothing else is sent point to point
}  // namespace

RankExchange::RankExchange() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  const auto ranks = static_cast<std::size_t>(size_);
  send_counts_.assign(ranks, 0);
  receive_counts_.assign(ranks, 0);
  inbox_.assign(ranks, {});
}

sim::Time RankExchange::earliest(sim::Time earliest_here) const {
  const std::int64_t here = sim::to_ns(earliest_here);
  std::int64_t everywhere = here;
  MPI_Allreduce(&here, &everywhere, 1, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD);
  return sim::kTimeZero + sim::Duration{everywhere};
}

const std::vector<std::vector<std::byte>>& RankExchange::exchange(
    const std::vector<std::vector<std::byte>>& outbox) {
  MASNET_ASSERT(outbox.size() == static_cast<std::size_t>(size_), "one outbox entry per rank");
  // The counts first (one int per pair of ranks), then each pair's bytes straight from the
  // outbox into the inbox: no gathered copy on either side (a tile's ledger at the end of a
  // large run is hundreds of megabytes).
  for (int r = 0; r < size_; ++r) {
    const auto k = static_cast<std::size_t>(r);
    const std::size_t count = r == rank_ ? 0 : outbox[k].size();
    MASNET_ASSERT(count <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
                  "a window's exchange with one rank stays under 2 GiB");
    send_counts_[k] = static_cast<int>(count);
    bytes_sent_ += count;
  }
  MPI_Alltoall(send_counts_.data(), 1, MPI_INT, receive_counts_.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<MPI_Request> requests;
  requests.reserve(2 * outbox.size());
  for (int r = 0; r < size_; ++r) {
    const auto k = static_cast<std::size_t>(r);
    inbox_[k].resize(static_cast<std::size_t>(receive_counts_[k]));
    sim::shrink_if_oversized(inbox_[k]);
    if (receive_counts_[k] > 0)
      MPI_Irecv(inbox_[k].data(), receive_counts_[k], MPI_BYTE, r, kBytesTag, MPI_COMM_WORLD,
                &requests.emplace_back());
  }
  for (int r = 0; r < size_; ++r) {
    const auto k = static_cast<std::size_t>(r);
    if (send_counts_[k] > 0)
      MPI_Isend(outbox[k].data(), send_counts_[k], MPI_BYTE, r, kBytesTag, MPI_COMM_WORLD,
                &requests.emplace_back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return inbox_;
}

}  // namespace masnet::ranks
