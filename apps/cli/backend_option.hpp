// --backend cpu|cuda|cuda-emulation: the one option of dentsph run (offline and --realtime),
// replay and bench, and of dentsph-viewer, and how either program says that a command failed.
#pragma once

#include <exception>
#include <string>

#include <CLI/CLI.hpp>

namespace dentsph::cli {

// Adds --backend to `app`, read into `backend` (default "cpu"); `help` says what it does there.
CLI::Option* add_backend_option(CLI::App& app, std::string& backend,
                                const std::string& help = "Where the step runs: cpu, cuda (a GPU), cuda-emulation "
                                                          "(the GPU's algorithm on the CPU, slow)");

// Prints why a command failed ("error: ..." on stderr; CudaUnavailable as "error: --backend cuda:
// <the reason>") and returns its exit status, 2.
int failed(const std::exception& e);

}  // namespace dentsph::cli
