#pragma once
// The pollution field of paper §VI-B (docs/field-models.md): ∂u/∂t = κ∇²u + Σ f δ(x − x(t)) on a
// rectangle, u(x, 0) = 0, discretised on a node grid and advanced by fixed steps. Plain numerics:
// no event kernel here; the World owns one field, steps it from a periodic event, tells it where
// the point injections (sources, robots' sprays) are and reads it at sensor positions. Schemes,
// limits and measured accuracy: docs/field-models.md.
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "net/vec2.hpp"

namespace masnet::agents {

using net::Vec2;

/// `fidelity` reproduces the paper's MATLAB platform Diff-MAS2D; `physical` is a consistent
/// discretisation of the PDE (see docs/field-models.md for both, stencil by stencil).
enum class DiffusionMode {
  fidelity,  ///< RK4 at dt_s; injections and reads snapped to the nearest node, no 1/h² scaling
  physical,  ///< Euler substeps within the positivity limit; bilinear δ of mass f and reads
};

enum class Boundary {
  dirichlet,  ///< u = 0 on ∂Ω: walls absorb pollution
  no_flux,    ///< ∂u/∂n = 0 (ghost-node reflection): mass is conserved
};

struct DiffusionParams {
  DiffusionMode mode = DiffusionMode::fidelity;
  Boundary boundary = Boundary::dirichlet;
  double kappa = 0.01;  ///< diffusivity κ, world units²/s
  int cells = 30;       ///< grid intervals along x; nodes x0 + i·hx, i = 0..cells
  int cells_y = 0;      ///< grid intervals along y; 0 = same as `cells`
  double dt_s = 0.002;  ///< the step `step()` advances by, s
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;  ///< Ω = (x0, x1) × (y0, y1), world units
  /// Clip u at 0 after each (sub)step at the nodes where sprays act. Unset = the mode's default:
  /// physical clips (then u ≥ 0 everywhere, given u ≥ 0 at the start); fidelity does not, like
  /// Diff-MAS2D (its World uses only positive readings).
  std::optional<bool> clip_sprays_at_zero;
  /// Physical mode: upper bound on the forward-Euler substep, s; 0 = the positivity limit only.
  double max_substep_s = 0.0;
};

/// Empty when `params` is usable, else "what is wrong and what is allowed" for the loader.
std::string diffusion_params_error(const DiffusionParams& params);

/// A point injection at one instant: rate > 0 is a source, rate < 0 a spray (sink).
/// Units of rate: physical mode, mass/s (mass = ∫u dA); fidelity mode, u/s added to du/dt at
/// one node (Diff-MAS2D's unscaled coupling; mass-equivalent rate·h²).
struct PointInjection {
  Vec2 position{0.0, 0.0};
  double rate = 0.0;
};

/// What one injection did during one step. Amounts are ∫ rate dt in the caller's rate units
/// (rate·s), integrated with the scheme's own quadrature, signed like the rate.
struct InjectionTally {
  double requested = 0.0;  ///< ∫ rate dt as passed in
  double applied = 0.0;    ///< the part that reached the field (less Dirichlet-wall losses and
                           ///< spray clipped because no pollution was left to neutralise)
};

/// Totals of one step, magnitudes ≥ 0, same units as InjectionTally.
struct StepReport {
  double source_requested = 0.0;
  double source_applied = 0.0;
  double spray_requested = 0.0;
  double spray_applied = 0.0;
  /// One tally per injection, in the order the callback produced them. Points into the field;
  /// valid until the next call of step().
  std::span<const InjectionTally> injections;
  int substeps = 0;  ///< integrator steps taken (fidelity: 1)
};

/// Fills `out` (passed in empty) with the injections acting at time t_s. Called several times per
/// step at the integrator's stage times (non-decreasing), and must produce the same injections in
/// the same order at every call of one step. A lambda capturing one pointer or reference does not
/// allocate when wrapped in std::function.
using InjectionFn = std::function<void(double t_s, std::vector<PointInjection>& out)>;

struct NodeIndex {
  int i = 0;  ///< along x, 0..nx()−1
  int j = 0;  ///< along y, 0..ny()−1
  friend bool operator==(const NodeIndex&, const NodeIndex&) = default;
};

class DiffusionField {
 public:
  /// Precondition: diffusion_params_error(params) is empty (asserted). Starts with u = 0.
  explicit DiffusionField(const DiffusionParams& params);

