#pragma once
// Density fields ρ(s, t) >= 0 sampled by the sensors (docs/field-models.md): acoustic targets
// (paper eq. 3), Gaussian bumps, uniform. The diffusion PDE lives in diffusion_field.hpp and is
// advanced by the world. See docs/field-models.md.
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "agents/diffusion_field.hpp"
#include "agents/targets.hpp"
#include "net/vec2.hpp"

namespace masnet::agents {

enum class FieldKind { uniform, acoustic, gaussian, diffusion };

struct GaussianBump {
  PathDef path;  ///< where the centre is
  double sigma = 0.1;
  double amplitude = 1.0;
};

/// A moving pollution source of strength f(t) = A·e^(−b t) (paper §VI-B: A = 20, b = 1).
struct SourceDef {
  PathDef path;
  double amplitude = 20.0;  ///< A, field units per second
  double decay = 1.0;       ///< b, 1/s
  double rate(double t_s) const { return amplitude * std::exp(-decay * t_s); }
};

struct FieldDef {
  FieldKind kind = FieldKind::uniform;
  double uniform_value = 1.0;
  // acoustic: ρ(s,t) = Σ_k a·max(‖p_k(t) − s‖, d_min)^(−α)
  double amplitude = 1.0;     ///< a
  double alpha = 2.0;         ///< α > 0
  double min_distance = 0.0;  ///< d_min > 0 (the builder sets h/2 by default)
  std::vector<PathDef> targets;
  // gaussian: ρ(s,t) = Σ_b A_b exp(−‖s − c_b(t)‖² / (2σ_b²))
  std::vector<GaussianBump> bumps;
  // diffusion: the PDE of docs/field-models.md with moving point sources (advanced by the world)
  DiffusionParams diffusion;
  std::vector<SourceDef> sources;
};

/// Analytic fields. `value` is called for many sensors at one time, so target positions are
/// cached per time.
class AnalyticField {
 public:
  explicit AnalyticField(const FieldDef& def);

  /// ρ(s, t). Counts readings clamped at d_min (acoustic).
  double value(const Vec2& s, double t_s);
  /// ρ(s, t) without touching the clamp counter (for metrics and figures).
  double peek(const Vec2& s, double t_s);
  /// ρ at the n points (xs[k], y) at time t into out[k] — the same arithmetic as value(), with
  /// the per-call work done once for the row (the oracle's scanline pass).
  void row_values(double y, const double* xs, std::size_t n, double t_s, double* out);

  /// The value everywhere when the field is uniform (lets a row of readings skip the field).
  std::optional<double> uniform_value() const {
    return def_.kind == FieldKind::uniform ? std::optional<double>(def_.uniform_value)
                                           : std::nullopt;
  }

  /// Gaussian bumps that never move: ρ(s) is the same at every time (and reading it counts
  /// nothing), so a sensor's value may be kept.
  bool time_invariant() const;

  std::uint64_t clamped_readings() const { return clamped_; }
  const FieldDef& def() const { return def_; }
  /// Positions of the moving entities (targets or bump centres) at t.
  std::vector<Vec2> sources_at(double t_s) const;

 private:
  double evaluate(const Vec2& s, double t_s, bool count);
  double point_value(const Vec2& s, bool count);  // after move_to
  void move_to(double t_s);
  void sources_into(double t_s, std::vector<Vec2>& out) const;

  FieldDef def_;
  double cached_t_s_ = -1.0;
  std::vector<Vec2> centres_;
  std::uint64_t clamped_ = 0;
};

}  // namespace masnet::agents
