// The GPU backend's algorithm on the CPU: the same stage bodies, views and buffers as the CUDA
// build, each kernel a loop over its indices, CUB's stable radix sort a stable sort, the block
// reductions sums over blocks of kBlock particles. Tests hold it to the CPU reference, so that
// everything of the GPU backend but launches, CUB, graphs and device memory is tested everywhere.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

#include "backend/cuda/buffers.hpp"
#include "backend/cuda/engine.hpp"
#include "backend/cuda/density.hpp"
#include "backend/cuda/forces.hpp"
#include "backend/cuda/hash.hpp"
#include "backend/cuda/integrate.hpp"
#include "backend/cuda/pressure.hpp"
#include "backend/cuda/reduce.hpp"
#include "backend/cuda/reorder.hpp"
#include "backend/cuda/sort.hpp"
#include "backend/cuda/tool_wrench.hpp"

namespace dentsph::gpu {

namespace {

struct HostMemory {
  template <class T>
  T* alloc(std::size_t n) {
    void* p = std::malloc(std::max<std::size_t>(1, n) * sizeof(T));
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void release(void* p) { std::free(p); }
  template <class T>
  void to_device(T* d, const T* h, std::size_t n) {
    if (n) std::memcpy(static_cast<void*>(d), static_cast<const void*>(h), n * sizeof(T));
  }
  template <class T>
  void to_host(T* h, const T* d, std::size_t n) {
    if (n) std::memcpy(static_cast<void*>(h), static_cast<const void*>(d), n * sizeof(T));
  }
};

// Each "launch": body(i) for i in [0, n).
template <class Body>
void launch(std::uint32_t n, Body&& body) {
  for (std::uint32_t i = 0; i < n; ++i) body(i);
}

class EmulatedEngine final : public Engine {
 public:
  EmulatedEngine(const Model& model, const State& state) : Engine(model) {
    buf_.upload(model, state);
    start_from(state);
    prepare();
  }

  void step(const Pose& tool_pose) override { run(tool_pose, nullptr); }
  void step_timed(const Pose& tool_pose, StageTimes& times) override { run(tool_pose, &times); }
  void download(State& state) const override {
    buf_.download(state, *buf_.base().events);
    copy_results(state);
  }
  void reload(const State& state) override {
    buf_.put_state(state);
    start_from(state);
    prepare();
  }
  std::string device_name() const override { return "host emulation of the CUDA backend"; }

 private:
  // The broad phase of a step: keys, sort and cell ranges, reorder.
  static void hash(const gpu::StepView& v) {
    launch(v.n, [&](std::uint32_t i) { gpu::hash_body(v, i); });
  }
  static void sort(const gpu::StepView& v) {
    std::copy(v.iota, v.iota + v.n, v.order);
    std::stable_sort(v.order, v.order + v.n, [&](std::uint32_t a, std::uint32_t b) { return v.key[a] < v.key[b]; });
    launch(v.n, [&](std::uint32_t k) { v.key_sorted[k] = v.key[v.order[k]]; });
    std::fill(v.bucket_begin, v.bucket_begin + 2 * std::size_t(v.buckets), 0u);  // begin and end
    launch(v.n, [&](std::uint32_t k) { gpu::cell_range_body(v, k); });
  }
  static void reorder(const gpu::StepView& v) {
    launch(v.n, [&](std::uint32_t k) { gpu::reorder_body(v, k); });
  }

  // After the upload: the static boundary density, once (and rho, pressure for the new order).
  void prepare() {
    const gpu::StepView v = buf_.next_view();
    hash(v);
    sort(v);
    reorder(v);
    launch(v.n, [&](std::uint32_t i) { gpu::static_density_body(v, i); });
    launch(v.n, [&](std::uint32_t i) { gpu::density_body(v, i); });
    launch(v.n, [&](std::uint32_t i) { gpu::pressure_body(v, i); });
    std::fill(v.force, v.force + v.n, Vec3{});
    buf_.flip();
  }

  template <class Body>
  static void block_sums(const gpu::StepView& v, gpu::StepSums* partials, Body&& body) {
    for (std::uint32_t b = 0; b < gpu::blocks_for(v.n); ++b) {
      gpu::StepSums s;
      for (std::uint32_t i = b * gpu::kBlock; i < std::min(v.n, (b + 1) * gpu::kBlock); ++i) s.add(body(i));
      partials[b] = s;
    }
  }

  void run(const Pose& tool_pose, StageTimes* times) {
    *buf_.tool() = gpu::tool_input(tool_pose, tool_pose_applied());
    const gpu::StepView v = buf_.next_view();
    auto t = std::chrono::steady_clock::now();
    auto lap = [&](double StageTimes::*field) {
      if (!times) return;
      const auto now = std::chrono::steady_clock::now();
      times->*field += std::chrono::duration<double, std::micro>(now - t).count();
      t = now;
    };
    hash(v);
    lap(&StageTimes::hash_us);
    sort(v);
    lap(&StageTimes::sort_us);
    reorder(v);
    lap(&StageTimes::reorder_us);
    launch(v.n, [&](std::uint32_t i) { gpu::density_body(v, i); });
    lap(&StageTimes::density_us);
    launch(v.n, [&](std::uint32_t i) { gpu::pressure_body(v, i); });
    lap(&StageTimes::pressure_us);
    launch(v.n, [&](std::uint32_t i) {
      gpu::BondEvents ev;
      gpu::forces_body(v, i, ev);
      v.events->formed += ev.formed;
      v.events->broken += ev.broken;
      v.events->overflowed += ev.overflowed;
    });
    lap(&StageTimes::forces_us);
    const std::uint32_t blocks = gpu::blocks_for(v.n);
    block_sums(v, v.partials, [&](std::uint32_t i) { return gpu::wrench_term(v, i); });
    lap(&StageTimes::wrench_us);
    block_sums(v, v.partials + blocks, [&](std::uint32_t i) { return gpu::integrate_body(v, i); });
    gpu::finish_body(v);
    lap(&StageTimes::integrate_us);
    if (times) ++times->steps;
    buf_.flip();
    const gpu::StepResults r = gpu::results_of(*v.out, buf_.base_counters());
    finish_step(r.wrench, r.diagnostics, r.counters, tool_pose);
  }

  gpu::Buffers<HostMemory> buf_;
};

}  // namespace

std::unique_ptr<Engine> make_emulated_engine(const Model& model, const State& state) {
  return std::make_unique<EmulatedEngine>(model, state);
}

}  // namespace dentsph::gpu
