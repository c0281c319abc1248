// The pollution field solver (agents/diffusion_field): Diff-MAS2D's nodal coupling in fidelity
// mode, exact discrete conservation and decay laws, the analytic heat kernel with second-order
// convergence in physical mode, and the spray accounting the World relies on.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "agents/diffusion_field.hpp"

namespace {

using masnet::agents::Boundary;
using masnet::agents::DiffusionField;
using masnet::agents::DiffusionMode;
using masnet::agents::DiffusionParams;
using masnet::agents::NodeIndex;
using masnet::agents::PointInjection;
using masnet::agents::Vec2;

constexpr double pi = std::numbers::pi;

DiffusionParams physical(int cells, Boundary boundary) {
  DiffusionParams p;
  p.mode = DiffusionMode::physical;
  p.boundary = boundary;
  p.cells = cells;
  return p;
}

// Heat kernel on the no-flux unit interval by the method of images: a Gaussian of variance s2
// centred at c, mirrored at 0 and 1 (images at ±c + 2m); |m| ≤ 3 is exact to rounding here.
double neumann_gaussian_1d(double x, double c, double s2) {
  double sum = 0.0;
  for (int m = -3; m <= 3; ++m) {
    const double a = x - c - 2.0 * m, b = x + c - 2.0 * m;
    sum += std::exp(-a * a / (2.0 * s2)) + std::exp(-b * b / (2.0 * s2));
  }
  return sum / std::sqrt(2.0 * pi * s2);
}

// Classic RK4 stability polynomial (the amplification of a decaying mode e^{−λt}).
double rk4_amplification(double z) {
  return 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
}

}  // namespace

TEST_CASE("A source at (0.21, 0.79) snaps to node (6, 24) of the paper's 30-interval grid",
          "[agents]") {
  DiffusionField field(DiffusionParams{});
  REQUIRE(field.nx() == 31);
  REQUIRE(field.ny() == 31);
  CHECK(field.nearest_node({0.21, 0.79}) == NodeIndex{6, 24});  // 6.3 → 6, 23.7 → 24
  CHECK(field.nearest_node({0.8, 0.21}) == NodeIndex{24, 6});   // 24.0 → 24, 6.3 → 6
  // Points outside Ω clamp onto the nearest wall node.
  CHECK(field.nearest_node({-0.3, 1.2}) == NodeIndex{0, 30});

  // One step with a source there changes that node first and most.
  const auto source = [](double, std::vector<PointInjection>& out) {
    out.push_back({{0.21, 0.79}, 20.0});
  };
  field.step(0.0, source);
  CHECK(field.peak() == field.value(6, 24));
  CHECK(field.value_at({0.21, 0.79}) == field.value(6, 24));
  CHECK(field.value_at({0.19, 0.81}) == field.value(6, 24));  // 5.7 → 6, 24.3 → 24
}

TEST_CASE("An exact half-way point snaps to the node with the larger index", "[agents]") {
  DiffusionParams p;
  p.cells = 4;  // h = 1/4: 0.125 and 0.375 are exactly half-way and exact in binary
  DiffusionField field(p);
  CHECK(field.nearest_node({0.125, 0.375}) == NodeIndex{1, 2});
  CHECK(field.nearest_node({0.625, 0.875}) == NodeIndex{3, 4});
}

