// The parallel-plate rheometer in oscillation and steady shear (include/dentsph/handling.hpp; docs/model.md,
// "Handling tests"). The rig is the Couette test's (tests/physics/test_iisph_couette.cpp): a disc
// of paste of radius R between a fixed plate (boundary particles) and a plate turning at Omega (the
// tool), both two layers deep and 3 spacings wider than the disc, without gravity. The gap H is
// taken between the plates' first layers (the no-slip planes), so the shear rate at the rim is
// Omega R / H.
//
// A parallel-plate rheometer measures the torque T; for a paste of stress tau(gammadot),
// T = 2 pi int_0^R tau(Omega r / H) r^2 dr, and the stress at the rim follows from the torque and
// its slope over the rim's shear rate (Weissenberg-Rabinowitsch for parallel plates):
//   tau_R = T / (2 pi R^3) (3 + d ln T / d ln gammadot_R),   eta(gammadot_R) = tau_R / gammadot_R.
// The rig's own constant (the disc's rim feels the plates beyond it: 1.11 to 1.13 in the Couette
// tests) is measured with a Newtonian standard on the paste's form and divided out, as a real
// rheometer is calibrated with a standard oil.
#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "dentsph/handling.hpp"
#include "dentsph/scene.hpp"
#include "handling/rig.hpp"
#include "physics/rheology.hpp"

