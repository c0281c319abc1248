#include "scenarios/sweep/sweep_statistics.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include <sqlite3.h>
#include <boost/math/distributions/students_t.hpp>

#include "scenarios/sweep/sweep.hpp"

namespace masnet::scenarios {

double student_t_975(std::size_t df) {
  if (df == 0) return std::numeric_limits<double>::quiet_NaN();
  const boost::math::students_t_distribution<double> t(static_cast<double>(df));
  return boost::math::quantile(t, 0.975);
}

MeanCi mean_ci95(const std::vector<double>& values) {
  MeanCi r;
  r.n = values.size();
  if (r.n == 0) return r;
  double sum = 0;
  for (double v : values)
    sum += v;
  const auto n = static_cast<double>(r.n);
  r.mean = sum / n;
  if (r.n < 2) return r;
  double squares = 0;
  for (double v : values)
    squares += (v - r.mean) * (v - r.mean);
  r.sd = std::sqrt(squares / (n - 1));
  r.half_width = student_t_975(r.n - 1) * r.sd / std::sqrt(n);
  return r;
}

void add_derived_metrics(std::map<std::string, double>& metrics) {
  const auto energy = metrics.find("energy_j.total"), updates = metrics.find("protocol.updates");
  if (energy != metrics.end() && updates != metrics.end() && updates->second > 0)
    metrics["energy_per_update_j"] = energy->second / updates->second;
}

std::string configuration_label(const std::string& run_label) {
  const std::size_t at = run_label.rfind("seed=");
  if (at == std::string::npos) return run_label;
  std::string label = run_label.substr(0, at);
  while (!label.empty() && label.back() == ' ')
    label.pop_back();
  return label.empty() ? "(base)" : label;
}

namespace {

void exec(sqlite3* db, const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string m = message ? message : "unknown error";
    sqlite3_free(message);
    throw std::runtime_error(std::string("results.sqlite: ") + m + " in: " + sql);
  }
}

// A prepared statement, finalised on every path.
struct Prepared {
  sqlite3_stmt* stmt = nullptr;
  Prepared(sqlite3* db, const char* sql) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("results.sqlite: ") + sqlite3_errmsg(db) +
                               " in: " + sql);
  }
  ~Prepared() { sqlite3_finalize(stmt); }
  Prepared(const Prepared&) = delete;
  Prepared& operator=(const Prepared&) = delete;
};

void bind_number(sqlite3_stmt* s, int i, double v) {
  if (std::isfinite(v))
    sqlite3_bind_double(s, i, v);
  else
    sqlite3_bind_null(s, i);
}

}  // namespace

void write_statistics_table(sqlite3* db, const std::vector<RunSpec>& runs) {
  exec(db,
       "CREATE TABLE IF NOT EXISTS statistics (configuration TEXT, parameters TEXT, metric TEXT, n "
       "INTEGER, mean REAL, sd REAL, ci95_low REAL, ci95_high REAL, PRIMARY KEY (configuration, "
       "metric))");
  // Configurations in expansion order; each gathers its ok runs' metrics.
  struct Configuration {
    std::string parameters;
    std::map<std::string, std::vector<double>> values;
  };
  std::vector<std::string> order;
  std::map<std::string, Configuration> configurations;
  {
    Prepared status(db, "SELECT status FROM runs WHERE run_id = ?");
    Prepared metrics(db, "SELECT key, value FROM metrics WHERE run_id = ?");
    for (const RunSpec& run : runs) {
      const std::string label = configuration_label(run.label);
      auto [it, added] = configurations.try_emplace(label);
      if (added) {
        order.push_back(label);
        it->second.parameters = run.parameters.dump();
      }
      sqlite3_bind_text(status.stmt, 1, run.id.c_str(), -1, SQLITE_TRANSIENT);
      const bool ok =
          sqlite3_step(status.stmt) == SQLITE_ROW &&
          std::string(reinterpret_cast<const char*>(sqlite3_column_text(status.stmt, 0))) == "ok";
      sqlite3_reset(status.stmt);
      if (!ok) continue;
      std::map<std::string, double> values;
      sqlite3_bind_text(metrics.stmt, 1, run.id.c_str(), -1, SQLITE_TRANSIENT);
      while (sqlite3_step(metrics.stmt) == SQLITE_ROW)
        if (sqlite3_column_type(metrics.stmt, 1) != SQLITE_NULL)
          values[reinterpret_cast<const char*>(sqlite3_column_text(metrics.stmt, 0))] =
              sqlite3_column_double(metrics.stmt, 1);
      sqlite3_reset(metrics.stmt);
      add_derived_metrics(values);
      for (const auto& [key, value] : values)
        it->second.values[key].push_back(value);
    }
  }
  exec(db, "BEGIN");
  try {
    exec(db, "DELETE FROM statistics");
    Prepared insert(
        db,
        "INSERT INTO statistics (configuration, parameters, metric, n, mean, sd, ci95_low, "
        "ci95_high) VALUES (?,?,?,?,?,?,?,?)");
    for (const std::string& label : order) {
      const Configuration& c = configurations.at(label);
      for (const auto& [metric, values] : c.values) {
        const MeanCi m = mean_ci95(values);
        sqlite3_bind_text(insert.stmt, 1, label.c_str(), -1, SQLITE_TRANSIENT);
        sqlite3_bind_text(insert.stmt, 2, c.parameters.c_str(), -1, SQLITE_TRANSIENT);
        sqlite3_bind_text(insert.stmt, 3, metric.c_str(), -1, SQLITE_TRANSIENT);
        sqlite3_bind_int64(insert.stmt, 4, static_cast<sqlite3_int64>(m.n));
        bind_number(insert.stmt, 5, m.mean);
        bind_number(insert.stmt, 6, m.sd);
        bind_number(insert.stmt, 7, m.mean - m.half_width);
        bind_number(insert.stmt, 8, m.mean + m.half_width);
        if (sqlite3_step(insert.stmt) != SQLITE_DONE)
          throw std::runtime_error(std::string("results.sqlite: ") + sqlite3_errmsg(db));
        sqlite3_reset(insert.stmt);
      }
    }
    exec(db, "COMMIT");
  } catch (...) {
    sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

}  // namespace masnet::scenarios