TEST_CASE("Fidelity mode reproduces Diff-MAS2D's nodal coupling on a 3 x 3 interior grid",
          "[agents]") {
  // cells = 4 under Dirichlet walls: 3 × 3 unknowns. A unit source at the centre node adds 1 to
  // du/dt there — no 1/h² — and one RK4 step from u = 0 is done here by hand on the three node
  // classes the symmetry leaves: centre C, edge-adjacent E (4 nodes), corner D (4 nodes).
  // With a = κ/h², the 5-point Laplacian on them is
  //   (LC, LE, LD) = (4aE − 4aC,  aC + 2aD − 4aE,  2aE − 4aD).
  const double kappa = GENERATE(0.01, 1.0);
  const double dt = kappa == 1.0 ? 0.01 : 0.002;  // κ = 1 makes the high-order terms visible
  DiffusionParams p;
  p.cells = 4;
  p.kappa = kappa;
  p.dt_s = dt;
  DiffusionField field(p);
  field.step(0.0, [](double, std::vector<PointInjection>& out) {
    out.push_back({{0.5, 0.5}, 1.0});
  });

  const double a = kappa * 16.0;
  struct Classes {
    double c, e, d;
  };
  const auto deriv = [a](Classes y) {  // κ∇²y + g, g = 1 at the centre
    return Classes{4 * a * y.e - 4 * a * y.c + 1.0, a * y.c + 2 * a * y.d - 4 * a * y.e,
                   2 * a * y.e - 4 * a * y.d};
  };
  const Classes k1 = deriv({0, 0, 0});
  const Classes k2 = deriv({dt / 2 * k1.c, dt / 2 * k1.e, dt / 2 * k1.d});
  const Classes k3 = deriv({dt / 2 * k2.c, dt / 2 * k2.e, dt / 2 * k2.d});
  const Classes k4 = deriv({dt * k3.c, dt * k3.e, dt * k3.d});
  const Classes hand{dt / 6 * (k1.c + 2 * k2.c + 2 * k3.c + k4.c),
                     dt / 6 * (k1.e + 2 * k2.e + 2 * k3.e + k4.e),
                     dt / 6 * (k1.d + 2 * k2.d + 2 * k3.d + k4.d)};
  // The same step as a polynomial: u = dt (g + B g/2 + B²g/6 + B³g/24), B = dt·L, which gives
  // C = dt − 2a dt² + 10/3 a²dt³ − 14/3 a³dt⁴, E = a dt²/2 − 4/3 a²dt³ + 7/3 a³dt⁴,
  // D = a²dt³/3 − a³dt⁴.
  const double ad = a * dt;
  const Classes closed{dt * (1 - 2 * ad + 10.0 / 3 * ad * ad - 14.0 / 3 * ad * ad * ad),
                       dt * (ad / 2 - 4.0 / 3 * ad * ad + 7.0 / 3 * ad * ad * ad),
                       dt * (ad * ad / 3 - ad * ad * ad)};
  CHECK(hand.c == Approx(closed.c).margin(1e-16));
  CHECK(hand.e == Approx(closed.e).margin(1e-16));
  CHECK(hand.d == Approx(closed.d).margin(1e-16));

  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      INFO("node (" << i << ", " << j << ")");
      const bool wall = i == 0 || j == 0 || i == 4 || j == 4;
      const int off = std::abs(i - 2) + std::abs(j - 2);  // 0 centre, 1 edge-adjacent, 2 corner
      const double expected = wall ? 0.0 : off == 0 ? hand.c : off == 1 ? hand.e : hand.d;
      CHECK(field.value(i, j) == Approx(expected).margin(1e-15));
    }
}

TEST_CASE("Fidelity mode: a source snapped to a Dirichlet wall node has no effect", "[agents]") {
  DiffusionField field(DiffusionParams{});
  const auto report = field.step(0.0, [](double, std::vector<PointInjection>& out) {
    out.push_back({{0.01, 0.5}, 20.0});  // 0.3 → node 0, the wall
  });
  CHECK(field.peak() == 0.0);
  CHECK(report.source_requested == Approx(20.0 * 0.002).epsilon(1e-15));
  CHECK(report.source_applied == 0.0);
  REQUIRE(report.injections.size() == 1);
  CHECK(report.injections[0].applied == 0.0);
}

