// The iisph solver's pair pass: every particle's density (the paper's, rho_i = sum_j m_j
// W_poly6(r_ij), self included, or with the cubic spline's W where the model's kernel says so
// (KernelCoeffs::cubic_density); a boundary particle's boundary part is static, rho_static) and its
// row of neighbours within h:
//  - a material particle lists every neighbour: m_j gradW(r_i - r_j) (the spiky kernel's or the
//    cubic spline's, model.iisph.gradient) and the viscosity weight
//    (mu_i + mu_j)/2 m_j lapW_visc, material neighbours from the front of the row, boundary and tool
//    ones from the back, so that each solver sweep is a short loop over precomputed numbers;
//  - a boundary or tool particle lists its material neighbours alone (its density is a constraint of
//    the pressure solve, and its pressure pushes them);
//  - S_i = sum_j m_j gradW_ij (material) and diag_x, from which the pressure solve's diagonal comes;
//  - material and tool particles bond to the material closer than A (bonds::form_bonds, the paper's
//    step's rule).
// The neighbours come from the neighbour lists of the paper's step (radius h + skin, built here at a
// rebuild, kept until some material particle has moved half the skin; a boundary particle's holds
// its material neighbours) or, for an overflowed list, a search of the grid; the tool's, which the
// lists leave out, from tool_pairs.cpp, found every step.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "bonds/hysteresis.hpp"
#include "physics/kernels.hpp"
#include "solver/block_sum.hpp"
#include "solver/iisph.hpp"
#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph::iisph {

namespace {

// The neighbours of one particle within h, gathered without branches before its row is made (a
// neighbour list holds about a quarter of candidates beyond h, in no order a branch predictor
// could follow). Full, it is handed to the row and starts again.
struct Within {
  static constexpr std::uint32_t capacity = 64;
  std::uint32_t j[capacity + 1];
  real dx[capacity + 1], dy[capacity + 1], dz[capacity + 1], r2[capacity + 1];
  // Filled by the row from those: density term, m_j g / r, m_j g^2, viscosity weight.
  real rho[capacity], f[capacity], g2[capacity], visc[capacity];
  std::uint32_t n = 0;
};

// Builds the row of particle i from the neighbours handed to it, in the order given.
class RowBuilder {
 public:
  RowBuilder(const Model& model, State& s, IisphScratch& x, std::uint32_t i)
      : k_(model.kernel), s_(s), x_(x), i_(i), role_(s.role[i]), mi_(s.mass[i]), mu_i_(s.mu[i]),
        A2_(role_ == Role::boundary ? 0 : model.adhesion.A * model.adhesion.A), inv_h_(1 / k_.h),
        grad6_(6 * k_.cubic / k_.h), grad6_over_h_(grad6_ * inv_h_),
        spiky_(model.iisph.gradient == PressureGradient::spiky), unit_(x.rheology),
        projected_(10 / (spiky_ ? kProjectedShearSpiky : kProjectedShearCubic)), pairs_(x.pairs.data() + std::size_t(i) * IisphScratch::kPairStride) {}

  // Candidate j at d = r_i - r_j, r2 = |d|^2: kept when within h and not i itself.
  void offer(std::uint32_t j, const Vec3& d, real r2) {
    Within& w = within_;
    w.j[w.n] = j;
    w.dx[w.n] = d.x;
    w.dy[w.n] = d.y;
    w.dz[w.n] = d.z;
    w.r2[w.n] = r2;
    w.n += std::uint32_t(r2 < k_.h2) & std::uint32_t(j != i_);
    if (w.n == Within::capacity) take();
  }

