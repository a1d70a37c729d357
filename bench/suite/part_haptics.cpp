// `serosa bench haptics`: the virtual coupling stiffness k_c (ContactModel::coupling_stiffness_Npm)
// rendered through haptics::ForceRenderer at 1 kHz, swept over a range around Colgate's passivity
// bound. For each k_c:
//  - force error: the device pressed slowly (10 mm/s, kinematic) 5 mm into tissue of stiffness
//    k_t = 1000 N/m; the solver (quasi-static, one tick behind) moves the simulated tool tip to
//    where coupling and tissue balance, s = x k_c / (k_c + k_t) below the surface; the renderer
//    couples the device to it. Ideal force: the tissue's own k_t × depth at the device. Error: mean
//    |F - F_ideal| / F_ideal over the samples deeper than 1 mm (in theory k_t / (k_c + k_t)).
//  - stability margin: a device of mass m = 0.1 kg and damping b = 2 N s/m (handle and hand)
//    pressed with 3 N into a rigid wall through the coupling (god object on the wall), force
//    sampled and held per 1 ms tick (zero-order hold; dynamics integrated in 50 substeps). After a
//    small tap (1e-4 m/s) the energy of the deviation from equilibrium, E = m v²/2 + k_c e²/2,
//    decays as exp(-2 sigma t); sigma (1/s, fitted to log E over at least 4 periods) is the
//    margin: positive decays, negative grows (unstable). Colgate & Schenkel's passivity bound
//    k_c < 2 b / T (4000 N/m here) for comparison, and the static wall penetration 3 N / k_c.
//  - loop time per tick: set_model + render, the 1 kHz loop's force work, µs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "bench/suite/bench_parts.h"
#include "haptics/contact_model.h"
#include "haptics/force_renderer.h"

