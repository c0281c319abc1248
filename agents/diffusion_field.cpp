#include "agents/diffusion_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "sim/assert.hpp"

namespace masnet::agents {

namespace {

// Where classic RK4's stability polynomial 1 + z + z²/2 + z³/6 + z⁴/24 leaves the unit disk on
// the negative real axis: the real root of z³ + 4z² + 12z + 24 = 0.
constexpr double kRk4RealStability = 2.785293563405282;

int cells_y_of(const DiffusionParams& p) {
  return p.cells_y > 0 ? p.cells_y : p.cells;
}

// Largest eigenvalue magnitude of κ·(5-point Laplacian) on the node grid. The 1-D second
// difference with N intervals has eigenvalues −(4/h²) sin²(kπ/2N): k = 1..N−1 on the interior
// nodes (Dirichlet), k = 0..N with ghost-node reflection (no flux, k = N is the checkerboard).
double lambda_max(const DiffusionParams& p) {
  const int nxc = p.cells, nyc = cells_y_of(p);
  const double hx = (p.x1 - p.x0) / nxc, hy = (p.y1 - p.y0) / nyc;
  double fx = 1.0, fy = 1.0;
  if (p.boundary == Boundary::dirichlet) {
    fx = std::pow(std::cos(std::numbers::pi / (2.0 * nxc)), 2);
    fy = std::pow(std::cos(std::numbers::pi / (2.0 * nyc)), 2);
  }
  return p.kappa * (4.0 * fx / (hx * hx) + 4.0 * fy / (hy * hy));
}

// Fidelity: RK4's stability bound. Physical: forward Euler's positivity bound, where the
// centre coefficient 1 − 2κdt(1/hx² + 1/hy²) of the update reaches 0 (also its no-flux
// stability bound; the Dirichlet one is a hair larger).
double stable_dt_of(const DiffusionParams& p) {
  if (p.kappa == 0.0) return std::numeric_limits<double>::infinity();
  if (p.mode == DiffusionMode::fidelity) return kRk4RealStability / lambda_max(p);
  const double hx = (p.x1 - p.x0) / p.cells, hy = (p.y1 - p.y0) / cells_y_of(p);
  return 1.0 / (2.0 * p.kappa * (1.0 / (hx * hx) + 1.0 / (hy * hy)));
}

}  // namespace

std::string diffusion_params_error(const DiffusionParams& p) {
  std::ostringstream out;
  constexpr int max_cells = 8192;
  if (!(std::isfinite(p.kappa) && p.kappa >= 0.0))
    out << "kappa = " << p.kappa << " must be a finite diffusivity >= 0 (world units²/s)";
  else if (p.cells < 2 || p.cells > max_cells)
    out << "cells = " << p.cells << " must be in 2.." << max_cells;
  else if (p.cells_y != 0 && (p.cells_y < 2 || p.cells_y > max_cells))
    out << "cells_y = " << p.cells_y << " must be 0 (same as cells) or in 2.." << max_cells;
  else if (!(std::isfinite(p.dt_s) && p.dt_s > 0.0))
    out << "dt_s = " << p.dt_s << " must be a finite step > 0 (s)";
  else if (!(std::isfinite(p.x0) && std::isfinite(p.x1) && p.x1 > p.x0))
    out << "the domain needs x0 < x1 (got x0 = " << p.x0 << ", x1 = " << p.x1 << ")";
  else if (!(std::isfinite(p.y0) && std::isfinite(p.y1) && p.y1 > p.y0))
    out << "the domain needs y0 < y1 (got y0 = " << p.y0 << ", y1 = " << p.y1 << ")";
  else if (!(std::isfinite(p.max_substep_s) && p.max_substep_s >= 0.0))
    out << "max_substep_s = " << p.max_substep_s << " must be >= 0 (0 = the stability limit)";
  else if (p.mode == DiffusionMode::fidelity && p.dt_s > stable_dt_of(p))
    out << "dt_s = " << p.dt_s << " exceeds " << stable_dt_of(p)
        << " s, the stability limit of the single RK4 step that fidelity mode takes; use a "
           "smaller dt_s, fewer cells or mode physical (which substeps)";
  return out.str();
}

DiffusionField::DiffusionField(const DiffusionParams& params) : params_(params) {
  MASNET_ASSERT(diffusion_params_error(params).empty(), diffusion_params_error(params));
  const int nxc = params.cells, nyc = cells_y_of(params);
  nx_ = nxc + 1;
  ny_ = nyc + 1;
  hx_ = (params.x1 - params.x0) / nxc;
  hy_ = (params.y1 - params.y0) / nyc;
  cx_ = params.kappa / (hx_ * hx_);
  cy_ = params.kappa / (hy_ * hy_);
  dirichlet_ = params.boundary == Boundary::dirichlet;
  stable_dt_ = stable_dt_of(params);
  clip_ = params.clip_sprays_at_zero.value_or(params.mode == DiffusionMode::physical);
  if (params.mode == DiffusionMode::physical) {
    double limit = stable_dt_;
    if (params.max_substep_s > 0.0) limit = std::min(limit, params.max_substep_s);
    // ⌈dt/limit⌉, then guard the division's rounding so that dt/n never exceeds the limit.
    const double ratio = params.dt_s / limit;
    substeps_ = std::isfinite(ratio) ? std::max(1, static_cast<int>(std::ceil(ratio))) : 1;
    while (params.dt_s / substeps_ > limit)
      ++substeps_;
  }
  const std::size_t n = static_cast<std::size_t>(nx_) * ny_;
  u_.assign(n, 0.0);
  acc_.assign(n, 0.0);
  stage_a_.assign(n, 0.0);
  stage_b_.assign(n, 0.0);
  // Converts u at a node to rate·s: fidelity adds the rate to du/dt unscaled, so 1; physical
  // spreads mass, and a node holds hx·hy·w of it per unit u (w: trapezoid weight).
  node_scale_.assign(n, 1.0);
  if (params.mode == DiffusionMode::physical) {
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const double wx = (i == 0 || i == nx_ - 1) ? 0.5 : 1.0;
        const double wy = (j == 0 || j == ny_ - 1) ? 0.5 : 1.0;
        node_scale_[index(i, j)] = hx_ * hy_ * wx * wy;
      }
  }
}