namespace dentsph {

namespace {

constexpr real pi = 3.14159265358979323846;

struct Geometry {
  real s = 0, R = 0, H = 0;
  int nr = 0, nz = 0;
};

// The paste between the plates at rest.
State plates_with(Model& model, const Geometry& g, const Material& paste) {
  const real m = lattice_particle_mass(paste.rho0, g.s, model.kernel);
  const Material plate = handling::wall_beside(paste);
  std::vector<ParticleInit> ps;
  const int reach = g.nr + 3;
  for (int k = -2; k <= g.nz + 1; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const Vec3 x{i * g.s, j * g.s, (k + 0.5) * g.s};  // the paste's layers at z = (k + 1/2) s, k = 0 .. nz - 1
        const real r = std::hypot(x.x, x.y);
        if (k < 0) {
          if (r <= reach * g.s) ps.push_back(make_particle(Role::boundary, x, m, plate));
        } else if (k >= g.nz) {
          if (r <= reach * g.s) ps.push_back(make_particle(Role::tool, x, m, plate));
        } else if (r < g.R) {
          ps.push_back(make_particle(Role::material, x, m, paste));
        }
      }
  State st;
  st.add_particles(model, ps);
  return st;
}

// The rig with the paste between its plates at rest, stepped at dt.
struct Rig {
  Model model;
  State state;
};
Rig rig_with(const Geometry& g, const Material& paste, real dt) {
  const real reach = g.nr + 6;
  Rig rig{make_model(handling::rig_params(g.s, Vec3{-reach, -reach, -6} * g.s, Vec3{reach, reach, g.nz + 6.0} * g.s,
                                          dt, {})),
          {}};
  rig.state = plates_with(rig.model, g, paste);
  return rig;
}

// The torque (N m) the paste puts against the plate turning at rim shear rate `rate`, averaged over
// time from a tenth of a radian to a quarter turn beyond (the same angles at every rate, so that the
// plate's lattice passes the paste's alike).
real steady_torque(const Geometry& g, const Material& paste, real rate, const RheometerOptions& o) {
  const real omega = rate * g.H / g.R, rim = omega * g.R;
  const real dt = std::min<real>(IisphParams{}.cfl * 2 * g.s / rim, 0.05);
  Rig rig = rig_with(g, paste, dt);
  State& st = rig.state;
  const real from = 0.1, to = from + 0.5 * pi;
  real sum = 0, time = 0;
  while (omega * st.time < to - 1e-9) {
    st.tool_pose = Pose{{}, Quat::from_axis_angle({0, 0, 1}, omega * (st.time + dt))};
    handling::rig_step(rig.model, st, o.run, "rheometer");
    if (omega * st.time > from) {
      sum += -st.tool_wrench.torque.z * dt;  // the paste's torque on the plate opposes its turning
      time += dt;
    }
  }
  return sum / time;
}

// The paste's moduli in oscillation: the plate turned to theta0 sin(omega t), theta0 = gamma0 H / R (the
// rim's strain amplitude gamma0, o.strain_amplitude; omega o.frequency), for o.cycles periods; the torque over the last cycles but the first
// fitted by least squares with T0 + A sin(omega t) + B cos(omega t): in phase with the strain the
// storage modulus G' = 2 H A / (pi R^4 theta0), with its rate the loss modulus G'' = 2 H B / (pi R^4
// theta0) (a linear paste's; a paste that yields or thins gives the first harmonic's, as a
// rheometer reports it); the caller divides them by the rig's constant in oscillation. Also the
// last cycle's strain and stress (less its mean), each over its amplitude, for the plot.
struct Moduli {
  real storage = 0, loss = 0;
  std::vector<real> time, strain, stress;  // the last cycle: s, of the strain's amplitude, of the stress's
};
Moduli oscillation(const Geometry& g, const Material& paste, const RheometerOptions& o) {
  const real omega = o.frequency;
  const int cycles = o.cycles;
  const real theta0 = o.strain_amplitude * g.H / g.R, period = 2 * pi / omega;
  const real rim = omega * theta0 * g.R;
  const real dt = std::min<real>(IisphParams{}.cfl * 2 * g.s / rim, period / 200);
  Rig rig = rig_with(g, paste, dt);
  State& st = rig.state;
  // Sums of the least-squares normal equations over (1, sin, cos).
  real S[3][3] = {}, b[3] = {};
  const int steps = int(std::ceil(cycles * period / dt - 1e-9));
  Moduli out;
  for (int k = 1; k <= steps; ++k) {
    const real t = k * dt;
    st.tool_pose = Pose{{}, Quat::from_axis_angle({0, 0, 1}, theta0 * std::sin(omega * t))};
    handling::rig_step(rig.model, st, o.run, "rheometer");
    if (t <= period) continue;  // the first cycle: the stress building up
    const real torque = -st.tool_wrench.torque.z;
    if (t > (cycles - 1) * period) {
      out.time.push_back(t - (cycles - 1) * period);
      out.strain.push_back(std::sin(omega * t));
      out.stress.push_back(torque);
    }
    const real f[3] = {1, std::sin(omega * t), std::cos(omega * t)};
    for (int r = 0; r < 3; ++r) {
      b[r] += f[r] * torque;
      for (int c = 0; c < 3; ++c) S[r][c] += f[r] * f[c];
    }
  }
  // Solve S c = b (3 x 3, by Cramer's rule).
  auto det3 = [](const real M[3][3]) {
    return M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
           M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  };
  const real d = det3(S);
  real c[3];
  for (int k = 0; k < 3; ++k) {
    real M[3][3];
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q) M[r][q] = q == k ? b[r] : S[r][q];
    c[k] = det3(M) / d;
  }
  const real scale = 2 * g.H / (pi * std::pow(g.R, 4) * theta0);
  out.storage = c[1] * scale;
  out.loss = c[2] * scale;
  const real amplitude = std::hypot(c[1], c[2]);
  for (real& T : out.stress) T = amplitude > 0 ? (T - c[0]) / amplitude : 0;
  return out;
}

// log-log interpolation of y(x) at x0 (x ascending, at least two points): the nearest segment's line.
real loglog_at(const std::vector<real>& x, const std::vector<real>& y, real x0) {
  std::size_t i = 0;
  while (i + 2 < x.size() && x[i + 1] < x0) ++i;
  const real t = (std::log(x0) - std::log(x[i])) / (std::log(x[i + 1]) - std::log(x[i]));
  return std::exp(std::log(y[i]) + t * (std::log(y[i + 1]) - std::log(y[i])));
}

}  // namespace

void check_rheometer_options(const RheometerOptions& o) {
  if (o.shear_rates.size() < 2)
    throw std::invalid_argument("rheometer: shear_rates needs at least two rates (the torque's slope); give e.g. 1, 10, 100");
  for (std::size_t i = 0; i < o.shear_rates.size(); ++i)
    if (!(o.shear_rates[i] > 0) || (i > 0 && !(o.shear_rates[i] > o.shear_rates[i - 1])))
      throw std::invalid_argument("rheometer: shear_rates must be positive and ascending");
  if (!(o.spacing > 0) || o.radius_spacings < 4 || o.gap_layers < 2)
    throw std::invalid_argument("rheometer: the spacing must be > 0, the disc at least 4 spacings wide and 2 layers deep");
  if (!(o.frequency > 0) || !(o.strain_amplitude > 0 && o.strain_amplitude <= 10) || o.cycles < 2)
    throw std::invalid_argument(
        "rheometer: the oscillation needs a frequency > 0, a strain amplitude in (0, 10] and at least 2 cycles (the "
        "first is let go by); give e.g. 10 rad/s, 1 and 3");
}