TEST_CASE("The discrete sine mode decays at exactly the scheme's rate under Dirichlet walls",
          "[agents]") {
  // sin(πx) sin(πy) on the nodes is an eigenvector of the 5-point Laplacian with eigenvalue
  // −λ, λ = 2·(4κ/h²) sin²(πh/2); RK4 multiplies it by P(−λ dt) per step, forward Euler by
  // (1 − λ dt_sub) per substep.
  const auto mode = GENERATE(DiffusionMode::fidelity, DiffusionMode::physical);
  DiffusionParams p;
  p.mode = mode;
  p.kappa = 0.05;
  DiffusionField field(p);
  field.set_values([](const Vec2& x) { return std::sin(pi * x.x()) * std::sin(pi * x.y()); });
  const double h = 1.0 / 30.0;
  const double lambda = 2.0 * 4.0 * p.kappa / (h * h) * std::pow(std::sin(pi * h / 2), 2);
  const int steps = 200;
  for (int n = 0; n < steps; ++n)
    field.step(n * p.dt_s);
  const double sub = p.dt_s / field.substeps_per_step();
  const double factor = mode == DiffusionMode::fidelity
                            ? std::pow(rk4_amplification(-lambda * p.dt_s), steps)
                            : std::pow(1.0 - lambda * sub, steps * field.substeps_per_step());
  double worst = 0.0;
  for (int j = 0; j < field.ny(); ++j)
    for (int i = 0; i < field.nx(); ++i) {
      const Vec2 x = field.node_position(i, j);
      const double expected = factor * std::sin(pi * x.x()) * std::sin(pi * x.y());
      worst = std::max(worst, std::abs(field.value(i, j) - expected));
    }
  CHECK(worst < 1e-13);
  CHECK(factor < 0.9);  // the test saw real decay
}

TEST_CASE("Dirichlet walls remove mass monotonically when there is no source", "[agents]") {
  const auto mode = GENERATE(DiffusionMode::fidelity, DiffusionMode::physical);
  DiffusionParams p;
  p.mode = mode;
  p.kappa = 0.02;
  DiffusionField field(p);
  // Positive everywhere inside, touching the walls: a plateau with a bump off-centre.
  field.set_values([](const Vec2& x) {
    return 1.0 + 5.0 * std::exp(-((x - Vec2{0.3, 0.6}).squaredNorm()) / 0.01);
  });
  double previous = field.mass();
  const double initial = previous;
  for (int n = 0; n < 1000; ++n) {
    field.step(n * p.dt_s);
    const double now = field.mass();
    REQUIRE(now < previous);
    previous = now;
  }
  CHECK(field.minimum() >= 0.0);
  CHECK(previous < 0.8 * initial);
}

TEST_CASE("With no-flux walls and no sinks the physical field's mass is the injected mass",
          "[agents]") {
  // 10⁴ steps of 2 ms: a source 20 e^{−t} moving across the grid, a constant source 0.5 sliding
  // along the wall row and one fixed in a corner cell. Injected mass, analytically:
  // 20 (1 − e^{−T}) + 0.5 T + 0.25 T.
  DiffusionParams p = physical(30, Boundary::no_flux);
  DiffusionField field(p);
  const auto sources = [](double t, std::vector<PointInjection>& out) {
    out.push_back({{0.21 + 0.03 * t, 0.79 - 0.02 * t}, 20.0 * std::exp(-t)});
    out.push_back({{0.05 + 0.04 * t, 0.0}, 0.5});
    out.push_back({{0.99, 0.995}, 0.25});
  };
  const int steps = 10000;
  double requested = 0.0, applied = 0.0;
  for (int n = 0; n < steps; ++n) {
    const auto report = field.step(n * p.dt_s, sources);
    requested += report.source_requested;
    applied += report.source_applied;
    REQUIRE(report.spray_requested == 0.0);
  }
  const double T = steps * p.dt_s;
  const double injected = 20.0 * (1.0 - std::exp(-T)) + 0.5 * T + 0.25 * T;
  CHECK(std::abs(field.mass() - injected) / injected < 1e-12);
  CHECK(std::abs(requested - injected) / injected < 1e-12);
  CHECK(applied == Approx(requested).epsilon(1e-14));  // no-flux walls lose nothing
  CHECK(field.minimum() >= 0.0);
}

TEST_CASE("With no-flux walls fidelity mode gains h^2 of mass per unit of unscaled injection",
          "[agents]") {
  // Fidelity adds the rate f to du/dt at one interior node (weight 1), so the trapezoid mass
  // hx·hy·Σ w u grows by f·h² per unit time: after T it is h²·∫f dt, to RK4's Simpson-rule
  // accuracy in time (relative (b dt)⁴/2880 ≈ 1e-14 here).
  DiffusionParams p;
  p.boundary = Boundary::no_flux;
  DiffusionField field(p);
  const auto sources = [](double t, std::vector<PointInjection>& out) {
    out.push_back({{0.21 + 0.03 * t, 0.79}, 20.0 * std::exp(-t)});
    out.push_back({{0.8 - 0.03 * t, 0.21}, 20.0 * std::exp(-t)});
  };
  const int steps = 10000;
  double requested = 0.0;
  for (int n = 0; n < steps; ++n)
    requested += field.step(n * p.dt_s, sources).source_requested;
  const double T = steps * p.dt_s, h = 1.0 / 30.0;
  const double injected = 2.0 * 20.0 * (1.0 - std::exp(-T));
  CHECK(std::abs(field.mass() - h * h * injected) / (h * h * injected) < 1e-12);
  CHECK(std::abs(requested - injected) / injected < 1e-12);
}