  // Writes the row's sums and the density; forms the bonds of the close pairs.
  void finish(bonds::Events& ev, std::uint64_t& overflow) {
    take();
    flush_bonds();
    ev += events_;
    IisphScratch& x = x_;
    x.n_material[i_] = std::uint8_t(front_);
    x.n_other[i_] = std::uint8_t(IisphScratch::kPairStride - back_);
    const bool material = role_ == Role::material;
    x.grad_sum[i_] = S_;
    // a_ii = -dt^2 / rho_i^2 diag_x: p_i moves i itself (material: |S_i|^2) and its material
    // neighbours (m_i sum_j m_j |gradW_ij|^2); pressure.cpp.
    x.diag_x[i_] = (material ? norm2(S_) : 0) + mi_ * g2_;
    if (k_.cubic_density) {
      s_.rho[i_] = role_ == Role::boundary ? s_.rho_static[s_.id[i_]] + rho_sum_ : mi_ * k_.cubic + rho_sum_;
    } else {
      const real h6 = k_.h2 * k_.h2 * k_.h2;
      s_.rho[i_] = role_ == Role::boundary ? s_.rho_static[s_.id[i_]] + k_.poly6 * rho_sum_
                                           : k_.poly6 * (mi_ * h6 + rho_sum_);
    }
    x.inv_rho[i_] = 1 / s_.rho[i_];
    overflow += overflow_;
  }

 private:
  // Fills w's density terms, gradient terms (m_j g / r, m_j g^2) and viscosity weights for its
  // first n neighbours; radial(r) gives g and g / r.
  template <class Radial>
  void gradients(Within& w, std::uint32_t n, Radial radial) const {
    const real* mass = s_.mass.data();
    const real* mu = s_.mu.data();
    for (std::uint32_t e = 0; e < n; ++e) {
      const real r2 = w.r2[e], mj = mass[w.j[e]];
      const real wk = k_.h2 - r2;
      w.rho[e] = kernels::poly6_mass_term(mj, wk);
      const real r = std::sqrt(r2);
      const auto [g, g_over_r] = radial(r);
      w.f[e] = mj * g_over_r;
      w.g2[e] = mj * g * g;  // |m_j gradW|^2 / m_j
      // With a non-Newtonian material, the projected form's weight without the viscosity, 2 (d + 2) r /
      // ((r^2 + 0.01 h^2) m_j |g|) over its lattice share (model.hpp; rheology.cpp weighs it; 0 for
      // coincident particles, which have no direction).
      w.visc[e] = unit_ ? (g != 0 ? projected_ * r / ((r2 + 0.01 * k_.h2) * mj * std::abs(g)) : 0)
                        : 0.5 * (mu_i_ + mu[w.j[e]]) * mj * k_.visc_lap * (k_.h - r);
    }
    // The cubic spline's density terms, m_j W(r_ij) (finish() then applies no constant).
    if (k_.cubic_density)
      for (std::uint32_t e = 0; e < n; ++e) w.rho[e] = mass[w.j[e]] * kernels::cubic(std::sqrt(w.r2[e]), k_);
  }

  // The gathered neighbours into the row.
  void take() {
    Within& w = within_;
    const std::uint32_t n = w.n;
    // Each neighbour's numbers first, in a loop without branches the compiler can vectorise
    // (one loop per gradient): its density term, the kernel's radial derivative g (r < h here) and
    // g / r, and the viscosity weight.
    if (spiky_)
      gradients(w, n, [this](real r) {
        // The spiky kernel's (kernels::spiky_grad_radial) over kSpikyLatticeGradient; g / r = 0 for
        // coincident particles (no direction).
        const real c = k_.h - r;
        const real g = -k_.spiky_lattice * c * c;
        return std::pair<real, real>{g, r > 0 ? g / r : 0};
      });
    else
      gradients(w, n, [this](real r) {
        // The cubic spline's (kernels::cubic_grad_radial): for q = r / h <= 1/2,
        // g = grad6 q (3 q - 2) and g / r = grad6 (3 q - 2) / h, so the division is needed beyond
        // h / 2 alone (computed for both, the other selected; r = 0 selects the first).
        const real q = r * inv_h_;
        const real inner_over_r = grad6_over_h_ * (3 * q - 2);
        const real c = 1 - q;
        const real outer = -grad6_ * c * c;
        const real outer_over_r = outer / r;  // r = 0 (coincident particles): not selected
        const bool inner = q <= 0.5;
        return std::pair<real, real>{inner ? inner_over_r * r : outer, inner ? inner_over_r : outer_over_r};
      });
    // Then the row, in the order given: the density's sum over all of them; a material row lists
    // every one (material from the front, boundary and tool from the back), a boundary or tool row
    // its material ones.
    const bool row_material = role_ == Role::material;
    for (std::uint32_t e = 0; e < n; ++e) {
      const std::uint32_t j = w.j[e];
      rho_sum_ += w.rho[e];
      const bool material = s_.role[j] == Role::material;
      if (!material && !row_material) continue;  // boundary and tool rows list material alone
      if (front_ == back_) {  // the row is full: counted, never expected near rest density
        ++overflow_;
        continue;
      }
      const real f = w.f[e];
      const Vec3 grad{w.dx[e] * f, w.dy[e] * f, w.dz[e] * f};
      const std::uint32_t slot = material ? front_ : back_ - 1;
      front_ += std::uint32_t(material);
      back_ -= std::uint32_t(!material);
      pairs_[slot] = {float(grad.x), float(grad.y), float(grad.z), float(w.visc[e]), j};
      S_ += grad;
      g2_ += material ? w.g2[e] : 0;
      close_[n_close_] = j;
      n_close_ += std::uint32_t(w.r2[e] < A2_);
    }
    w.n = 0;
    if (n_close_ > kClose - Within::capacity) flush_bonds();
  }