HandlingResult rheometer_test(const PastePreset& preset, const RheometerOptions& o) {
  check_rheometer_options(o);
  Geometry g;
  g.s = o.spacing;
  g.nr = o.radius_spacings;
  g.nz = o.gap_layers;
  g.R = g.nr * g.s;
  g.H = (g.nz + 1) * g.s;
  auto say = [&](const std::string& line) {
    if (o.run.progress) o.run.progress(line);
  };

  // The rig's constant, with a Newtonian standard of the preset's viscosity at 10 /s on the paste's
  // (projected) form: a yield stress of a micropascal puts it there and changes no stress.
  Material standard = preset.paste;
  standard.mu = preset.viscosity_at_10;
  standard.flow_index = 1;
  standard.yield_stress = 1e-6;
  standard.max_viscosity = 1e3 * standard.mu;
  const real cal_rate = 10;
  const real cal_torque = steady_torque(g, standard, cal_rate, o);
  const real cal = cal_torque / (pi * standard.mu * (cal_rate * g.H / g.R) * std::pow(g.R, 4) / (2 * g.H));
  say(fmt::format("rheometer: calibrated with a Newtonian standard of {:.4g} Pa s: the rig reads {:.4f} of its torque",
                  standard.mu, cal));

  // In oscillation the rig's constant is measured again, with the same standard oscillated (its
  // complex viscosity is its viscosity).
  const Moduli standard_osc = oscillation(g, standard, o);
  const real cal_osc = std::hypot(standard_osc.storage, standard_osc.loss) / o.frequency / standard.mu;
  const Moduli osc = oscillation(g, preset.paste, o);
  const real eta_star = std::hypot(osc.storage, osc.loss) / cal_osc / o.frequency;
  const real phase = std::atan2(osc.loss, osc.storage) * 180 / pi;
  say(fmt::format("rheometer: {} at {:g} rad/s, strain {:g}: G' {:.4g} Pa, G'' {:.4g} Pa: |eta*| {:.4g} Pa s, phase "
                  "{:.2f} deg (the rig reads {:.4f} of the standard's in oscillation)",
                  preset.name, o.frequency, o.strain_amplitude, osc.storage / cal_osc, osc.loss / cal_osc, eta_star,
                  phase, cal_osc));

  std::vector<real> rates = o.shear_rates, torques;
  for (real rate : rates) {
    torques.push_back(steady_torque(g, preset.paste, rate, o) / cal);
    say(fmt::format("rheometer: {} at {:g} /s: torque {:.4g} N m", preset.name, rate, torques.back()));
  }
  // The Weissenberg-Rabinowitsch correction, the slope d ln T / d ln gammadot by finite differences
  // (central inside, one-sided at the ends).
  const std::size_t n = rates.size();
  std::vector<real> viscosity(n), stress(n), law(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? i : i + 1;
    const real slope = std::log(torques[b] / torques[a]) / std::log(rates[b] / rates[a]);
    stress[i] = torques[i] / (2 * pi * std::pow(g.R, 3)) * (3 + slope);
    viscosity[i] = stress[i] / rates[i];
    law[i] = rheology::effective_viscosity(preset.paste, rates[i]);
  }
  // The flow index: the slope of the stress over the shear rate, log-log, between the two highest
  // rates (where a yield stress's share and a low-shear plateau are least).
  const real flow_index = std::log(stress[n - 1] / stress[n - 2]) / std::log(rates[n - 1] / rates[n - 2]);

  HandlingResult r = handling::result_of("rheometer", preset);
  HandlingFigure eta10{"viscosity at 10 /s", loglog_at(rates, viscosity, 10), "Pa s", std::nullopt,
                       "steady shear; the preset's constants were set so that it lies in the range of the complex "
                       "viscosities published at 10 rad/s (the Cox-Merz rule): " + preset.source};
  HandlingFigure complex{fmt::format("complex viscosity at {:g} rad/s", o.frequency), eta_star, "Pa s", std::nullopt,
                         fmt::format("oscillation to a rim strain of {:g}; ", o.strain_amplitude) + preset.source};
  if (preset.published_high > 0 && preset.temperature_c == 23) {
    eta10.range = std::array<real, 2>{preset.published_low, preset.published_high};
    if (o.frequency == 10) complex.range = eta10.range;
  } else if (preset.published_high > 0) {
    eta10.source = complex.source =
        fmt::format("the published range is at 23 C ({:.4g} to {:.4g} Pa s); this paste is at {:g} C",
                    preset.published_low, preset.published_high, preset.temperature_c);
  }
  r.figures.push_back(eta10);
  r.figures.push_back(complex);
  HandlingFigure delta{fmt::format("phase angle at {:g} rad/s", o.frequency), phase, "deg", std::nullopt,
                       "Lee, Son & Um, Dent Mater 2003: 30.9 to 78.1 degrees at 10 rad/s over nine composites (25 C). "
                       "Departure: the model's paste has no elasticity (docs/model.md, \"Elasticity\"), so its stress "
                       "is in phase with the strain rate: 90 degrees"};
  if (o.frequency == 10) delta.range = std::array<real, 2>{30.9, 78.1};
  r.figures.push_back(delta);
  // The viscosity over a conventional composite's (the universal preset's at 10 /s at the same
  // temperature), where the preset has a published ratio no constant was set from (the flowable's:
  // its viscosity was chosen in Loumprinis 2021's range, the universal's from Lee 2003's packable ratio).
  if (preset.published_ratio) {
    const real universal = paste_preset("universal", preset.temperature_c).viscosity_at_10;
    r.figures.push_back({"viscosity over a conventional composite's", eta10.value / universal, "",
                         preset.published_ratio, preset.ratio_source});
  }
  const real law_slope = std::log(law[n - 1] * rates[n - 1] / (law[n - 2] * rates[n - 2])) /
                         std::log(rates[n - 1] / rates[n - 2]);
  r.figures.push_back({"flow index", flow_index, "", std::nullopt,
                       fmt::format("the slope of the stress over the shear rate (log-log) between {:g} and {:g} /s; the "
                                   "preset's law gives {:.3f} there (flow index {:g}, assumed: docs/model.md, "
                                   "\"Presets\"; every composite Lee, Son & Um, Dent Mater 2003, measured thins under "
                                   "shear)",
                                   rates[n - 2], rates[n - 1], law_slope, preset.paste.flow_index)});
  r.figures.push_back({"rig constant", cal, "", std::nullopt,
                       "the torque of a Newtonian standard over pi mu Omega R^4 / (2 H): divided out of every steady torque"});
  r.figures.push_back({"rig constant in oscillation", cal_osc, "", std::nullopt,
                       "the complex viscosity the rig reads from the same standard oscillated, over its viscosity: "
                       "divided out of the paste's moduli"});
  HandlingCurve curve;
  curve.file = "flow_curve";
  curve.title = fmt::format("Flow curve: {} at {:g} C", preset.name, preset.temperature_c);
  curve.x_label = "shear rate at the rim (1/s)";
  curve.y_label = "viscosity (Pa s)";
  curve.log_x = curve.log_y = true;
  curve.series.push_back({"virtual rheometer", rates, viscosity, false});
  curve.series.push_back({"the preset's law", rates, law, true});
  if (eta10.range) curve.range_bar = std::array<real, 3>{10, (*eta10.range)[0], (*eta10.range)[1]};
  r.curves.push_back(curve);
  HandlingCurve wave;
  wave.file = "oscillation";
  wave.title = fmt::format("Oscillation: {} at {:g} rad/s, rim strain {:g}", preset.name, o.frequency, o.strain_amplitude);
  wave.x_label = "time in the last cycle (s)";
  wave.y_label = "of its amplitude";
  wave.series.push_back({"strain", osc.time, osc.strain, true});
  wave.series.push_back({"stress (torque)", osc.time, osc.stress, false});
  wave.legend_right = true;
  r.curves.push_back(wave);
  r.notes.push_back(fmt::format(
      "a disc of radius {:.2f} mm between plates {:.2f} mm apart, particles {:.2f} mm apart; the torque over the same "
      "quarter turn at each rate, read with the Weissenberg-Rabinowitsch correction",
      g.R * 1e3, g.H * 1e3, g.s * 1e3));
  r.notes.push_back(fmt::format(
      "the published figures are complex viscosities at 10 rad/s in small oscillations; the model's paste has no "
      "elasticity and its yield stress no linear region below it, so the plate oscillates to a rim strain of {:g} (a "
      "rim strain rate of {:g} /s at most) and the moduli are the torque's first harmonic; its phase angle is that of "
      "a liquid, 90 degrees (the published 30.9 to 78.1: a departure)",
      o.strain_amplitude, o.strain_amplitude * o.frequency));
  return r;
}

}  // namespace dentsph
