#include "scenarios/run/curve_summary.hpp"

namespace masnet::scenarios {

nlohmann::json curve_summary(const std::vector<Sample>& samples, double Sample::*value,
                             double threshold_or_zero) {
  std::size_t peak_at = 0;
  for (std::size_t k = 0; k < samples.size(); ++k)
    if (samples[k].*value > samples[peak_at].*value) peak_at = k;
  const double peak = samples[peak_at].*value, final = samples.back().*value;
  bool monotonic = true;
  for (std::size_t k = peak_at + 1; k < samples.size(); ++k)
    if (samples[k].*value > samples[k - 1].*value) monotonic = false;
  const double threshold = threshold_or_zero > 0 ? threshold_or_zero : 0.05 * peak;
  nlohmann::json clean = nullptr;
  for (std::size_t k = peak_at; k < samples.size(); ++k)
    if (samples[k].*value < threshold) {
      clean = samples[k].t_s;
      break;
    }
  return {{"peak", peak},
          {"peak_time_s", samples[peak_at].t_s},
          {"final", final},
          {"final_over_peak", peak > 0 ? final / peak : 0.0},
          {"monotonic_after_peak", monotonic},
          {"clean_threshold", threshold},
          {"time_to_clean_s", clean}};
}
}  // namespace masnet::scenarios