bool DiffusionField::is_wall(int i, int j) const {
  return dirichlet_ && (i == 0 || j == 0 || i == nx_ - 1 || j == ny_ - 1);
}

Vec2 DiffusionField::node_position(int i, int j) const {
  return {params_.x0 + i * hx_, params_.y0 + j * hy_};
}

NodeIndex DiffusionField::nearest_node(const Vec2& p) const {
  // Scale first and divide by the side length once, so that a node's own coordinate k/N maps
  // back to k exactly in the usual cases; floor(s + 1/2) sends an exact half up.
  const double sx = (p.x() - params_.x0) * (nx_ - 1) / (params_.x1 - params_.x0);
  const double sy = (p.y() - params_.y0) * (ny_ - 1) / (params_.y1 - params_.y0);
  const auto round_clamp = [](double s, int last) {
    const double r = std::floor(s + 0.5);
    if (!(r > 0.0)) return 0;  // also catches NaN
    return r >= last ? last : static_cast<int>(r);
  };
  return {round_clamp(sx, nx_ - 1), round_clamp(sy, ny_ - 1)};
}

namespace {
// Bilinear stencil of a point: the lower-left node of its cell and the offsets in [0, 1].
struct Bilinear {
  int i, j;
  double fx, fy;
};
Bilinear bilinear_of(double sx, double sy, int nxc, int nyc) {
  sx = std::clamp(sx, 0.0, static_cast<double>(nxc));
  sy = std::clamp(sy, 0.0, static_cast<double>(nyc));
  const int i = std::min(static_cast<int>(sx), nxc - 1);
  const int j = std::min(static_cast<int>(sy), nyc - 1);
  return {i, j, sx - i, sy - j};
}
}  // namespace

