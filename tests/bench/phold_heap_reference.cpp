// The reference design for masnet's kernel: PHOLD (phold_workload.hpp: the workload, random
// stream and tie-break of tests/bench/phold.cpp, so the same checksum) on a plain 4-ary min-heap of
// 16-byte POD records {time, sequence, LP}, the work done by a direct call. No fingerprint, no
// cancellation, no type-erased actions: the floor a general kernel is measured against
// (docs/performance.md).
//   masnet_bench_phold_heap_reference --lps=100 --m=10 --events=1e7 [--warmup=N]
#include <cstdint>
#include <memory>
#include <new>

#include "phold_workload.hpp"

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
  bench::PholdWorkload work;
  std::uint32_t next_sequence = 0;
  std::int64_t now = 0;
  bool stopped = false;

  explicit Phold(const bench::Args& args) : work(args) {}
  void schedule(std::int64_t delay, std::uint32_t lp) {
    heap.push(Record{now + delay, lp, next_sequence++});
  }
  void handle(std::uint32_t lp) {
    if (work.count(lp)) {
      stopped = true;
      return;
    }
    const std::uint32_t dst = work.random_lp();
    schedule(work.delay_ticks(), dst);
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
  Phold p{bench::Args{argc, argv}};
  p.heap.reserve(p.work.population() + 16);
  for (std::uint32_t lp = 0; lp < p.work.lps; ++lp)
    for (std::uint32_t j = 0; j < p.work.initial_per_lp; ++j)
      p.schedule(p.work.delay_ticks(), lp);
  p.run();
  p.work.print_result("heap4-reference");
  return 0;
}