  void flush_bonds() {
    if (n_close_ > 0) bonds::form_bonds(s_, i_, close_, n_close_, events_);
    n_close_ = 0;
  }

  static constexpr std::uint32_t kClose = 2 * Within::capacity + 1;
  const KernelCoeffs& k_;
  State& s_;
  IisphScratch& x_;
  std::uint32_t i_;
  Role role_;
  real mi_, mu_i_, A2_, inv_h_, grad6_, grad6_over_h_;
  bool spiky_, unit_;
  real projected_;
  SolverPair* pairs_;
  std::uint32_t front_ = 0, back_ = IisphScratch::kPairStride;
  real rho_sum_ = 0, g2_ = 0;
  Vec3 S_;
  Within within_;
  std::uint32_t close_[kClose];
  std::uint32_t n_close_ = 0;
  bonds::Events events_;
  std::uint64_t overflow_ = 0;
};

// Which neighbours particle i lists: a boundary particle the moving ones (its boundary part is
// static), the others all.
grid::Visit listed(const State& s, std::uint32_t i) {
  return s.role[i] == Role::boundary ? grid::Visit::moving : grid::Visit::all;
}

// The grid search around particle i, over the sorted coordinates (valid after a reorder) or, between
// rebuilds, over the positions themselves.
template <class Fn>
void search(const Model& model, const State& s, std::uint32_t i, bool sorted, Fn&& fn) {
  const GridIndex& g = s.grid;
  const Vec3 pi = s.pos[i];
  grid::for_each_neighbour_range(model.grid, g, pi, listed(s, i), [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j) {
      const Vec3 d = sorted ? Vec3{pi.x - g.x[j], pi.y - g.y[j], pi.z - g.z[j]} : pi - s.pos[j];
      fn(j, d, norm2(d));
    }
  });
}

// Rebuild: the search writes i's list of neighbours within h + skin (as the paper's density pass
// does: every candidate written at the count, the count advancing for those within reach; past the
// capacity it marks the overflow). The search is the rebuild's cost (about five candidates of the
// 27 cells for each one within reach), so it does nothing else; the row is then made from the list
// as between rebuilds (the same neighbours in the same order, the same positions: the sorted
// coordinates are the positions' copies). Returns whether the list holds them all.
bool build_list(const Model& model, State& s, std::uint32_t i) {
  GridIndex& g = s.grid;
  const real reach = model.kernel.h + model.neighbour_skin, reach2 = reach * reach;
  constexpr std::uint32_t cap = GridIndex::kNeighbourCapacity;
  std::uint32_t* list = g.neighbours.data() + std::size_t(i) * GridIndex::kNeighbourStride;
  std::uint32_t count = 0;
  const real xi = s.pos[i].x, yi = s.pos[i].y, zi = s.pos[i].z;
  const real* x = g.x.data();
  const real* y = g.y.data();
  const real* z = g.z.data();
  grid::for_each_neighbour_range(model.grid, g, s.pos[i], listed(s, i), [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j) {
      const real dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
      const std::uint32_t within = (dx * dx + dy * dy + dz * dz < reach2) & (j != i) & (s.role[j] != Role::tool);
      list[count < cap ? count : cap] = j;
      count += within;
    }
  });
  g.neighbour_count[i] = std::uint16_t(count > cap ? cap + 1 : count);
  return count <= cap;
}

