// The CUDA stepper (docs/cuda.md): device memory sized once from the State, the step captured once
// per direction as a CUDA graph and replayed; the tool pose goes in and the step's output comes
// out through pinned host memory, one small copy each way inside the graph, and the one host
// synchronisation per step waits for that output.
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include <cuda_runtime_api.h>
#include <fmt/format.h>

#include "backend/cuda/buffers.hpp"
#include "backend/cuda/engine.hpp"
#include "backend/cuda/launch.hpp"
#include "dentsph/backend.hpp"

namespace dentsph {

namespace {

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw std::runtime_error(fmt::format("CUDA backend: {}: {}", what, cudaGetErrorString(e)));
}

struct DeviceMemory {
  template <class T>
  T* alloc(std::size_t n) {
    void* p = nullptr;
    const std::size_t bytes = (n > 0 ? n : 1) * sizeof(T);
    if (const cudaError_t e = cudaMalloc(&p, bytes); e != cudaSuccess) {
      std::size_t free = 0, total = 0;
      cudaGetLastError();
      cudaMemGetInfo(&free, &total);
      throw std::runtime_error(fmt::format(
          "CUDA backend: cannot allocate {} MiB of device memory ({}); {} of {} MiB free: the scene is too large "
          "for this GPU",
          bytes >> 20, cudaGetErrorString(e), free >> 20, total >> 20));
    }
    return static_cast<T*>(p);
  }
  void release(void* p) { cudaFree(p); }
  template <class T>
  void to_device(T* d, const T* h, std::size_t n) {
    if (n) check(cudaMemcpy(d, h, n * sizeof(T), cudaMemcpyHostToDevice), "upload");
  }
  template <class T>
  void to_host(T* h, const T* d, std::size_t n) {
    if (n) check(cudaMemcpy(h, d, n * sizeof(T), cudaMemcpyDeviceToHost), "download");
  }
};

std::string describe(const cudaDeviceProp& p) {
  return fmt::format("{} (compute capability {}.{}, {} multiprocessors, {:.0f} GiB)", p.name, p.major, p.minor,
                     p.multiProcessorCount, double(p.totalGlobalMem) / (1 << 30));
}

// Threads per block of the neighbour passes: DENTSPH_CUDA_NEIGHBOUR_BLOCK (32 to 1024, a multiple
// of 32) lets a benchmark compare launch shapes without a rebuild; 256 otherwise, the fastest of 32,
// 64, 128 and 256 on every scene measured on an H100 (docs/cuda.md; bench/results/nvidia-h100-80gb-hbm3.txt).
std::uint32_t neighbour_block() {
  const char* env = std::getenv("DENTSPH_CUDA_NEIGHBOUR_BLOCK");
  if (!env) return 256;
  const long t = std::strtol(env, nullptr, 10);
  if (t < 32 || t > 1024 || t % 32 != 0)
    throw std::invalid_argument(fmt::format("DENTSPH_CUDA_NEIGHBOUR_BLOCK={}: give a multiple of 32 from 32 to 1024", env));
  return std::uint32_t(t);
}

class CudaEngine final : public gpu::Engine {
 public:
  CudaEngine(const Model& model, const State& state) : Engine(model) {
    const CudaStatus st = cuda_status();
    if (!st.available) throw CudaUnavailable(st.reason);
    device_ = st.device;
    // The haptic step waits for every step's force: spinning wakes the host sooner than yielding
    // or blocking. Refused (and harmless) once the device's context runs with other flags.
    if (cudaSetDeviceFlags(cudaDeviceScheduleSpin) != cudaSuccess) cudaGetLastError();
    check(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "stream");
    buf_.upload(model, state);
    buf_.set_neighbour_block(neighbour_block());
    start_from(state);
    scratch_.bytes = gpu::sort_scratch_bytes(buf_.base());
    scratch_.ptr = buf_.memory().alloc<unsigned char>(scratch_.bytes);
    check(cudaHostAlloc(reinterpret_cast<void**>(&in_), sizeof(gpu::ToolInput), cudaHostAllocDefault), "pinned input");
    check(cudaHostAlloc(reinterpret_cast<void**>(&out_), sizeof(gpu::StepOutput), cudaHostAllocDefault),
          "pinned output");
    *in_ = gpu::ToolInput{};
    *out_ = gpu::StepOutput{};
    for (cudaEvent_t& e : marks_) check(cudaEventCreate(&e), "event");
    prepare();
    for (int dir = 0; dir < 2; ++dir) capture(dir);
  }

  ~CudaEngine() override {
    if (stream_) cudaStreamSynchronize(stream_);
    for (cudaGraphExec_t g : exec_)
      if (g) cudaGraphExecDestroy(g);
    for (cudaEvent_t e : marks_)
      if (e) cudaEventDestroy(e);
    if (scratch_.ptr) cudaFree(scratch_.ptr);
    if (in_) cudaFreeHost(in_);
    if (out_) cudaFreeHost(out_);
    if (stream_) cudaStreamDestroy(stream_);
  }

  void step(const Pose& tool_pose) override {
    *in_ = gpu::tool_input(tool_pose, tool_pose_applied());
    check(cudaGraphLaunch(exec_[buf_.current()], stream_), "graph launch");
    check(cudaStreamSynchronize(stream_), "step");  // the one wait: the step's force
    finish(tool_pose);
  }