namespace serosa::bench {
namespace {

using haptics::ContactModel;
using haptics::ForceRenderer;
using Clock = std::chrono::steady_clock;

constexpr double kT = 1e-3;                       // haptic tick, s
constexpr double kMass = 0.1;                     // device + hand mass, kg
constexpr double kDamping = 2.0;                  // device + hand damping, N s/m
constexpr double kHand = 3.0;                     // hand force into the wall, N
constexpr double kTissue = 1000.0;                // tissue stiffness, N/m
constexpr double kColgate = 2.0 * kDamping / kT;  // passivity bound, N/m

ContactModel coupled_model(double k_c, std::uint64_t step, const Vec3& sim_tip) {
  ContactModel m;
  m.step = step;
  m.time_s = static_cast<double>(step) * kT;
  m.coupling_stiffness_Npm = k_c;
  m.tools[0].coupled = 1;
  m.tools[0].sim_tip_m = {sim_tip.x(), sim_tip.y(), sim_tip.z()};
  return m;
}

/// Mean relative force error of a slow press into tissue (see the file comment).
double force_error(double k_c) {
  ForceRenderer r;
  const double speed = 0.01;  // m/s
  const int ticks = 600;      // +0.5 mm to -5.5 mm
  Vec3 prev(0.0, 0.0, 5e-4);
  double sum = 0.0;
  int n = 0;
  for (int k = 0; k < ticks; ++k) {
    const double t = k * kT;
    const Vec3 x(0.0, 0.0, 5e-4 - speed * t);
    // The solver, one tick behind: tip where k_c (x - s) balances k_t × depth(s).
    const double z = prev.z() < 0.0 ? prev.z() * k_c / (k_c + kTissue) : prev.z();
    r.set_model(coupled_model(k_c, static_cast<std::uint64_t>(k + 1), Vec3(0.0, 0.0, z)), t);
    Vec3 f;
    r.render(0, x, t, kT, f);
    const double depth = -x.z();
    if (depth > 1e-3) {
      const double ideal = kTissue * depth;
      sum += std::abs(f.z() - ideal) / ideal;
      ++n;
    }
    prev = x;
  }
  return sum / n;
}

struct Stability {
  double decay_per_s = 0.0;     ///< sigma, 1/s
  double penetration_mm = 0.0;  ///< mean wall penetration, mm
  double us_per_tick = 0.0;     ///< set_model + render, µs
};

/// The tapped device on the rigid wall (see the file comment).
Stability stability(double k_c) {
  ForceRenderer r;
  const double x_eq = -kHand / k_c;
  const double omega = std::sqrt(k_c / kMass);
  const int ticks = static_cast<int>(std::max(0.3, 4.0 * 2.0 * 3.14159265358979 / omega) / kT);
  double x = x_eq, v = 0.0;
  // Held at equilibrium until the slew-limited force has ramped up.
  std::uint64_t step = 1;
  Vec3 f = Vec3::Zero();
  for (int k = 0; k < 40; ++k, ++step) {
    const Vec3 p(0.0, 0.0, x);
    r.set_model(coupled_model(k_c, step, Vec3(0.0, 0.0, std::max(x, 0.0))),
                static_cast<double>(step) * kT);
    r.render(0, p, static_cast<double>(step) * kT, kT, f);
  }
  v = -1e-4;  // the tap
  // Least-squares fit of log E = a - 2 sigma t.
  double st = 0.0, sl = 0.0, stt = 0.0, stl = 0.0, pen = 0.0, seconds = 0.0;
  constexpr int kSub = 50;
  for (int k = 0; k < ticks; ++k, ++step) {
    const double now = static_cast<double>(step) * kT;
    const Vec3 p(0.0, 0.0, x);
    const auto t0 = Clock::now();
    r.set_model(coupled_model(k_c, step, Vec3(0.0, 0.0, std::max(x, 0.0))), now);
    r.render(0, p, now, kT, f);
    seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    const double e = x - x_eq;
    const double energy = 0.5 * kMass * v * v + 0.5 * k_c * e * e;
    const double t = k * kT, l = std::log(std::max(energy, 1e-300));
    st += t;
    sl += l;
    stt += t * t;
    stl += t * l;
    pen += -x;
    const double h = kT / kSub;
    for (int s = 0; s < kSub; ++s) {  // semi-implicit Euler, force held
      v += h * (f.z() - kHand - kDamping * v) / kMass;
      x += h * v;
    }
  }
  const double n = ticks;
  const double slope = (n * stl - st * sl) / (n * stt - st * st);
  Stability out;
  out.decay_per_s = -0.5 * slope;
  out.penetration_mm = 1e3 * pen / n;
  out.us_per_tick = 1e6 * seconds / n;
  return out;
}

}  // namespace

PartResult run_haptics_part(const BenchOptions& options) {
  const std::vector<double> stiffness =
      options.quick ? std::vector<double>{100, 300, 1000, 2000, 4000, 8000}
                    : std::vector<double>{50,   100,  200,  300,  500,  1000, 1500,
                                          2000, 3000, 4000, 5000, 6000, 8000, 12000};
  Table t{"haptics_stiffness",
          {"coupling_Npm", "force_error_rel", "wall_penetration_mm", "decay_per_s",
           "colgate_margin", "us_per_tick"},
          {},
          {}};
  for (const double k : stiffness) {
    const Stability s = stability(k);
    std::string label = "k_c=";
    label.append(std::to_string(static_cast<int>(k))).append(" N/m");
    t.add(label,
          {k, force_error(k), s.penetration_mm, s.decay_per_s, 1.0 - k / kColgate, s.us_per_tick});
  }
  PartResult result;
  result.tables.push_back(std::move(t));
  Plot error{"haptics_force_error",
             "Haptics: force error against coupling stiffness",
             "coupling stiffness, N/m",
             "relative force error, wall penetration (mm)",
             true,
             true,
             {}};
  error.series.push_back(
      {"haptics_stiffness", "coupling_Npm", "force_error_rel", "force error", false, false});
  error.series.push_back({"haptics_stiffness", "coupling_Npm", "wall_penetration_mm",
                          "wall penetration, mm", false, false});
  result.plots.push_back(std::move(error));
  Plot margin{"haptics_stability",
              "Haptics: stability margin against coupling stiffness",
              "coupling stiffness, N/m",
              "decay rate of a tap, 1/s (< 0: unstable)",
              true,
              false,
              {}};
  margin.series.push_back(
      {"haptics_stiffness", "coupling_Npm", "decay_per_s", "decay rate", false, false});
  result.plots.push_back(std::move(margin));
  Plot time{"haptics_time",
            "Haptics: force error against loop time per tick",
            "set_model + render per tick, us",
            "relative force error",
            false,
            true,
            {}};
  time.series.push_back(
      {"haptics_stiffness", "us_per_tick", "force_error_rel", "one per stiffness", true, true});
  result.plots.push_back(std::move(time));
  result.checks.push_back({"haptics_stiffness", "coupling_Npm", "force_error_rel",
                           Direction::decreasing, 0.0, 0.0,
                           "a stiffer coupling renders the tissue's force more faithfully"});
  result.checks.push_back({"haptics_stiffness", "coupling_Npm", "decay_per_s",
                           Direction::decreasing, 0.02, 0.05,
                           "a stiffer coupling leaves less stability margin (Colgate)"});
  std::string note = "haptics: passivity bound 2b/T = ";
  note.append(std::to_string(static_cast<int>(kColgate)))
      .append(" N/m (b = 2 N s/m, T = 1 ms); the decay rate should cross 0 near it");
  result.notes.push_back(std::move(note));
  return result;
}

}  // namespace serosa::bench
