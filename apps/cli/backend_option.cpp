#include "backend_option.hpp"

namespace dentsph::cli {

CLI::Option* add_backend_option(CLI::App& app, std::string& backend, const std::string& help) {
  return app.add_option("--backend", backend, help)
      ->check(CLI::IsMember({"cpu", "cuda", "cuda-emulation"}))
      ->capture_default_str();
}

}  // namespace dentsph::cli
