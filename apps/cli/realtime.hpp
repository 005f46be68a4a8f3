// `dentsph run --realtime`: the haptic runtime's options on the run command and the run itself
// (docs/haptics.md).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "dentsph/haptics.hpp"

namespace dentsph::cli {

class RealtimeCommand {
 public:
  // Adds --realtime and its options to `run`.
  void add_options(CLI::App& run);
  // Adds the device and rendering options alone (--device, --mode, --profile, --port, ...), each
  // requiring `gate` when given (the viewer has no --realtime flag).
  void add_device_options(CLI::App& app, CLI::Option* gate = nullptr);
  bool enabled() const { return realtime_; }
  const std::string& device_name() const { return device_; }
  // The runtime's options from the command line, for `scene` (duration in wall seconds).
  RealtimeOptions options(const Scene& scene, double duration_s, int threads, bool allow_unstable,
                          const std::filesystem::path& out_dir) const;
  // The chosen device (a UDP bridge is bound and says where it listens).
  std::unique_ptr<Device> make_device(const Scene& scene, const RealtimeOptions& options, bool quiet) const;
  // Runs `scene` under the runtime; `offline` carries --duration, --out, --threads, --backend and
  // --allow-unstable. Returns the exit code.
  int run(const Scene& scene, const RunOptions& offline, bool quiet);

 private:
  bool realtime_ = false, free_run_ = false;
  std::string device_ = "scripted", mode_ = "coupling", profile_ = "falcon", replay_dir_;
  UdpDeviceOptions udp_;
  double haptic_rate_ = 1000, snapshot_rate_ = 30, sim_rate_ = 0, workspace_scale_ = 1, solve_share_ = 0;
  double force_scale_ = 0;  // 0: the scene's
  std::vector<double> origin_;
  CouplingParams coupling_;
  const CLI::Option* threads_option_ = nullptr;
};

// `dentsph replay RECORDING [SCENE] [--backend B] [--out DIR]`: steps the scene on the recorded
// tool poses and compares the tool forces with the recorded ones; with `out_dir`, also writes the
// replay as a run folder with its report. Returns 0 when they agree (bit for bit on the
// recording's backend, within kBackendParityTolerance on another), 4 otherwise. The step is
// `solver` (--solver), or else the one the recording names (session.json), or else the scene's, as
// choose_solver takes it for `backend`.
int replay_recording(Scene scene, const std::string& recording_dir, int threads, Backend backend,
                     const std::filesystem::path& out_dir = {}, const std::string& solver = {});

}  // namespace dentsph::cli