  void step_timed(const Pose& tool_pose, StageTimes& times) override {
    *in_ = gpu::tool_input(tool_pose, tool_pose_applied());
    const gpu::StepView v = buf_.next_view();
    check(cudaMemcpyAsync(buf_.tool(), in_, sizeof(gpu::ToolInput), cudaMemcpyHostToDevice, stream_), "pose in");
    check(gpu::enqueue_step(v, scratch_, stream_, marks_), "step");
    check(cudaMemcpyAsync(out_, v.out, sizeof(gpu::StepOutput), cudaMemcpyDeviceToHost, stream_), "output");
    check(cudaStreamSynchronize(stream_), "step");
    double StageTimes::*fields[8] = {&StageTimes::hash_us,     &StageTimes::sort_us,     &StageTimes::reorder_us,
                                     &StageTimes::density_us,  &StageTimes::pressure_us, &StageTimes::forces_us,
                                     &StageTimes::wrench_us,   &StageTimes::integrate_us};
    for (int k = 0; k < 8; ++k) {
      float ms = 0;
      check(cudaEventElapsedTime(&ms, marks_[k], marks_[k + 1]), "stage time");
      times.*fields[k] += 1e3 * double(ms);
    }
    ++times.steps;
    finish(tool_pose);
  }

  void download(State& state) const override {
    check(cudaStreamSynchronize(stream_), "download");
    buf_.download(state, out_->events);
    copy_results(state);
  }

  // The same memory and the same graphs: upload, sort and the static boundary density again.
  void reload(const State& state) override {
    check(cudaStreamSynchronize(stream_), "reload");
    buf_.put_state(state);
    start_from(state);
    *out_ = gpu::StepOutput{};  // its bond events count from the upload
    prepare();
  }

  std::string device_name() const override { return device_; }

 private:
  // After the upload: sort once, the static boundary density, and rho and pressure in that order.
  void prepare() {
    const gpu::StepView v = buf_.next_view();
    check(gpu::launch_hash(v, stream_), "hash");
    check(gpu::launch_sort(v, scratch_, stream_), "sort");
    check(gpu::launch_reorder(v, stream_), "reorder");
    check(gpu::launch_static_density(v, stream_), "static density");
    check(gpu::launch_density(v, stream_), "density");
    check(gpu::launch_pressure(v, stream_), "pressure");
    check(cudaMemsetAsync(v.force, 0, sizeof(Vec3) * v.n, stream_), "force");
    check(cudaStreamSynchronize(stream_), "prepare");
    buf_.flip();
  }

  // The step reading set `dir` and sorting into the other, with the pose copy in and the output
  // copy out, as one graph.
  void capture(int dir) {
    const gpu::StepView v = buf_.view(dir);
    cudaGraph_t graph = nullptr;
    check(cudaStreamBeginCapture(stream_, cudaStreamCaptureModeThreadLocal), "begin capture");
    cudaError_t e = cudaMemcpyAsync(buf_.tool(), in_, sizeof(gpu::ToolInput), cudaMemcpyHostToDevice, stream_);
    if (e == cudaSuccess) e = gpu::enqueue_step(v, scratch_, stream_);
    if (e == cudaSuccess) e = cudaMemcpyAsync(out_, v.out, sizeof(gpu::StepOutput), cudaMemcpyDeviceToHost, stream_);
    const cudaError_t end = cudaStreamEndCapture(stream_, &graph);
    check(e, "capture");
    check(end, "end capture");
    e = cudaGraphInstantiate(&exec_[dir], graph, 0);
    cudaGraphDestroy(graph);
    check(e, "graph instantiate");
    check(cudaGraphUpload(exec_[dir], stream_), "graph upload");  // not on the first step's time
  }

  void finish(const Pose& tool_pose) {
    buf_.flip();
    const gpu::StepResults r = gpu::results_of(*out_, buf_.base_counters());
    finish_step(r.wrench, r.diagnostics, r.counters, tool_pose);
  }

  std::string device_;
  cudaStream_t stream_ = nullptr;
  gpu::Buffers<DeviceMemory> buf_;
  gpu::SortScratch scratch_;
  gpu::ToolInput* in_ = nullptr;     // pinned
  gpu::StepOutput* out_ = nullptr;   // pinned
  cudaGraphExec_t exec_[2] = {nullptr, nullptr};
  cudaEvent_t marks_[9] = {};
};

}  // namespace

bool cuda_built() { return true; }

CudaStatus cuda_status() {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    cudaGetLastError();
    return {false,
            fmt::format("no CUDA device: {}", e != cudaSuccess ? cudaGetErrorString(e) : "cudaGetDeviceCount found none"),
            ""};
  }
  int dev = 0;
  cudaDeviceProp p{};
  if (cudaGetDevice(&dev) != cudaSuccess || cudaGetDeviceProperties(&p, dev) != cudaSuccess) {
    cudaGetLastError();
    return {false, "no CUDA device: its properties cannot be read", ""};
  }
  return {true, "", describe(p)};
}

std::unique_ptr<gpu::Engine> gpu::make_cuda_engine(const Model& model, const State& state) {
  return std::make_unique<CudaEngine>(model, state);
}

}  // namespace dentsph
