#include "scenarios/cli/sweep_command.hpp"

#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <memory>
#include <thread>

#include <ifaddrs.h>
#include <net/if.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include "scenarios/cli/mpi_scope.hpp"
#include "scenarios/run/run_directory.hpp"
#include "scenarios/sweep/sweep.hpp"
#include "sim/cpus.hpp"

#ifdef MASNET_HAVE_MPI
#include <mpi.h>
#endif

namespace masnet::scenarios {
namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;

void print_counts(const SweepCounts& c, const SweepOptions& options, bool quiet) {
  if (!quiet) {
    std::printf(
        "sweep: %zu runs: %zu run now (%zu failed), %zu done before; %.1f s wall with %d job%s × "
        "%d rank%s\n",
        c.total, c.executed, c.failed, c.skipped, c.wall_time_s, options.jobs,
        options.jobs == 1 ? "" : "s", options.ranks, options.ranks == 1 ? "" : "s");
    if (c.foreign > 0)
      std::printf(
          "note: results.sqlite also holds %zu row%s of runs that are not in this sweep (kept, "
          "run_index NULL, left out of results.csv and report.html)\n",
          c.foreign, c.foreign == 1 ? "" : "s");
    const std::filesystem::path dir = std::filesystem::absolute(options.out_dir);
    std::printf("results: %s/{results.sqlite, results.csv, report.html}\n", dir.string().c_str());
  }
  if (c.failed > 0)
    std::fprintf(
        stderr,
        "masnet sweep: %zu run%s failed; their errors are in results.csv (column error) and "
        "report.html; a rerun retries them\n",
        c.failed, c.failed == 1 ? "" : "s");
}

#ifdef MASNET_HAVE_MPI
constexpr int kTagReady = 1;   // worker -> 0: int, its number of threads
constexpr int kTagTask = 2;    // 0 -> worker: long long, a run index, or -1: no more
constexpr int kTagResult = 3;  // worker -> 0: chars, RunResult::to_json() text

// Rank 0: a work queue. Its own threads take runs too; each other rank asks for as many runs
// as it has threads and gets a new one for every result it sends back.
int mpi_root(const SweepDef& sweep, const SweepOptions& options, bool quiet, int size) {
  std::unique_ptr<SweepSession> results;
  int status = 0;
  try {
    results = std::make_unique<SweepSession>(sweep, expand_sweep(sweep), options);
  } catch (const SweepOutputError& e) {
    std::fprintf(stderr, "masnet sweep: %s\n", e.what());
    status = kBadInput;
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (status != 0) return status;

  std::deque<std::size_t> queue(results->pending().begin(), results->pending().end());
  const std::size_t expected = queue.size();
  std::vector<std::size_t> outstanding(static_cast<std::size_t>(size), 0);
  std::vector<bool> stopped(static_cast<std::size_t>(size), false);
  int live = size - 1;
  auto send_task = [&](int rank) {
    if (queue.empty()) return false;
    long long index = static_cast<long long>(queue.front());
    queue.pop_front();
    MPI_Send(&index, 1, MPI_LONG_LONG, rank, kTagTask, MPI_COMM_WORLD);
    ++outstanding[static_cast<std::size_t>(rank)];
    return true;
  };
  auto stop_if_done = [&](int rank) {
    const auto r = static_cast<std::size_t>(rank);
    if (!queue.empty() || outstanding[r] > 0 || stopped[r]) return;
    long long none = -1;
    MPI_Send(&none, 1, MPI_LONG_LONG, rank, kTagTask, MPI_COMM_WORLD);
    stopped[r] = true;
    --live;
  };
  std::size_t received = 0;
  {
    SweepWorkers local(sweep, results->runs(), options.out_dir, options.jobs);
    auto fill_local = [&] {
      while (local.in_flight() < static_cast<std::size_t>(options.jobs) && !queue.empty()) {
        local.submit(queue.front());
        queue.pop_front();
      }
    };
    fill_local();
    while (received < expected || live > 0) {
      bool busy = false;
      for (;;) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (!flag) break;
        busy = true;
        const int source = st.MPI_SOURCE;
        if (st.MPI_TAG == kTagReady) {
          int slots = 0;
          MPI_Recv(&slots, 1, MPI_INT, source, kTagReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          for (int i = 0; i < slots && send_task(source); ++i) {
          }
          stop_if_done(source);
        } else if (st.MPI_TAG == kTagResult) {
          int length = 0;
          MPI_Get_count(&st, MPI_CHAR, &length);
          std::string text(static_cast<std::size_t>(length), '\0');
          MPI_Recv(text.data(), length, MPI_CHAR, source, kTagResult, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
          --outstanding[static_cast<std::size_t>(source)];
          send_task(source);
          stop_if_done(source);
          results->record(RunResult::from_json(nlohmann::json::parse(text)));
          ++received;
        } else {
          throw std::runtime_error("unexpected MPI message tag " + std::to_string(st.MPI_TAG));
        }
      }
      // Local results; when idle this wait is the polling interval.
      while (auto r = local.next(std::chrono::milliseconds(busy ? 0 : 2))) {
        results->record(*r);
        ++received;
        fill_local();
        busy = true;
      }
    }
  }
  const SweepCounts counts = results->finish();
  print_counts(counts, options, quiet);
  int code = counts.exit_code();
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}

int mpi_worker(const SweepDef& sweep, const SweepOptions& options) {
  int status = 0;
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (status != 0) return status;
  const std::vector<RunSpec> runs = expand_sweep(sweep);
  {
    SweepWorkers local(sweep, runs, options.out_dir, options.jobs);
    int slots = options.jobs;
    MPI_Send(&slots, 1, MPI_INT, 0, kTagReady, MPI_COMM_WORLD);
    bool stop = false;
    while (!stop || local.in_flight() > 0) {
      int flag = 0;
      MPI_Iprobe(0, kTagTask, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
      if (flag || (!stop && local.in_flight() == 0)) {  // idle: block until told what to do
        long long index = -1;
        MPI_Recv(&index, 1, MPI_LONG_LONG, 0, kTagTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (index < 0) {
          stop = true;
        } else {
          if (static_cast<std::size_t>(index) >= runs.size())
            throw std::runtime_error("rank 0 sent run " + std::to_string(index) + " of " +
                                     std::to_string(runs.size()));
          local.submit(static_cast<std::size_t>(index));
        }
        continue;
      }
      if (auto r = local.next(std::chrono::milliseconds(2))) {
        const std::string text = r->to_json().dump();
        MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kTagResult,
                 MPI_COMM_WORLD);
      }
    }
  }
  int code = 0;
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}
#endif

// Whether this process can reach any network beyond loopback (false in a private network
// namespace), and whether mpirun was told to keep both its channels on loopback.
bool sees_only_loopback() {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return false;
  bool only = true;
  for (ifaddrs* a = list; a; a = a->ifa_next)
    if (a->ifa_addr && (a->ifa_addr->sa_family == AF_INET || a->ifa_addr->sa_family == AF_INET6) &&
        !(a->ifa_flags & IFF_LOOPBACK) && (a->ifa_flags & IFF_UP))
      only = false;
  freeifaddrs(list);
  return only;
}

bool mpi_told_loopback() {
  auto value = [](const char* name) {
    const char* v = std::getenv(name);
    return std::string(v ? v : "");
  };
  const std::string btl = value("OMPI_MCA_btl");
  // "self,vader" leaves TCP out, "^tcp" excludes it; "^openib" still has it.
  const bool has_tcp = btl.find("tcp") != std::string::npos, excludes = btl.rfind("^", 0) == 0;
  const bool btl_ok = !value("OMPI_MCA_btl_tcp_if_include").empty() ||
                      (!btl.empty() && (excludes ? has_tcp : !has_tcp));
  return !value("OMPI_MCA_oob_tcp_if_include").empty() && btl_ok;
}

int sweep_main(const SweepArgs& args, MpiScope& mpi) {
  const bool root = mpi.rank() == 0;
  // A sweep on one machine needs no network; OpenMPI listens on every interface unless told
  // otherwise (docs/sweeps.md, "MPI on one machine").
  if (mpi.size() > 1 && mpi.all_on_one_host() && root && !args.quiet && !sees_only_loopback() &&
      !mpi_told_loopback())
    std::fprintf(stderr,
                 "masnet sweep: note: all %d ranks run on this host, yet OpenMPI listens on every "
                 "network interface by default. On one machine `masnet sweep --jobs N` needs no "
                 "MPI; to keep mpirun on loopback see docs/sweeps.md (\"MPI on one machine\").\n",
                 mpi.size());
  // Every rank reads the sweep file itself (same file, same expansion); only rank 0 speaks.
  SweepLoad loaded = load_sweep(args.file);
  if (!loaded.sweep) {
    if (root)
      for (const Diagnostic& d : loaded.diagnostics)
        std::fprintf(stderr, "%s\n", d.text().c_str());
    return kBadInput;
  }
  const SweepDef& sweep = *loaded.sweep;
  if (args.list) {
    if (root)
      for (const RunSpec& r : expand_sweep(sweep))
        std::printf("%zu %s %s\n", r.index, r.id.c_str(), r.label.c_str());
    return 0;
  }
  SweepOptions options;
  options.out_dir = args.out.empty() ? sweep.output_dir : args.out;
  options.ranks = mpi.size();
  // Refused before any run: a folder that can never hold results, or one that cannot be
  // written (a read-only mount), must not be found out after hours of simulation.
  std::string problem = forbidden_output_directory(options.out_dir, "--out");
  if (problem.empty()) problem = probe_writable(options.out_dir);
  if (!problem.empty()) {
    if (root) std::fprintf(stderr, "masnet sweep: %s\n", problem.c_str());
    return kBadInput;
  }
  const int cpus = masnet::sim::allowed_cpu_count();
  options.jobs = args.jobs > 0 ? args.jobs : (mpi.size() > 1 ? 1 : cpus);
  // More threads than runs would only sit idle; more than the CPUs this process may use is
  // allowed (runs then share them) but said.
  const std::size_t run_count = expand_sweep(sweep).size();
  if (static_cast<std::size_t>(options.jobs) > run_count)
    options.jobs = static_cast<int>(std::max<std::size_t>(1, run_count));
  if (root && args.jobs > cpus) {
    std::string capped;
    if (options.jobs < args.jobs)
      capped = " (capped at the sweep's " + std::to_string(options.jobs) + " runs)";
    std::fprintf(
        stderr,
        "masnet sweep: warning: --jobs %d is more than the %d CPU%s this process may use; the runs "
        "will share them%s\n",
        args.jobs, cpus, cpus == 1 ? "" : "s", capped.c_str());
  }
  options.force = args.force;
  options.progress = root && !args.quiet && ::isatty(STDERR_FILENO) == 1;
#ifdef MASNET_HAVE_MPI
  if (mpi.size() > 1)
    return root ? mpi_root(sweep, options, args.quiet, mpi.size()) : mpi_worker(sweep, options);
#endif
  SweepCounts counts;
  try {
    counts = run_sweep_locally(sweep, options);
  } catch (const SweepOutputError& e) {
    std::fprintf(stderr, "masnet sweep: %s\n", e.what());
    return kBadInput;
  }
  print_counts(counts, options, args.quiet);
  return counts.exit_code();
}

}  // namespace

bool sweep_has_mpi() {
#ifdef MASNET_HAVE_MPI
  return true;
#else
  return false;
#endif
}

CLI::App* add_sweep_subcommand(CLI::App& app, SweepArgs& args) {
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "run a parameter sweep: many runs of a base scenario, results.sqlite/csv and report.html");
  sweep->add_option("sweep_file", args.file, "sweep file (YAML, docs/sweeps.md)")->required();
  sweep
      ->add_option("--jobs,-j", args.jobs,
                   "worker threads per process (default: all cores; 1 per rank under mpirun)")
      ->check(CLI::NonNegativeNumber);
  sweep->add_option("--out", args.out, "results folder (default: the sweep file's output.dir)");
  sweep->add_flag("--force", args.force,
                  "discard earlier results in the folder and run every run again");
  sweep->add_flag("--list", args.list,
                  "print the runs (index, id, parameters) without running them");
  sweep->add_flag("--quiet", args.quiet, "no progress line and no closing summary");
  sweep->add_flag("--no-mpi", args.no_mpi, "run in this process only, even when started by mpirun");
  sweep->footer(
      "Exit code: 0 all runs ok; 2 bad sweep file or unusable folder; 1 internal error; otherwise "
      "the number of failed runs (at most 125). Finished runs are skipped when a sweep is rerun.");
  return sweep;
}

int run_sweep_command(const SweepArgs& args) {
  MpiScope mpi(!args.no_mpi);
  try {
    return sweep_main(args, mpi);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "masnet sweep: internal error: %s\n", e.what());
    if (mpi.size() > 1) mpi.abort(kInternalError);
    return kInternalError;
  }
}

}  // namespace masnet::scenarios
