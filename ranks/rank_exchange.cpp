#include "ranks/rank_exchange.hpp"

#include <mpi.h>

#include <cstdint>
#include <limits>

#include "sim/assert.hpp"

namespace masnet::ranks {

RankExchange::RankExchange() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  const auto ranks = static_cast<std::size_t>(size_);
  send_counts_.assign(ranks, 0);
  receive_counts_.assign(ranks, 0);
  send_offsets_.assign(ranks, 0);
  receive_offsets_.assign(ranks, 0);
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
  // The counts first (one int per pair of ranks), then the bytes in one call.
  send_buffer_.clear();
  for (int r = 0; r < size_; ++r) {
    const auto k = static_cast<std::size_t>(r);
    const std::size_t count = r == rank_ ? 0 : outbox[k].size();
    MASNET_ASSERT(send_buffer_.size() + count <= std::numeric_limits<int>::max(),
                  "a window's exchange stays under 2 GiB");
    send_offsets_[k] = static_cast<int>(send_buffer_.size());
    send_counts_[k] = static_cast<int>(count);
    if (count > 0) send_buffer_.insert(send_buffer_.end(), outbox[k].begin(), outbox[k].end());
  }
  bytes_sent_ += send_buffer_.size();
  MPI_Alltoall(send_counts_.data(), 1, MPI_INT, receive_counts_.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (std::size_t k = 0; k < receive_counts_.size(); ++k) {
    receive_offsets_[k] = total;
    total += receive_counts_[k];
  }
  receive_buffer_.resize(static_cast<std::size_t>(total));
  MPI_Alltoallv(send_buffer_.data(), send_counts_.data(), send_offsets_.data(), MPI_BYTE,
                receive_buffer_.data(), receive_counts_.data(), receive_offsets_.data(), MPI_BYTE,
                MPI_COMM_WORLD);
  for (std::size_t k = 0; k < inbox_.size(); ++k) {
    const std::byte* from = receive_buffer_.data() + receive_offsets_[k];
    inbox_[k].assign(from, from + receive_counts_[k]);
  }
  return inbox_;
}

}  // namespace masnet::ranks
