#include "agents/density_field.hpp"

#include <algorithm>
#include <cmath>

namespace masnet::agents {

AnalyticField::AnalyticField(const FieldDef& def) : def_(def) {}

std::vector<Vec2> AnalyticField::sources_at(double t_s) const {
  std::vector<Vec2> out;
  sources_into(t_s, out);
  return out;
}

void AnalyticField::sources_into(double t_s, std::vector<Vec2>& out) const {
  out.clear();
  for (const PathDef& p : def_.targets)
    out.push_back(position_on(p, t_s));
  for (const GaussianBump& b : def_.bumps)
    out.push_back(position_on(b.path, t_s));
  for (const SourceDef& s : def_.sources)
    out.push_back(position_on(s.path, t_s));
}

bool AnalyticField::time_invariant() const {
  if (def_.kind != FieldKind::gaussian) return false;
  // position_on: start + t·0 is start exactly, so a still path's centre is the same at every t.
  return std::all_of(def_.bumps.begin(), def_.bumps.end(), [](const GaussianBump& bump) {
    const PathDef& path = bump.path;
    return path.waypoints.empty() ? path.velocity == Vec2{0, 0}
                                  : path.waypoints.size() == 1 || path.speed <= 0.0;
  });
}

void AnalyticField::move_to(double t_s) {
  if (t_s == cached_t_s_) return;
  sources_into(t_s, centres_);  // in place: a new instant allocates nothing
  cached_t_s_ = t_s;
}

double AnalyticField::value(const Vec2& s, double t_s) {
  return evaluate(s, t_s, true);
}
double AnalyticField::peek(const Vec2& s, double t_s) {
  return evaluate(s, t_s, false);
}

double AnalyticField::evaluate(const Vec2& s, double t_s, bool count) {
  if (def_.kind == FieldKind::acoustic || def_.kind == FieldKind::gaussian) move_to(t_s);
  return point_value(s, count);
}

void AnalyticField::row_values(double y, const double* xs, std::size_t n, double t_s, double* out) {
  if (def_.kind == FieldKind::acoustic || def_.kind == FieldKind::gaussian) move_to(t_s);
  switch (def_.kind) {
    case FieldKind::uniform:
    case FieldKind::diffusion:
      std::fill(out, out + n, def_.uniform_value);
      return;
    case FieldKind::acoustic:
      if (def_.alpha == 2.0) {  // the default, the paper's: point_value's arithmetic, row-wise
        const double d2_min = def_.min_distance * def_.min_distance, amplitude = def_.amplitude;
        std::fill(out, out + n, 0.0);
        std::uint64_t clamped = 0;
        for (std::size_t t = 0; t < def_.targets.size(); ++t) {
          const double cx = centres_[t].x(), dy = centres_[t].y() - y, dy2 = dy * dy;
          const double* __restrict row_xs = xs;
          double* __restrict row_out = out;
          if (dy2 >=
              d2_min) {  // d² >= dy² everywhere on the row: nothing clamps, and this vectorises
            for (std::size_t k = 0; k < n; ++k) {
              const double dx = cx - row_xs[k];
              row_out[k] += amplitude / (dx * dx + dy2);
            }
            continue;
          }
          for (std::size_t k = 0; k < n; ++k) {
            const double dx = cx - row_xs[k];
            const double d2 = dx * dx + dy2;
            clamped += d2 < d2_min ? 1u : 0u;
            row_out[k] += amplitude / (d2 < d2_min ? d2_min : d2);
          }
        }
        clamped_ += clamped;
        return;
      }
      break;
    default:
      break;
  }
  for (std::size_t k = 0; k < n; ++k)
    out[k] = point_value(Vec2{xs[k], y}, true);
}

double AnalyticField::point_value(const Vec2& s, bool count) {
  switch (def_.kind) {
    case FieldKind::uniform:
    case FieldKind::diffusion:
      return def_.uniform_value;
    case FieldKind::acoustic: {
      double rho = 0.0;
      const double d2_min = def_.min_distance * def_.min_distance;
      for (std::size_t k = 0; k < def_.targets.size(); ++k) {
        double d2 = (centres_[k] - s).squaredNorm();
        if (d2 < d2_min) {  // the singularity at the target: clamp, and count it
          d2 = d2_min;
          if (count) ++clamped_;
        }
        // α = 2 (the default) needs no pow: a·d^(−2) = a / d².
        rho += def_.alpha == 2.0 ? def_.amplitude / d2
                                 : def_.amplitude * std::pow(d2, -0.5 * def_.alpha);
      }
      return rho;
    }
    case FieldKind::gaussian: {
      double rho = 0.0;
      for (std::size_t b = 0; b < def_.bumps.size(); ++b) {
        const GaussianBump& bump = def_.bumps[b];
        const double d2 = (centres_[def_.targets.size() + b] - s).squaredNorm();
        rho += bump.amplitude * std::exp(-d2 / (2.0 * bump.sigma * bump.sigma));
      }
      return rho;
    }
  }
  return 0.0;
}

}  // namespace masnet::agents