TEST_CASE("A Gaussian bump follows the heat kernel with second-order convergence in h",
          "[agents]") {
  // Physical mode, no-flux unit square, initial Gaussian of variance σ0² = 0.01 mirrored at the
  // walls (method of images), so the exact solution is the mirrored Gaussian of variance
  // σ0² + 2κt. dt = 0.1024·h²/κ on every grid, so the forward-Euler time error scales like the
  // space error, h².
  const double kappa = 0.01, s0 = 0.01, T = 0.25;
  const Vec2 centre{0.42, 0.55};
  std::vector<double> errors;
  for (int cells : {32, 64, 128, 256}) {
    DiffusionParams p = physical(cells, Boundary::no_flux);
    p.kappa = kappa;
    const int steps = 25 * (cells / 32) * (cells / 32);
    p.dt_s = T / steps;
    DiffusionField field(p);
    REQUIRE(field.substeps_per_step() == 1);
    field.set_values([&](const Vec2& x) {
      return neumann_gaussian_1d(x.x(), centre.x(), s0) *
             neumann_gaussian_1d(x.y(), centre.y(), s0);
    });
    for (int n = 0; n < steps; ++n)
      field.step(n * p.dt_s);
    const double s2 = s0 + 2.0 * kappa * T;
    double worst = 0.0;
    for (int j = 0; j < field.ny(); ++j)
      for (int i = 0; i < field.nx(); ++i) {
        const Vec2 x = field.node_position(i, j);
        const double exact =
            neumann_gaussian_1d(x.x(), centre.x(), s2) * neumann_gaussian_1d(x.y(), centre.y(), s2);
        worst = std::max(worst, std::abs(field.value(i, j) - exact));
      }
    errors.push_back(worst);
    // The mass is that of the exact solution, 1, to rounding.
    CHECK(field.mass() == Approx(1.0).epsilon(1e-12));
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    INFO("max error " << errors[k] << " -> " << errors[k + 1] << ", observed order " << order);
    CHECK(order > 1.8);
    CHECK(order < 2.2);
  }
  CHECK(errors.back() < 1e-3 * (1.0 / (2.0 * pi * (s0 + 2.0 * kappa * T))));  // < 0.1 % of peak
}

TEST_CASE("Physical mode spreads a point injection bilinearly and reads bilinearly", "[agents]") {
  DiffusionParams p = physical(10, Boundary::no_flux);
  DiffusionField field(p);
  // A linear field is read back exactly anywhere.
  field.set_values([](const Vec2& x) { return 1.0 + x.x() + 2.0 * x.y(); });
  for (const Vec2& x : {Vec2{0.123, 0.456}, Vec2{0.0, 1.0}, Vec2{0.999, 0.5}, Vec2{0.55, 0.05}})
    CHECK(field.value_at(x) == Approx(1.0 + x.x() + 2.0 * x.y()).epsilon(1e-14));

  // From u = 0 one step with no diffusion (κ = 0): the four nodes of the cell get
  // rate·dt·φ/(hx·hy·w), φ the bilinear weights, w the trapezoid weight of the node.
  p.kappa = 0.0;
  DiffusionField still(p);
  still.step(0.0, [](double, std::vector<PointInjection>& out) {
    out.push_back({{0.13, 0.07}, 3.0});
  });
  const double amount = 3.0 * p.dt_s, cell = 0.01;  // fx = 0.3, fy = 0.7 in cell (1, 0)
  CHECK(still.value(1, 0) == Approx(amount * 0.7 * 0.3 / (cell * 0.5)));
  CHECK(still.value(2, 0) == Approx(amount * 0.3 * 0.3 / (cell * 0.5)));
  CHECK(still.value(1, 1) == Approx(amount * 0.7 * 0.7 / cell));
  CHECK(still.value(2, 1) == Approx(amount * 0.3 * 0.7 / cell));
  CHECK(still.mass() == Approx(amount).epsilon(1e-14));
}