double DiffusionField::value_at(const Vec2& p) const {
  if (params_.mode == DiffusionMode::fidelity) {
    const NodeIndex k = nearest_node(p);
    return value(k.i, k.j);
  }
  const Bilinear b =
      bilinear_of((p.x() - params_.x0) / hx_, (p.y() - params_.y0) / hy_, nx_ - 1, ny_ - 1);
  const double* row = u_.data() + index(b.i, b.j);
  const double* up = row + nx_;
  return (1.0 - b.fy) * ((1.0 - b.fx) * row[0] + b.fx * row[1]) +
         b.fy * ((1.0 - b.fx) * up[0] + b.fx * up[1]);
}

double DiffusionField::mass() const {
  double total = 0.0;
  for (int j = 0; j < ny_; ++j) {
    const double* row = u_.data() + index(0, j);
    double line = 0.5 * (row[0] + row[nx_ - 1]);
    for (int i = 1; i < nx_ - 1; ++i)
      line += row[i];
    total += (j == 0 || j == ny_ - 1) ? 0.5 * line : line;
  }
  return total * hx_ * hy_;
}

double DiffusionField::peak() const {
  return *std::max_element(u_.begin(), u_.end());
}
double DiffusionField::minimum() const {
  return *std::min_element(u_.begin(), u_.end());
}

void DiffusionField::set_values(const std::function<double(const Vec2&)>& f) {
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      u_[index(i, j)] = is_wall(i, j) ? 0.0 : f(node_position(i, j));
}

// Calls op(node, κ∇²u) for every unknown node: the interior under Dirichlet walls (the walls
// stay 0 in every buffer), all nodes under no-flux walls with the ghost node mirrored
// (u[−1] = u[1]), which is the second-order Neumann condition and conserves the trapezoid mass.
template <class NodeOp>
void DiffusionField::sweep(const double* in, NodeOp&& op) const {
  const int nx = nx_, ny = ny_;
  const double cx = cx_, cy = cy_, cc = -2.0 * (cx_ + cy_);
  if (dirichlet_) {
    for (int j = 1; j < ny - 1; ++j) {
      const std::size_t base = index(0, j);
      const double* row = in + base;
      const double* down = row - nx;
      const double* up = row + nx;
      for (int i = 1; i < nx - 1; ++i)
        op(base + i, cx * (row[i - 1] + row[i + 1]) + cy * (down[i] + up[i]) + cc * row[i]);
    }
    return;
  }
  for (int j = 0; j < ny; ++j) {
    const std::size_t base = index(0, j);
    const double* row = in + base;
    const double* down = in + index(0, j == 0 ? 1 : j - 1);
    const double* up = in + index(0, j == ny - 1 ? ny - 2 : j + 1);
    op(base, cx * (2.0 * row[1]) + cy * (down[0] + up[0]) + cc * row[0]);
    for (int i = 1; i < nx - 1; ++i)
      op(base + i, cx * (row[i - 1] + row[i + 1]) + cy * (down[i] + up[i]) + cc * row[i]);
    const int e = nx - 1;
    op(base + e, cx * (2.0 * row[e - 1]) + cy * (down[e] + up[e]) + cc * row[e]);
  }
}

// Asks for the injections at t_s and turns them into node forcing (u/s) in touches_. Fidelity:
// the whole rate at the nearest node. Physical: rate·φ_k/(hx·hy·w_k) at the four nodes of the
// enclosing cell (φ = bilinear weights), so that hx·hy·Σ w_k·(du_k/dt) = rate exactly. Parts
// landing on Dirichlet walls are dropped (the wall is held at 0) and counted as not applied.
void DiffusionField::collect_injections(const InjectionFn& injections, double t_s) {
  scratch_.clear();
  touches_.clear();
  if (injections) injections(t_s, scratch_);
  if (tallies_.empty()) tallies_.resize(scratch_.size());
  MASNET_ASSERT(tallies_.size() == scratch_.size(),
                "the injection callback changed the number of injections within one step");
  kept_.assign(scratch_.size(), 0.0);  // no allocation once the list has reached its size
  const bool fidelity = params_.mode == DiffusionMode::fidelity;
  for (std::size_t k = 0; k < scratch_.size(); ++k) {
    const PointInjection& inj = scratch_[k];
    MASNET_ASSERT(std::isfinite(inj.rate) && std::isfinite(inj.position.x()) &&
                      std::isfinite(inj.position.y()),
                  "an injection has a non-finite rate or position");
    if (inj.rate == 0.0) continue;
    const auto touch = [&](int i, int j, double weight) {
      if (weight == 0.0 || is_wall(i, j)) return;
      const std::size_t node = index(i, j);
      kept_[k] += weight;
      touches_.push_back(
          {static_cast<int>(node), static_cast<int>(k), inj.rate * weight / node_scale_[node]});
    };
    if (fidelity) {
      const NodeIndex n = nearest_node(inj.position);
      touch(n.i, n.j, 1.0);
    } else {
      const Bilinear b = bilinear_of((inj.position.x() - params_.x0) / hx_,
                                     (inj.position.y() - params_.y0) / hy_, nx_ - 1, ny_ - 1);
      touch(b.i, b.j, (1.0 - b.fx) * (1.0 - b.fy));
      touch(b.i + 1, b.j, b.fx * (1.0 - b.fy));
      touch(b.i, b.j + 1, (1.0 - b.fx) * b.fy);
      touch(b.i + 1, b.j + 1, b.fx * b.fy);
    }
  }
}