  /// Advances u from t_s to t_s + dt_s. No allocation once the injection lists have reached their
  /// largest size.
  StepReport step(double t_s, const InjectionFn& injections);
  /// Advances with no injections.
  StepReport step(double t_s);

  /// The field at p: fidelity, the value of the nearest node; physical, bilinear interpolation.
  /// Points outside Ω are clamped onto it.
  double value_at(const Vec2& p) const;
  /// ∫u dA by the trapezoid rule on the nodes: hx·hy·Σ w·u with w = 1 inside, 1/2 on edges, 1/4
  /// at corners — the quadrature the no-flux scheme conserves exactly (up to rounding).
  double mass() const;
  /// max u over the nodes.
  double peak() const;
  /// min u over the nodes (negative only where unclipped sprays acted).
  double minimum() const;
  /// Step bound of the explicit scheme, s. Fidelity: the RK4 stability limit 2.7853/λmax, which
  /// dt_s must not exceed. Physical: the forward-Euler limit 1/(2κ(1/hx² + 1/hy²)) below which
  /// the scheme is positive (and stable); substeps respect it.
  double stable_dt() const { return stable_dt_; }
  /// Integrator steps per step(): fidelity 1; physical ⌈dt_s / min(stable_dt, max_substep)⌉.
  int substeps_per_step() const { return substeps_; }

  /// Grid for heat maps and tests: nodes (i, j) at (x0 + i·hx, y0 + j·hy), row-major values
  /// (index j·nx + i), boundary nodes included (zero under Dirichlet walls).
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double hx() const { return hx_; }
  double hy() const { return hy_; }
  Vec2 node_position(int i, int j) const;
  double value(int i, int j) const { return u_[index(i, j)]; }
  std::span<const double> values() const { return u_; }
  /// The node a point snaps to in fidelity mode: round((x − x0)/hx), halves rounded up (towards
  /// the larger index), clamped to the grid.
  NodeIndex nearest_node(const Vec2& p) const;

  /// Initial condition for tests and restarts: u(node) = f(node position); Dirichlet walls stay 0.
  void set_values(const std::function<double(const Vec2&)>& f);
  const DiffusionParams& params() const { return params_; }

 private:
  // One node's share of one injection: forcing in u/s (touches_), or u added over a (sub)step
  // (spray_touches_).
  struct Touch {
    int node;
    int injection;
    double amount_u;
  };

  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx_ + i; }
  bool is_wall(int i, int j) const;
  template <class NodeOp>
  void sweep(const double* in, NodeOp&& op) const;
  void collect_injections(const InjectionFn& injections, double t_s);
  void account_injections(double weight_dt);
  void apply_touches(double* target, double factor) const;
  void clip_sprays(double* target);
  StepReport step_rk4(double t_s, const InjectionFn& injections);
  StepReport step_euler(double t_s, const InjectionFn& injections);
  StepReport finish_report(int substeps);

  DiffusionParams params_;
  int nx_ = 0, ny_ = 0;
  double hx_ = 0.0, hy_ = 0.0;
  double cx_ = 0.0, cy_ = 0.0;  // κ/hx², κ/hy²
  double stable_dt_ = 0.0;
  int substeps_ = 1;
  bool clip_ = false;
  bool dirichlet_ = true;

  std::vector<double> u_, acc_, stage_a_, stage_b_;  // node arrays, row-major
  std::vector<double> node_scale_;                   // u at a node → rate·s (see Touch)
  std::vector<PointInjection> scratch_;              // what the callback fills
  std::vector<Touch> touches_;                       // forcing of the last collection, u/s
  std::vector<double> kept_;                         // per injection: fraction off the walls
  std::vector<Touch> spray_touches_;                 // this (sub)step's spray contributions
  std::vector<InjectionTally> tallies_;
  double source_requested_ = 0.0, source_applied_ = 0.0;
  double spray_requested_ = 0.0, spray_applied_ = 0.0;
};

}  // namespace masnet::agents
