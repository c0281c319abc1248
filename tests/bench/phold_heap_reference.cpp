// The reference design for masnet's kernel: PHOLD (tests/bench/phold.cpp, identical workload,
// random stream and tie-break, so the same checksum) on a plain 4-ary min-heap of 16-byte POD
// records {time, sequence, LP}, the work done by a direct call. No fingerprint, no cancellation,
// no type-erased actions: the floor a general kernel is measured against (docs/performance.md).
//   masnet_bench_phold_heap_reference --lps=100 --m=10 --events=1e7 [--warmup=N]
#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <vector>

#include "bench_args.hpp"
#include "sim/random.hpp"

using namespace masnet;

namespace {

struct Record {
  std::int64_t time;
  std::uint32_t lp;
  std::uint32_t sequence;  // tie-break: scheduling order (10⁷ events fit in 32 bits)
};
static_assert(sizeof(Record) == 16);

// (time, sequence) as one 128-bit number: one compare, no branch on equal times.
unsigned __int128 order(const Record& r) {
  return (static_cast<unsigned __int128>(static_cast<std::uint64_t>(r.time)) << 64) |
         (static_cast<unsigned __int128>(r.sequence) << 32);
}

// Positions start at 3 and the array at a 64-byte boundary, so the four children of a record
// (positions 4(p-2) .. 4(p-2)+3) fill exactly one cache line.
class FourAryHeap {
 public:
  bool empty() const { return end_ == kRoot; }
  void reserve(std::size_t n) { records_.reset(new (std::align_val_t{64}) Record[n + kRoot]); }
  void push(Record r) {
    std::size_t i = end_++;
    const unsigned __int128 key = order(r);
    while (i > kRoot) {
      const std::size_t parent = i / 4 + 2;
      if (key >= order(records_[parent])) break;
      records_[i] = records_[parent];
      i = parent;
    }
    records_[i] = r;
  }
  Record pop() {
    const Record top = records_[kRoot];
    const Record last = records_[--end_];
    const std::size_t n = end_;
    const unsigned __int128 key = order(last);
    std::size_t i = kRoot;
    for (;;) {
      const std::size_t first = 4 * (i - 2);
      if (first >= n) break;
      std::size_t best = first;
      unsigned __int128 best_key = order(records_[first]);
      if (first + 4 <= n) {  // all four children: selections the compiler turns into cmovs
        for (std::size_t c = first + 1; c < first + 4; ++c) {
          const unsigned __int128 k = order(records_[c]);
          const bool less = k < best_key;
          best = less ? c : best;
          best_key = less ? k : best_key;
        }
      } else {
        for (std::size_t c = first + 1; c < n; ++c) {
          const unsigned __int128 k = order(records_[c]);
          if (k < best_key) {
            best = c;
            best_key = k;
          }
        }
      }
      if (best_key >= key) break;
      records_[i] = records_[best];
      i = best;
    }
    if (i < n) records_[i] = last;
    return top;
  }

 private:
  static constexpr std::size_t kRoot = 3;
  struct AlignedDelete {
    void operator()(Record* p) const { ::operator delete[](p, std::align_val_t{64}); }
  };
  std::unique_ptr<Record[], AlignedDelete> records_;
  std::size_t end_ = kRoot;  // one past the last record
};

struct Phold {
  FourAryHeap heap;
  sim::RandomStream rng{42};
  std::uint32_t lps = 0;
  std::uint32_t next_sequence = 0;
  std::int64_t now = 0;
  bool stopped = false;
  std::vector<std::uint64_t> per_lp;
  std::uint64_t processed = 0, warmup = 0, measured = 0;
  double t0 = 0, t1 = 0;

  std::int64_t delay_ticks() {
    const auto d =
        static_cast<std::int64_t>(-std::log(bench::unit_open_closed(rng.next_u64())) * 1e9);
    return d < 1 ? 1 : d;
  }
  std::uint32_t random_lp() {
    return static_cast<std::uint32_t>((static_cast<unsigned __int128>(rng.next_u64()) * lps) >> 64);
  }
  void schedule(std::int64_t delay, std::uint32_t lp) {
    heap.push(Record{now + delay, lp, next_sequence++});
  }
  void handle(std::uint32_t lp) {
    ++per_lp[lp];
    ++processed;
    if (processed == warmup) t0 = bench::wall_seconds();
    if (processed == warmup + measured) {
      t1 = bench::wall_seconds();
      stopped = true;
      return;
    }
    const std::uint32_t dst = random_lp();
    schedule(delay_ticks(), dst);
  }
  void run() {
    while (!heap.empty() && !stopped) {
      const Record r = heap.pop();
      now = r.time;
      handle(r.lp);
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  bench::Args args{argc, argv};
  Phold p;
  p.lps = static_cast<std::uint32_t>(args.number("lps", 100));
  const auto per_lp = static_cast<std::uint32_t>(args.number("m", 10));
  p.measured = static_cast<std::uint64_t>(args.number("events", 1e7));
  const std::uint64_t population = std::uint64_t{p.lps} * per_lp;
  p.warmup = static_cast<std::uint64_t>(
      args.number("warmup", static_cast<double>(population < 200000 ? 200000 : population)));
  p.per_lp.assign(p.lps, 0);
  p.heap.reserve(population + 16);
  for (std::uint32_t lp = 0; lp < p.lps; ++lp)
    for (std::uint32_t j = 0; j < per_lp; ++j)
      p.schedule(p.delay_ticks(), lp);
  p.run();
  std::uint64_t checksum = bench::kFnvBasis;
  for (std::uint64_t c : p.per_lp)
    checksum = bench::fnv_word(checksum, c);
  const double sec = p.t1 - p.t0;
  std::printf(
      "RESULT name=phold/heap4-reference/pop=%llu metric=%.0f unit=events/s ns_per_event=%.1f "
      "sec=%.3f events=%llu lps=%u m=%u checksum=%016llx\n",
      static_cast<unsigned long long>(population), static_cast<double>(p.measured) / sec,
      sec * 1e9 / static_cast<double>(p.measured), sec, static_cast<unsigned long long>(p.measured),
      p.lps, per_lp, static_cast<unsigned long long>(checksum));
  return 0;
}