// Offers the row of particle i the neighbours list[0, count).
void offer(const State& s, std::uint32_t i, const std::uint32_t* list, std::uint32_t count, RowBuilder& row) {
  const Vec3 pi = s.pos[i];
  for (std::uint32_t q = 0; q < count; ++q) {
    const std::uint32_t j = list[q];
    const Vec3 d = pi - s.pos[j];
    row.offer(j, d, norm2(d));
  }
}

// The row of material or boundary particle i: its listed neighbours (or, for an overflowed list,
// those of a search of the grid), then its tool neighbours (tool_pairs.cpp).
void offer_lists(const Model& model, const State& s, const IisphScratch& x, std::uint32_t i, bool listed_all, bool sorted, RowBuilder& row) {
  const GridIndex& g = s.grid;
  if (listed_all) {
    offer(s, i, g.neighbours.data() + std::size_t(i) * GridIndex::kNeighbourStride, g.neighbour_count[i], row);
  } else {  // every candidate of the grid offered, the tool's left to its own pairs
    search(model, s, i, sorted, [&](std::uint32_t j, const Vec3& d, real r2) {
      if (s.role[j] != Role::tool) row.offer(j, d, r2);
    });
  }
  offer(s, i, x.link_tool.data() + x.link_start[i], x.link_start[i + 1] - x.link_start[i], row);
}

}  // namespace

void compute_pairs(const Model& model, State& s, IisphScratch& x, int threads, bool build_lists) {
  if (!s.rho_static_valid) stages::compute_static_density(model, s);  // after particles were added
  std::uint64_t formed = 0, overflowed = 0, pair_overflow = find_tool_pairs(model, s, x, threads);
  auto finish_row = [&](RowBuilder& row) {
    bonds::Events ev;
    std::uint64_t over = 0;
    row.finish(ev, over);
    return std::array<std::uint64_t, 3>{ev.formed, ev.overflowed, over};
  };
  // The material and boundary rows.
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : formed, overflowed, pair_overflow)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::uint32_t i = std::uint32_t(k);
    if (s.role[i] == Role::tool) continue;
    RowBuilder row(model, s, x, i);
    const bool listed_all = build_lists ? build_list(model, s, i) : s.grid.neighbour_count[i] <= GridIndex::kNeighbourCapacity;
    offer_lists(model, s, x, i, listed_all, build_lists, row);
    const auto [f, o, p] = finish_row(row);
    formed += f;
    overflowed += o;
    pair_overflow += p;
  }
  // The tool rows, from the tool's pairs.
  const std::int64_t tools = std::int64_t(x.tools.size());
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : formed, overflowed, pair_overflow)
  for (std::int64_t k = 0; k < tools; ++k) {
    const std::uint32_t i = x.tools[k];
    RowBuilder row(model, s, x, i);
    offer(s, i, x.tool_list.data() + std::size_t(k) * IisphScratch::kToolStride, x.tool_count[k], row);
    const auto [f, o, p] = finish_row(row);
    formed += f;
    overflowed += o;
    pair_overflow += p;
  }
  bonds::Events total;
  total.formed = formed;
  total.overflowed = overflowed;
  bonds::record(s, total);
  s.diagnostics.pair_overflow = pair_overflow;
  // The compression the material has now, measured from its density: summed in fixed blocks, so
  // that every thread count reports the same (block_sum.hpp; the cg solve's block sums, free until
  // its start, hold the sum and the largest).
  const std::int64_t nm = std::int64_t(x.material.size());
  const PressureSums c = for_rows_summed(nm, threads, x.pc_partial.data(), [&](std::int64_t m) {
    const std::uint32_t i = x.material[m];
    PressureSums one;
    one.sum[0] = std::max<real>(0, s.rho[i] / s.rho0[i] - 1);
    one.max = one.sum[0];
    return one;
  });
  s.diagnostics.compression_mean = nm > 0 ? c.sum[0] / real(nm) : 0;
  s.diagnostics.compression_max = nm > 0 ? c.max : 0;
}

}  // namespace dentsph::iisph