// Books the collected injections with quadrature weight `weight_dt` (s): requested and applied
// amounts, and the spray contributions that clipping may give back.
void DiffusionField::account_injections(double weight_dt) {
  for (std::size_t k = 0; k < scratch_.size(); ++k) {
    const double amount = scratch_[k].rate * weight_dt;
    tallies_[k].requested += amount;
    tallies_[k].applied += amount * kept_[k];
    if (amount > 0.0) {
      source_requested_ += amount;
      source_applied_ += amount * kept_[k];
    } else {
      spray_requested_ -= amount;
      spray_applied_ -= amount * kept_[k];
    }
  }
  for (const Touch& t : touches_)
    if (t.amount_u < 0.0) spray_touches_.push_back({t.node, t.injection, t.amount_u * weight_dt});
}

// target[node] += factor · forcing, for this stage's touches.
void DiffusionField::apply_touches(double* target, double factor) const {
  for (const Touch& t : touches_)
    target[t.node] += factor * t.amount_u;
}

// Where sprays acted and u fell below 0, set u = 0 and give the restored amount back to the
// sprays of that node in proportion to what each removed there, so that the report says what
// was really neutralised. In physical mode everything but the sprays keeps u ≥ 0 (forward
// Euler in its positivity limit), so the restored amount never exceeds what the sprays removed.
void DiffusionField::clip_sprays(double* target) {
  // A total order (entries equal in all three keys are interchangeable), so the sums below do
  // not depend on the sort's handling of ties; std::sort does not allocate.
  std::sort(spray_touches_.begin(), spray_touches_.end(), [](const Touch& a, const Touch& b) {
    if (a.node != b.node) return a.node < b.node;
    if (a.injection != b.injection) return a.injection < b.injection;
    return a.amount_u < b.amount_u;
  });
  for (std::size_t first = 0; first < spray_touches_.size();) {
    const int node = spray_touches_[first].node;
    std::size_t last = first;
    double removed_u = 0.0;
    for (; last < spray_touches_.size() && spray_touches_[last].node == node; ++last)
      removed_u -= spray_touches_[last].amount_u;
    if (target[node] < 0.0 && removed_u > 0.0) {
      const double restored_u = -target[node];
      target[node] = 0.0;
      const double scale = node_scale_[static_cast<std::size_t>(node)];
      for (std::size_t e = first; e < last; ++e) {
        const Touch& t = spray_touches_[e];
        const double credit = restored_u * (-t.amount_u / removed_u) * scale;
        tallies_[static_cast<std::size_t>(t.injection)].applied += credit;
        spray_applied_ -= credit;
      }
    }
    first = last;
  }
}

StepReport DiffusionField::step(double t_s) {
  return step(t_s, InjectionFn{});
}

StepReport DiffusionField::step(double t_s, const InjectionFn& injections) {
  tallies_.clear();
  source_requested_ = source_applied_ = spray_requested_ = spray_applied_ = 0.0;
  return params_.mode == DiffusionMode::fidelity ? step_rk4(t_s, injections)
                                                 : step_euler(t_s, injections);
}

