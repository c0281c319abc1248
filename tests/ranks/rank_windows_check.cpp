// One partitioned run over MPI ranks (ranks/rank_exchange.hpp): the small network of the
// windowed-run tests (tests/sim/small_network.hpp), cut into one part per rank, run in
// conservative windows agreed over the ranks, the messages that crossed swapped between windows.
// Rank 0 gathers every node's record from its home rank and checks it against the run in one
// piece, event for event, and the fingerprint from each node's stream — with and without a node
// that every sender reads at send time (run by every rank). Run under mpirun with 1, 2 or 3
// ranks; exit 0 when every check holds on every rank.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "ranks/rank_exchange.hpp"
#include "sim/windowed_run.hpp"
#include "small_network.hpp"

using namespace masnet;
using namespace masnet::test;

namespace {

struct StreamValue {
  std::uint32_t origin;
  std::uint64_t value;
};

// The first node of each rank's part: kNodes cut as evenly as it goes.
std::uint32_t first_node(int rank, int ranks) {
  return static_cast<std::uint32_t>(rank) * kNodes / static_cast<std::uint32_t>(ranks);
}

// Runs the cut over the ranks; on rank 0, 0 when the merged run equals the one in one piece.
int run_over_ranks(ranks::RankExchange& ex, Watch watch) {
  const int me = ex.rank(), count = ex.size();
  const Time end = time_at(0.01);
  Part part(first_node(me, count), first_node(me + 1, count), watch);
  part.start();
  std::vector<std::vector<std::byte>> outbox(static_cast<std::size_t>(count));
  int too_early = 0;
  std::uint64_t windows = 0;
  {
    sim::WindowedRun run({&part.sim}, Duration{kLookahead}, 1);
    run.run_until(
        end,
        [&](Time window_end) {
          for (auto& box : outbox)
            box.clear();
          // A message goes to every other rank that runs its addressee (its home; every rank
          // for a node run everywhere).
          for (const Message& m : part.outbox) {
            too_early += m.time_ns <= to_ns(window_end);
            for (int r = 0; r < count; ++r) {
              const bool runs = (m.to >= first_node(r, count) && m.to < first_node(r + 1, count)) ||
                                part.everywhere(m.to);
              if (r != me && runs) sim::append_records(outbox[static_cast<std::size_t>(r)], &m, 1);
            }
          }
          part.outbox.clear();
          for (const std::vector<std::byte>& from : ex.exchange(outbox))
            for (const Message& m : sim::records_from<Message>(from))
              part.receive(m);
        },
        [&](Time earliest_here) { return ex.earliest(earliest_here); });
    windows = run.windows();
  }
  // Every node's record and fingerprint stream from its home rank, to rank 0.
  std::vector<Executed> held;
  for (const Executed& e : part.log)
    if (part.holds(e.node)) held.push_back(e);
  std::vector<StreamValue> streams;
  const std::vector<Fingerprint> own = part.sim.origin_streams();
  for (std::uint32_t origin = 0; origin < own.size(); ++origin)
    if ((origin == 0 && me == 0) || (origin > 0 && part.holds(origin - 1)))
      streams.push_back(StreamValue{origin, own[origin].value()});
  for (auto& box : outbox)
    box.clear();
  sim::append_records(outbox[0], held.data(), held.size());
  const std::vector<std::vector<std::byte>> logs = ex.exchange(outbox);
  for (auto& box : outbox)
    box.clear();
  sim::append_records(outbox[0], streams.data(), streams.size());
  const std::vector<std::vector<std::byte>> stream_bytes = ex.exchange(outbox);
  int bad = too_early + part.wrong_owner + (part.sim.now() == end ? 0 : 1);
  if (me != 0) return bad;

  std::vector<Executed> merged = held;
  std::vector<Fingerprint> by_origin(kNodes + 1);
  for (const StreamValue& s : streams)
    by_origin[s.origin] = Fingerprint::resumed(s.value);
  for (int r = 1; r < count; ++r) {
    for (const Executed& e : sim::records_from<Executed>(logs[static_cast<std::size_t>(r)]))
      merged.push_back(e);
    for (const StreamValue& s :
         sim::records_from<StreamValue>(stream_bytes[static_cast<std::size_t>(r)]))
      by_origin[s.origin] = Fingerprint::resumed(s.value);
  }
  std::sort(merged.begin(), merged.end(), in_total_order);
  Part whole(0, kNodes, Watch{watch.node, false});
  whole.start();
  whole.sim.run_until(end);
  const bool same_record = merged == whole.log && whole.log.size() > 1000;
  const bool same_fingerprint =
      combine_origin_streams(by_origin).value() == whole.sim.fingerprint().value();
  std::printf(
      "%d rank(s), watched node %s: %zu events in %llu windows; record %s, fingerprint %s; "
      "%d messages due inside their window\n",
      count, watch.node < kNodes ? "run by every rank" : "none", merged.size(),
      static_cast<unsigned long long>(windows), same_record ? "equal" : "DIFFERENT",
      same_fingerprint ? "equal" : "DIFFERENT", too_early);
  return bad + (same_record ? 0 : 1) + (same_fingerprint ? 0 : 1);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int failures = 0;
  {
    ranks::RankExchange ex;
    failures += run_over_ranks(ex, Watch{});
    failures += run_over_ranks(ex, Watch{4, true});
    int everywhere = 0;
    MPI_Allreduce(&failures, &everywhere, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    failures = everywhere;
  }
  MPI_Finalize();
  return failures == 0 ? 0 : 1;
}
