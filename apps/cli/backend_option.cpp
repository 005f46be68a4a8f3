#include "backend_option.hpp"

#include <fmt/format.h>

#include "dentsph/backend.hpp"

namespace dentsph::cli {

CLI::Option* add_backend_option(CLI::App& app, std::string& backend, const std::string& help) {
  return app.add_option("--backend", backend, help)
      ->check(CLI::IsMember({"cpu", "cuda", "cuda-emulation"}))
      ->capture_default_str();
}

int failed(const std::exception& e) {
  const bool cuda = dynamic_cast<const CudaUnavailable*>(&e) != nullptr;
  fmt::print(stderr, "error: {}{}\n", cuda ? "--backend cuda: " : "", e.what());
  return 2;
}

}  // namespace dentsph::cli