// Classic RK4 on du/dt = κ∇²u + g(t), as Diff-MAS2D's method of lines. k_s = κ∇²(stage) + g_s;
// the diffusion part is fused into one sweep per stage, the sparse forcing added afterwards.
// Stages 2 and 3 share the time t + dt/2, so the callback is asked three times.
StepReport DiffusionField::step_rk4(double t_s, const InjectionFn& injections) {
  const double dt = params_.dt_s;
  const double* u = u_.data();
  double* acc = acc_.data();
  double* sa = stage_a_.data();
  double* sb = stage_b_.data();
  spray_touches_.clear();

  collect_injections(injections, t_s);
  account_injections(dt / 6.0);
  sweep(u, [&](std::size_t n, double lap) {
    acc[n] = u[n] + (dt / 6.0) * lap;
    sa[n] = u[n] + (dt / 2.0) * lap;
  });
  apply_touches(acc, dt / 6.0);
  apply_touches(sa, dt / 2.0);

  collect_injections(injections, t_s + 0.5 * dt);
  account_injections(dt / 3.0);
  sweep(sa, [&](std::size_t n, double lap) {
    acc[n] += (dt / 3.0) * lap;
    sb[n] = u[n] + (dt / 2.0) * lap;
  });
  apply_touches(acc, dt / 3.0);
  apply_touches(sb, dt / 2.0);

  account_injections(dt / 3.0);  // stage 3 shares stage 2's time and forcing
  sweep(sb, [&](std::size_t n, double lap) {
    acc[n] += (dt / 3.0) * lap;
    sa[n] = u[n] + dt * lap;
  });
  apply_touches(acc, dt / 3.0);
  apply_touches(sa, dt);

  collect_injections(injections, t_s + dt);
  account_injections(dt / 6.0);
  sweep(sa, [&](std::size_t n, double lap) { acc[n] += (dt / 6.0) * lap; });
  apply_touches(acc, dt / 6.0);

  u_.swap(acc_);
  if (clip_) clip_sprays(u_.data());
  return finish_report(1);
}

// Forward Euler in substeps τ = dt/n ≤ stable_dt: u' = u + τ·κ∇²u + ∫ g over the substep by
// Simpson's rule (callback at the substep's start, middle and end; the end is reused as the next
// start). Every coefficient of the update is ≥ 0 in this limit, so sources alone keep u ≥ 0 and
// clipping at the spray nodes keeps it everywhere; Simpson makes the injected mass exact to
// O(τ⁵) per substep for smooth rates (the mass-conservation test needs 1e-12).
StepReport DiffusionField::step_euler(double t_s, const InjectionFn& injections) {
  const int n_sub = substeps_;
  const double sub_dt = params_.dt_s / n_sub;
  collect_injections(injections, t_s);
  for (int m = 0; m < n_sub; ++m) {
    const double t0 = t_s + m * sub_dt;
    const double t1 = m + 1 == n_sub ? t_s + params_.dt_s : t_s + (m + 1) * sub_dt;
    const double* u = u_.data();
    double* next = acc_.data();
    spray_touches_.clear();
    account_injections(sub_dt / 6.0);  // touches_ hold the forcing at t0
    sweep(u, [&](std::size_t n, double lap) { next[n] = u[n] + sub_dt * lap; });
    apply_touches(next, sub_dt / 6.0);
    collect_injections(injections, 0.5 * (t0 + t1));
    account_injections(sub_dt * (2.0 / 3.0));
    apply_touches(next, sub_dt * (2.0 / 3.0));
    collect_injections(injections, t1);
    account_injections(sub_dt / 6.0);
    apply_touches(next, sub_dt / 6.0);
    u_.swap(acc_);
    if (clip_) clip_sprays(u_.data());
  }
  return finish_report(n_sub);
}

StepReport DiffusionField::finish_report(int substeps) {
  StepReport report;
  report.source_requested = source_requested_;
  report.source_applied = source_applied_;
  report.spray_requested = spray_requested_;
  report.spray_applied = spray_applied_;
  report.injections = tallies_;
  report.substeps = substeps;
  return report;
}

}  // namespace masnet::agents
