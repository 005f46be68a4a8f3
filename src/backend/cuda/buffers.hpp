// The GPU backend's memory, sized once from a State (docs/cuda.md): every array of the StepView,
// allocated through a memory policy (device memory in the CUDA build, host memory in the
// emulation), and the upload of a State into it and the download back. No allocation after the
// upload: a step only reads and writes these arrays.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "backend/cuda/view.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph::gpu {

// The rigid transform of a pose, for the device (p = R a + t).
inline ToolInput tool_input(const Pose& target, const Pose& applied) {
  ToolInput in;
  const Vec3 cx = target.orientation.rotate({1, 0, 0}), cy = target.orientation.rotate({0, 1, 0}),
             cz = target.orientation.rotate({0, 0, 1});
  const real R[9] = {cx.x, cy.x, cz.x, cx.y, cy.y, cz.y, cx.z, cy.z, cz.z};
  std::copy(R, R + 9, in.R);
  in.t = target.position;
  in.applied = applied.position;
  return in;
}

// A step's output as the public types: the wrench, the diagnostics, the bond counters (the
// state's at the upload plus the events since).
struct StepResults {
  ToolWrench wrench;
  StepDiagnostics diagnostics;
  BondCounters counters;
};

inline StepResults results_of(const StepOutput& out, const BondCounters& base) {
  StepResults r;
  r.wrench.force = out.sums.force;
  r.wrench.torque = out.sums.torque;
  r.diagnostics.rebuilt = true;  // the GPU sorts every step
  r.diagnostics.max_accel = std::sqrt(out.sums.a2max);
  r.diagnostics.max_speed = std::sqrt(out.sums.v2max);
  r.diagnostics.non_finite = out.sums.non_finite;
  r.counters.formed = base.formed + out.events.formed;
  r.counters.broken = base.broken + out.events.broken;
  r.counters.overflowed = base.overflowed + out.events.overflowed;
  return r;
}

// Memory must provide: template <class T> T* alloc(std::size_t n); void release(void* p);
// template <class T> void to_device(T* d, const T* h, std::size_t n);
// template <class T> void to_host(T* h, const T* d, std::size_t n).
template <class Memory>
class Buffers {
 public:
  explicit Buffers(Memory memory = {}) : mem_(memory) {}
  Buffers(const Buffers&) = delete;
  Buffers& operator=(const Buffers&) = delete;
  ~Buffers() {
    for (void* p : owned_) mem_.release(p);
  }

  // Sizes every array for `state` under `model` and copies the state in (as set 0).
  void upload(const Model& model, const State& s) {
    allocate(model, s);
    put_state(s);
  }

  // Copies `s` in (as set 0) over the arrays sized for a State of its size: the memory, and the
  // graphs captured on it, stay.
  void put_state(const State& s) {
    const std::uint32_t n = s.size();
    if (n != v_.n)
      throw std::logic_error("GPU backend: a state of " + std::to_string(n) + " particles put into memory sized for " +
                             std::to_string(v_.n));
    const int cap = v_.bond_capacity;
    each_array(sets_[0], s, [&](auto* d, const auto& h) { put(d, h); });
    std::vector<std::uint32_t> iota(n), count(n), partner(std::size_t(n) * cap, 0);
    std::iota(iota.begin(), iota.end(), 0u);
    put(v_.iota, iota);
    for (std::uint32_t id = 0; id < n; ++id) {
      count[id] = std::uint32_t(std::min(s.bonds.count(id), cap));
      for (std::uint32_t k = 0; k < count[id]; ++k) partner[std::size_t(id) * cap + k] = s.bonds.partner(id, int(k));
    }
    put(v_.bond_count, count);
    put(v_.bond_partner, partner);
    const BondEvents none;
    mem_.to_device(v_.events, &none, 1);
    base_counters_ = s.bonds.counters;
    current_ = 0;
  }

  // Threads per block of the neighbour passes (a launch shape; set before the graphs are captured).
  void set_neighbour_block(std::uint32_t threads) { v_.neighbour_block = threads; }

  // The view of the next step: it reads the current set and sorts into the other.
  StepView next_view() const {
    StepView v = v_;
    v.src = sets_[current_];
    v.p = sets_[1 - current_];
    return v;
  }
  // The view of a given direction (0: set 0 -> set 1, 1: set 1 -> set 0), for graphs captured once.
  StepView view(int direction) const {
    StepView v = v_;
    v.src = sets_[direction];
    v.p = sets_[1 - direction];
    return v;
  }
  // After a step: the sorted set holds the particles now.
  void flip() { current_ = 1 - current_; }
  int current() const { return current_; }
  ToolInput* tool() const { return tool_; }
  StepOutput* output() const { return v_.out; }
  const StepView& base() const { return v_; }
  const BondCounters& base_counters() const { return base_counters_; }
  Memory& memory() { return mem_; }