TEST_CASE(
    "Physical mode reports the part of an injection that falls on a Dirichlet wall as "
    "not applied",
    "[agents]") {
  DiffusionParams p = physical(10, Boundary::dirichlet);
  DiffusionField field(p);
  const auto report = field.step(0.0, [](double, std::vector<PointInjection>& out) {
    out.push_back({{0.05, 0.5}, 4.0});  // half-way between the wall column and column 1
  });
  CHECK(report.source_requested == Approx(4.0 * p.dt_s).epsilon(1e-15));
  CHECK(report.source_applied == Approx(0.5 * 4.0 * p.dt_s).epsilon(1e-14));
  // What was applied is in the field (one substep, the wall has not absorbed anything yet
  // beyond the diffusion of this step, which starts from zero: only the injection counts).
  CHECK(field.mass() <= report.source_applied * (1.0 + 1e-14));
  CHECK(field.mass() > 0.9 * report.source_applied);
}

TEST_CASE("Sprays never drive the physical field below zero and report what they neutralised",
          "[agents]") {
  const auto boundary = GENERATE(Boundary::no_flux, Boundary::dirichlet);
  DiffusionParams p = physical(40, boundary);
  DiffusionField field(p);
  field.set_values([](const Vec2& x) {
    return 2.0 * std::exp(-((x - Vec2{0.5, 0.5}).squaredNorm()) / 0.005);
  });
  // A weak source upstream and two robots spraying at the world's cap (magnitude 2) while
  // moving through the bump (both start on a node and move across cells).
  const double cap = 2.0;
  const auto injections = [cap](double t, std::vector<PointInjection>& out) {
    out.push_back({{0.2, 0.2}, 0.05});
    out.push_back({{0.3 + 0.1 * t, 0.5}, -cap});
    out.push_back({{0.5, 0.5 + 0.0123 * t}, -cap});
  };
  double requested = 0.0, applied = 0.0;
  bool exhausted = false;
  for (int n = 0; n < 1500; ++n) {
    const double before = field.mass();
    const auto report = field.step(n * p.dt_s, injections);
    REQUIRE(field.minimum() >= 0.0);
    // The cap passed in is what is requested; what is applied never exceeds it.
    REQUIRE(report.spray_requested == Approx(2.0 * cap * p.dt_s).epsilon(1e-14));
    REQUIRE(report.spray_applied >= 0.0);
    REQUIRE(report.spray_applied <= report.spray_requested * (1.0 + 1e-14));
    REQUIRE(report.injections.size() == 3);
    REQUIRE(-(report.injections[1].applied + report.injections[2].applied) ==
            Approx(report.spray_applied).epsilon(1e-12));
    for (std::size_t k = 1; k < 3; ++k) {
      REQUIRE(report.injections[k].requested == Approx(-cap * p.dt_s).epsilon(1e-14));
      REQUIRE(report.injections[k].applied <= 1e-18);
      REQUIRE(report.injections[k].applied >= report.injections[k].requested * (1.0 + 1e-14));
    }
    if (report.spray_applied < 0.5 * report.spray_requested) exhausted = true;
    // Mass balance with what the report says (the no-flux walls lose nothing).
    if (boundary == Boundary::no_flux)
      REQUIRE(field.mass() ==
              Approx(before + report.source_applied - report.spray_applied).margin(1e-13));
    requested += report.spray_requested;
    applied += report.spray_applied;
  }
  CHECK(exhausted);  // the robots ran out of pollution to neutralise, and were not charged for it
  CHECK(applied < 0.9 * requested);
  CHECK(applied > 0.0);
}

