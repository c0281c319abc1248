#pragma once
// The per-configuration statistics of a sweep (docs/sweeps.md, table `statistics`): for each
// configuration (one point of every axis) and each metric, over the configuration's ok runs
// (its seeds): n, mean, sample standard deviation and the 95 % confidence interval of the mean
// with Student's t, so that "which protocol costs least energy per update, with its interval"
// is one query.
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

struct sqlite3;

namespace masnet::scenarios {

struct RunSpec;

/// The 97.5 % quantile of Student's t with `df` degrees of freedom (Boost.Math); NaN for 0.
double student_t_975(std::size_t df);

struct MeanCi {
  std::size_t n = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  /// Sample standard deviation (n − 1 in the denominator); NaN when n < 2.
  double sd = std::numeric_limits<double>::quiet_NaN();
  /// Half-width of the 95 % confidence interval of the mean, t(n-1)·s/√n; NaN when n < 2.
  double half_width = std::numeric_limits<double>::quiet_NaN();
};
MeanCi mean_ci95(const std::vector<double>& values);

/// Metrics derived from a run's summary metrics and added beside them: `energy_per_update_j`
/// (energy_j.total / protocol.updates, when there was an update).
void add_derived_metrics(std::map<std::string, double>& metrics);

/// "radio.loss=0.1 seed=3" -> "radio.loss=0.1": a run's label without its seed.
std::string configuration_label(const std::string& run_label);

/// Rewrites the table `statistics` of the open results database from its `runs` and
/// `metrics` tables, for the runs of `runs` (the current sweep file's expansion).
void write_statistics_table(sqlite3* db, const std::vector<RunSpec>& runs);

}  // namespace masnet::scenarios
