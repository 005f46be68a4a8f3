// --backend cpu|cuda|cuda-emulation: the one option of dentsph run (offline and --realtime),
// replay and bench, and of dentsph-viewer.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace dentsph::cli {

// Adds --backend to `app`, read into `backend` (default "cpu"); `help` says what it does there.
CLI::Option* add_backend_option(CLI::App& app, std::string& backend,
                                const std::string& help = "Where the step runs: cpu, cuda (a GPU), cuda-emulation "
                                                          "(the GPU's algorithm on the CPU, slow)");

}  // namespace dentsph::cli
