// The parallel-plate rheometer in steady shear (include/dentsph/handling.hpp; docs/model.md,
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

// The torque (N m) the paste puts against the plate turning at rim shear rate `rate`, averaged over
// time from a tenth of a radian to a quarter turn beyond (the same angles at every rate, so that the
// plate's lattice passes the paste's alike).
real steady_torque(const Geometry& g, const Material& paste, real rate, const RheometerOptions& o) {
  const real omega = rate * g.H / g.R, rim = omega * g.R;
  const real dt = std::min<real>(IisphParams{}.cfl * 2 * g.s / rim, 0.05);
  const real reach = g.nr + 6;
  ModelParams p = handling::rig_params(g.s, Vec3{-reach, -reach, -6} * g.s, Vec3{reach, reach, g.nz + 6.0} * g.s, dt, {});
  Model model = make_model(p);
  State st = plates_with(model, g, paste);
  const real from = 0.1, to = from + 0.5 * pi;
  real sum = 0, time = 0;
  while (omega * st.time < to - 1e-9) {
    st.tool_pose = Pose{{}, Quat::from_axis_angle({0, 0, 1}, omega * (st.time + dt))};
    handling::rig_step(model, st, o.run, "rheometer");
    if (omega * st.time > from) {
      sum += -st.tool_wrench.torque.z * dt;  // the paste's torque on the plate opposes its turning
      time += dt;
    }
  }
  return sum / time;
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
  HandlingFigure eta10{"viscosity at 10 /s", loglog_at(rates, viscosity, 10), "Pa s", std::nullopt, preset.source};
  if (preset.published_high > 0 && preset.temperature_c == 23)
    eta10.range = std::array<real, 2>{preset.published_low, preset.published_high};
  else if (preset.published_high > 0)
    eta10.source = fmt::format("the published range is at 23 C ({:.4g} to {:.4g} Pa s); this paste is at {:g} C",
                               preset.published_low, preset.published_high, preset.temperature_c);
  r.figures.push_back(eta10);
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
                       "the torque of a Newtonian standard over pi mu Omega R^4 / (2 H): divided out of every torque"});
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
  r.notes.push_back(fmt::format(
      "a disc of radius {:.2f} mm between plates {:.2f} mm apart, particles {:.2f} mm apart; the torque over the same "
      "quarter turn at each rate, read with the Weissenberg-Rabinowitsch correction",
      g.R * 1e3, g.H * 1e3, g.s * 1e3));
  r.notes.push_back(
      "the published figures are complex viscosities at 10 rad/s (oscillatory); the model has no elasticity, so its "
      "steady viscosity at 10 /s stands for them (the Cox-Merz rule)");
  return r;
}

}  // namespace dentsph