  // Copies the particles (in their current order), their bonds and the per-particle results into
  // `s`. The bond counters are the state's at the upload plus the events since.
  void download(State& s, const BondEvents& events) const {
    const std::uint32_t n = v_.n;
    each_array(sets_[current_], s, [&](const auto* d, auto& h) { get(h, d, n); });
    get(s.rho_static, v_.rho_static, n);
    s.rho_static_valid = true;
    const int cap = v_.bond_capacity;
    std::vector<std::uint32_t> count, partner;
    get(count, v_.bond_count, n);
    get(partner, v_.bond_partner, std::size_t(n) * cap);
    s.bonds = BondStore{};
    s.bonds.resize(n, cap);
    for (std::uint32_t id = 0; id < n; ++id)
      for (std::uint32_t k = 0; k < count[id]; ++k) s.bonds.try_add(id, partner[std::size_t(id) * cap + k]);
    s.bonds.counters.formed = base_counters_.formed + events.formed;
    s.bonds.counters.broken = base_counters_.broken + events.broken;
    s.bonds.counters.overflowed = base_counters_.overflowed + events.overflowed;
    s.grid.lists_valid = false;  // the CPU's neighbour lists do not know the GPU's order
    s.order_stamp = new_state_stamp();  // nor does what a solver object listed in the old one
  }

 private:
  // Sizes every array for a State of `s`'s size under `model`.
  void allocate(const Model& model, const State& s) {
    const std::uint32_t n = s.size();
    const std::uint64_t buckets = 2 * std::uint64_t(model.grid.cell_count());
    if (n == 0) throw std::invalid_argument("GPU backend: the state has no particles");
    if (buckets >= (std::uint64_t(1) << 32))
      throw std::invalid_argument("GPU backend: the grid has " + std::to_string(buckets / 2) +
                                  " cells, over the 2^31 the 32-bit sort keys allow; enlarge the kernel support or "
                                  "shrink simulation.domain");
    const int cap = model.max_bonds_per_particle;
    v_.n = n;
    v_.buckets = std::uint32_t(buckets);
    // n of each array a State has too, in both sets and for the step's results.
    auto per_particle = [&](auto*& d, const auto& h) { d = alloc<typename std::decay_t<decltype(h)>::value_type>(n); };
    for (ParticleArrays& a : sets_) each_set_array(a, s, per_particle);
    each_result_array(v_, s, per_particle);
    v_.key = alloc<std::uint32_t>(n);
    v_.key_sorted = alloc<std::uint32_t>(n);
    v_.iota = alloc<std::uint32_t>(n);
    v_.order = alloc<std::uint32_t>(n);
    v_.bucket_begin = alloc<std::uint32_t>(2 * buckets);  // begin and end in one block: one clear
    v_.bucket_end = v_.bucket_begin + buckets;
    v_.rho_static = alloc<real>(n);
    v_.bond_count = alloc<std::uint32_t>(n);
    v_.bond_partner = alloc<std::uint32_t>(std::size_t(n) * cap);
    v_.bond_capacity = cap;
    v_.events = alloc<BondEvents>(1);
    v_.partial_count = 2 * blocks_for(n);
    v_.partials = alloc<StepSums>(v_.partial_count);
    v_.tool = tool_ = alloc<ToolInput>(1);
    v_.out = alloc<StepOutput>(1);
    v_.grid = model.grid;
    v_.kernel = model.kernel;
    v_.adhesion = model.adhesion;
    v_.gravity = model.gravity;
    v_.dt = model.dt;
  }

  // Call fn(device array, state vector) for every per-particle array of a set (`a`), and of the
  // step's results (`v`), that a State holds in the same order (rho_static, by id, and the bonds
  // apart). The arrays are passed as lvalues: fn may set them (the allocation) or read them.
  template <class A, class S, class Fn>
  static void each_set_array(A& a, S& s, Fn&& fn) {
    fn(a.id, s.id);
    fn(a.role, s.role);
    fn(a.pos, s.pos);
    fn(a.vel, s.vel);
    fn(a.anchor, s.anchor);
    fn(a.mass, s.mass);
    fn(a.material, s.material);
    fn(a.mu, s.mu);
    fn(a.Kp, s.Kp);
    fn(a.rho0, s.rho0);
    fn(a.Ka, s.Ka);
  }
  template <class V, class S, class Fn>
  static void each_result_array(V& v, S& s, Fn&& fn) {
    fn(v.index_of_id, s.index_of_id);
    fn(v.rho, s.rho);
    fn(v.pressure, s.pressure);
    fn(v.volume, s.volume);
    fn(v.force, s.force);
  }
  template <class S, class Fn>
  void each_array(const ParticleArrays& a, S& s, Fn&& fn) const {
    each_set_array(a, s, fn);
    each_result_array(v_, s, fn);
  }

  template <class T>
  T* alloc(std::size_t n) {
    T* p = mem_.template alloc<T>(n);
    owned_.push_back(p);
    return p;
  }
  template <class T>
  void put(T* d, const std::vector<T>& h) {
    mem_.to_device(d, h.data(), h.size());
  }
  template <class T>
  void get(std::vector<T>& h, const T* d, std::size_t n) const {
    h.resize(n);
    mem_.to_host(h.data(), d, n);
  }

  mutable Memory mem_;
  std::vector<void*> owned_;
  ParticleArrays sets_[2];
  StepView v_;
  ToolInput* tool_ = nullptr;
  BondCounters base_counters_;
  int current_ = 0;
};

}  // namespace dentsph::gpu
