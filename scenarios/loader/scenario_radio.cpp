// The `radio` section: levels, timing, loss, energy, message sizes, propagation and the
// CSMA-CA knobs (docs/scenario-reference.md, docs/radio-and-energy.md).
#include <sstream>
#include <string>
#include <vector>

#include "scenarios/loader/scenario_parts.hpp"

namespace masnet::scenarios {
namespace {

void read_propagation(Section& radio, net::RadioParams& r) {
  Section p = radio.section("propagation");
  net::PropagationParams& q = r.propagation;
  q.model =
      p.choice<net::PropagationModel>("model", q.model,
                                      {{"unit_disk", net::PropagationModel::unit_disk},
                                       {"log_distance", net::PropagationModel::log_distance}});
  const bool log_distance = q.model == net::PropagationModel::log_distance;
  if (log_distance && !r.contended())
    p.error_at("model", "model 'log_distance' needs radio.level collision or csma");
  const char* why = "applies to model log_distance";
  auto number = [&](const char* key, double& field, Range range) {
    if (log_distance)
      field = p.number(key, field, range);
    else
      p.reject(key, std::string("'") + key + "' " + why);
  };
  number("exponent", q.exponent, Range{1.0, 10.0});
  number("reference_loss", q.reference_loss_db, Range{0.0, 200.0});
  number("tx_power", q.tx_power_dbm, Range{-100.0, 60.0});
  number("noise_floor", q.noise_floor_dbm, Range{-200.0, 0.0});
  number("shadowing_sigma", q.shadowing_sigma_db, Range{0.0, 30.0});
  number("sensitivity", q.sensitivity_dbm, Range{-200.0, 0.0});
  p.finish();
  if (radio.has("capture_threshold")) {
    if (!log_distance)
      radio.reject("capture_threshold",
                   "'capture_threshold' needs radio.propagation.model log_distance");
    else
      r.capture_threshold_db = radio.number("capture_threshold", 0.0, Range{-50.0, 100.0});
  } else {
    radio.mark_known("capture_threshold");
  }
}

std::string shown_number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// CC2420's transmit current per output power level (datasheet, 3 V supply): dBm, A.
const std::vector<Vec2> kCc2420TxCurrents = {{0, 0.0174},   {-1, 0.0165}, {-3, 0.0152},
                                             {-5, 0.0139},  {-7, 0.0125}, {-10, 0.0112},
                                             {-15, 0.0099}, {-25, 0.0085}};

void read_energy(Section e, net::RadioParams& r) {
  net::EnergyParams& p = r.energy;
  p.model = e.choice<net::EnergyModel>(
      "model", p.model,
      {{"first_order", net::EnergyModel::first_order}, {"states", net::EnergyModel::states}});
  const bool states = p.model == net::EnergyModel::states;
  auto number = [&](const char* key, double& field, Range range, bool applies, const char* model) {
    if (applies)
      field = e.number(key, field, range);
    else
      e.reject(key, std::string("'") + key + "' applies to model " + model);
  };
  number("electronics", p.electronics_j_per_bit, Range::non_negative(), !states, "first_order");
  number("free_space", p.free_space_j_per_bit_m2, Range::positive(), !states, "first_order");
  number("multipath", p.multipath_j_per_bit_m4, Range::positive(), !states, "first_order");
  number("idle_power", p.idle_power_w, Range::non_negative(), !states, "first_order");
  number("voltage", p.voltage_v, Range::positive(), states, "states");
  number("rx_current", p.rx_current_a, Range::non_negative(), states, "states");
  number("idle_current", p.idle_current_a, Range::non_negative(), states, "states");
  number("sleep_current", p.sleep_current_a, Range::non_negative(), states, "states");
  if (states) {
    // The transmit power in use picks its level: the lowest level at or above it.
    std::vector<Vec2> levels =
        e.has("tx_currents") ? e.points("tx_currents", 1) : kCc2420TxCurrents;
    const double power_dbm = r.propagation.tx_power_dbm;
    bool found = false;
    for (const Vec2& level : levels) {
      if (!(level.y() >= 0)) {
        e.error_at("tx_currents", "a current must be >= 0 A (got " + shown_number(level.y()) + ")");
        break;
      }
      if (level.x() >= power_dbm && (!found || level.x() < r.energy.tx_level_dbm)) {
        found = true;
        p.tx_level_dbm = level.x();
        p.tx_current_a = level.y();
      }
    }
    if (!found)
      e.error_at("tx_currents",
                 "no level reaches radio.propagation.tx_power " + shown_number(power_dbm) + " dBm");
  } else {
    e.reject("tx_currents", "'tx_currents' applies to model states");
  }
  p.battery_j = e.number("battery", p.battery_j, Range::non_negative());
  e.finish();
}

void read_csma(Section c, net::CsmaParams& m) {
  auto count = [&](const char* key, std::uint32_t& field, std::int64_t lo, std::int64_t hi) {
    field = static_cast<std::uint32_t>(c.integer(key, field, lo, hi));
  };
  count("max_be", m.max_be, 0, 20);
  count("min_be", m.min_be, 0, 20);
  if (m.min_be > m.max_be)
    c.error_at("min_be", "min_be " + std::to_string(m.min_be) + " is above max_be " +
                             std::to_string(m.max_be));
  count("max_backoffs", m.max_backoffs, 0, 100);
  count("max_frame_retries", m.max_frame_retries, 0, 100);
  m.symbol_s = c.number("symbol", m.symbol_s, Range{1e-9, 1.0});
  count("unit_backoff_symbols", m.unit_backoff_symbols, 1, 1'000'000);
  count("cca_symbols", m.cca_symbols, 1, 1'000'000);
  count("turnaround_symbols", m.turnaround_symbols, 0, 1'000'000);
  count("ack_wait_symbols", m.ack_wait_symbols, 1, 1'000'000);
  count("ack_bytes", m.ack_bytes, 1, 65535);
  count("sifs_symbols", m.sifs_symbols, 0, 1'000'000);
  count("lifs_symbols", m.lifs_symbols, 0, 1'000'000);
  count("max_sifs_frame_bytes", m.max_sifs_frame_bytes, 0, 65535);
  count("queue_frames", m.queue_frames, 1, 1'000'000);
  m.carrier_sense_range =
      c.number("carrier_sense_range", m.carrier_sense_range, Range::non_negative());
  m.cca_threshold_dbm = c.number("cca_threshold", m.cca_threshold_dbm, Range{-200.0, 60.0});
  c.finish();
}

}  // namespace

net::RadioParams read_radio(Section s) {
  net::RadioParams r;
  r.max_range = s.number("max_range", r.max_range, Range::positive());
  r.meters_per_unit = s.number("meters_per_unit", r.meters_per_unit, Range::positive());
  r.latency_s = s.number("latency", r.latency_s, Range::delay());
  // At least 1 kbit/s: the airtime of the largest message must fit the clock.
  r.bitrate_bps = s.number("bitrate", r.bitrate_bps, Range{1e3, kMaxMagnitude});
  r.jitter_s = s.number("jitter", r.jitter_s, Range::delay());
  r.level = s.choice<net::RadioLevel>("level", net::RadioLevel::airtime,
                                      {{"ideal", net::RadioLevel::ideal},
                                       {"airtime", net::RadioLevel::airtime},
                                       {"collision", net::RadioLevel::collision},
                                       {"csma", net::RadioLevel::csma}});
  if (r.contended() && r.jitter_s > 0)
    s.error_at("jitter",
               "'jitter' applies to levels ideal and airtime (under contention, frames take "
               "the time the medium gives them; a sensor's reply jitter is protocol.reply_jitter)");
  r.loss = s.number("loss", r.loss, Range{0.0, 1.0, false, true});
  Section z = s.section("sizes");
  auto size = [&](const char* key, std::uint32_t& field) {
    field = static_cast<std::uint32_t>(z.integer(key, field, 0, 65535));
  };
  size("header", r.sizes.header_bytes);
  size("id", r.sizes.id_bytes);
  size("position", r.sizes.position_bytes);
  size("measurement", r.sizes.measurement_bytes);
  size("radius", r.sizes.radius_bytes);
  size("vertex", r.sizes.vertex_bytes);
  size("counter", r.sizes.counter_bytes);
  z.finish();
  read_propagation(s, r);
  read_energy(s.section("energy"), r);
  if (r.level == net::RadioLevel::csma)
    read_csma(s.section("csma"), r.csma);
  else
    s.reject("csma", "'csma' applies to level csma");
  s.finish();
  return r;
}

}  // namespace masnet::scenarios