TEST_CASE("Fidelity mode lets a spray drive its node negative unless clipping is asked for",
          "[agents]") {
  const bool clip = GENERATE(false, true);
  DiffusionParams p;
  p.clip_sprays_at_zero = clip;
  DiffusionField field(p);
  const auto spray = [](double, std::vector<PointInjection>& out) {
    out.push_back({{0.5, 0.5}, -2.0});
  };
  const auto report = field.step(0.0, spray);
  const NodeIndex k = field.nearest_node({0.5, 0.5});
  CHECK(report.spray_requested == Approx(2.0 * p.dt_s).epsilon(1e-15));
  if (clip) {
    // The node is clipped; within the RK4 stages a little of the spray already reached the
    // neighbours (κ dt/h² = 0.018 per stage), which stay slightly negative and count as applied.
    CHECK(field.value(k.i, k.j) == 0.0);
    CHECK(report.spray_applied < 0.05 * report.spray_requested);
    CHECK(report.spray_applied == Approx(-field.mass() * 900.0).epsilon(1e-12));  // mass = h²Σu
  } else {
    CHECK(field.value(k.i, k.j) < 0.0);  // as Diff-MAS2D: the World reads only positive values
    CHECK(report.spray_applied == Approx(report.spray_requested).epsilon(1e-15));
  }
}

TEST_CASE("The stability limits are the scheme's, and fidelity rejects a step above RK4's",
          "[agents]") {
  DiffusionField paper(DiffusionParams{});
  // λmax = κ·8/h²·cos²(π/60) on the Dirichlet interior; RK4 is stable for λ dt ≤ 2.7853.
  const double lambda = 0.01 * 8.0 * 900.0 * std::pow(std::cos(pi / 60.0), 2);
  CHECK(paper.stable_dt() == Approx(2.785293563405282 / lambda).epsilon(1e-14));
  CHECK(paper.stable_dt() == Approx(0.0387908830832).epsilon(1e-10));
  CHECK(paper.substeps_per_step() == 1);

  DiffusionParams big;
  big.dt_s = 0.04;
  CHECK_FALSE(masnet::agents::diffusion_params_error(big).empty());
  big.dt_s = 0.038;
  CHECK(masnet::agents::diffusion_params_error(big).empty());

  // Physical: forward Euler's positivity limit h²/(4κ), met by substeps.
  DiffusionParams fine = physical(256, Boundary::dirichlet);
  DiffusionField f256(fine);
  CHECK(f256.stable_dt() == Approx(1.0 / (256.0 * 256.0 * 4.0 * 0.01)).epsilon(1e-14));
  CHECK(f256.substeps_per_step() == 6);  // ⌈0.002 / 3.81e-4⌉
}

TEST_CASE("Diffusion step costs are measured (fidelity paper grid, physical 256 x 256)",
          "[.][timing]") {
  using Clock = std::chrono::steady_clock;
  // The paper scenario's load: 2 moving sources, 4 robots spraying, 5000 steps.
  const auto paper = [](double t, std::vector<PointInjection>& out) {
    out.push_back({{0.21 + 0.06 * t, 0.79}, 20.0 * std::exp(-t)});
    out.push_back({{0.8 - 0.06 * t, 0.21}, 20.0 * std::exp(-t)});
    out.push_back({{1.0 / 3, 1.0 / 3}, -0.5});
    out.push_back({{1.0 / 3, 2.0 / 3}, -0.5});
    out.push_back({{2.0 / 3, 1.0 / 3}, -0.5});
    out.push_back({{2.0 / 3, 2.0 / 3}, -0.5});
  };
  {
    DiffusionField field(DiffusionParams{});
    const auto start = Clock::now();
    for (int n = 0; n < 5000; ++n)
      field.step(n * 0.002, paper);
    const double s = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("fidelity 31x31 RK4: %.2f us per step (5000 steps in %.4f s)\n", s / 5000 * 1e6, s);
    CHECK(std::isfinite(field.mass()));
  }
  for (const Boundary b : {Boundary::dirichlet, Boundary::no_flux}) {
    DiffusionParams p = physical(256, b);
    DiffusionField field(p);
    const auto start = Clock::now();
    for (int n = 0; n < 500; ++n)
      field.step(n * p.dt_s, paper);
    const double s = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("physical 257x257 nodes (%s), %d substeps per 2 ms step: %.3f s per simulated s\n",
                b == Boundary::dirichlet ? "dirichlet" : "no_flux", field.substeps_per_step(), s);
    CHECK(field.minimum() >= 0.0);
  }
}
