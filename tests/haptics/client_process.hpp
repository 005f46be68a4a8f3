// Runs the reference haptic client (apps/haptic-client) as a separate process and reads its
// JSON report.
#pragma once

#include <spawn.h>
#include <unistd.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

namespace dentsph::testing {

class ClientProcess {
 public:
  ClientProcess(std::uint16_t port, std::vector<std::string> args, const std::string& tag) {
    report_ = std::filesystem::temp_directory_path() / ("dentsph_client_" + tag + "_" + std::to_string(::getpid()) + ".json");
    std::filesystem::remove(report_);
    args.insert(args.begin(), {DENTSPH_HAPTIC_CLIENT, "--port", std::to_string(port), "--report", report_.string()});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ok_ = posix_spawn(&pid_, DENTSPH_HAPTIC_CLIENT, nullptr, nullptr, argv.data(), environ) == 0;
  }
  ~ClientProcess() {
    if (ok_ && !waited_) wait();
  }
  bool started() const { return ok_; }
  // Waits for the client and returns its report (empty on failure).
  nlohmann::json wait() {
    int status = 0;
    waitpid(pid_, &status, 0);
    waited_ = true;
    std::ifstream in(report_);
    if (!in || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return {};
    return nlohmann::json::parse(in);
  }

 private:
  pid_t pid_ = 0;
  bool ok_ = false, waited_ = false;
  std::filesystem::path report_;
};

}  // namespace dentsph::testing
