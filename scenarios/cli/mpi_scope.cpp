#include "scenarios/cli/mpi_scope.hpp"

#include <sched.h>

#include <cstdlib>

#include "sim/cpus.hpp"

#ifdef MASNET_HAVE_MPI
#include <mpi.h>

#include "ranks/rank_exchange.hpp"
#endif

namespace masnet::scenarios {
namespace {

// Started by mpirun, mpiexec or srun? Only then is MPI initialised: a plain `masnet sweep`
// never touches MPI.
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (const char* v = std::getenv(name); v && *v) return true;
  if (const char* tasks = std::getenv("SLURM_STEP_NUM_TASKS"); tasks && std::atoi(tasks) > 1)
    return true;
  return false;
}

#ifdef MASNET_HAVE_MPI
// The ranks of MPI_COMM_WORLD, one tile each.
class RankTileLink final : public TileLink {
 public:
  unsigned rank() const override { return static_cast<unsigned>(exchange_.rank()); }
  unsigned size() const override { return static_cast<unsigned>(exchange_.size()); }
  sim::Time earliest(sim::Time earliest_here) override { return exchange_.earliest(earliest_here); }
  const std::vector<std::vector<std::byte>>& exchange(
      const std::vector<std::vector<std::byte>>& outbox) override {
    return exchange_.exchange(outbox);
  }

 private:
  ranks::RankExchange exchange_;
};
#endif

}  // namespace

MpiScope::MpiScope(bool allowed) {
#ifdef MASNET_HAVE_MPI
  if (!allowed || !launched_by_mpi()) return;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    // Worker threads never call MPI: only the main thread does (FUNNELED).
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    owned_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#else
  (void)allowed;
#endif
}

MpiScope::~MpiScope() {
#ifdef MASNET_HAVE_MPI
  if (owned_) MPI_Finalize();
#endif
}

MpiScope::Host MpiScope::this_host() const {
  Host host;
  cpu_set_t mine;
  CPU_ZERO(&mine);
  const bool known = sched_getaffinity(0, sizeof(mine), &mine) == 0;
  host.processors = known ? CPU_COUNT(&mine) : sim::allowed_cpu_count();
#ifdef MASNET_HAVE_MPI
  if (size_ <= 1) return host;
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &host.ranks);
  cpu_set_t all;
  MPI_Allreduce(&mine, &all, static_cast<int>(sizeof(cpu_set_t)), MPI_BYTE, MPI_BOR, node);
  if (known) host.processors = CPU_COUNT(&all);
  MPI_Comm_free(&node);
#endif
  return host;
}

bool MpiScope::all(bool ok_here) const {
#ifdef MASNET_HAVE_MPI
  if (size_ <= 1) return ok_here;
  int here = ok_here ? 1 : 0, everywhere = 0;
  MPI_Allreduce(&here, &everywhere, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return everywhere == 1;
#else
  return ok_here;
#endif
}

bool MpiScope::first_rank_says(bool value) const {
#ifdef MASNET_HAVE_MPI
  if (size_ <= 1) return value;
  int said = value ? 1 : 0;
  MPI_Bcast(&said, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return said == 1;
#else
  return value;
#endif
}

std::unique_ptr<TileLink> MpiScope::tile_link() const {
#ifdef MASNET_HAVE_MPI
  if (size_ > 1) return std::make_unique<RankTileLink>();
#endif
  return nullptr;
}

void MpiScope::abort(int code) {
#ifdef MASNET_HAVE_MPI
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace masnet::scenarios
