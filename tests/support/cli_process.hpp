// Runs a command line (the built `dentsph` program, by default) and collects its exit status and
// its output, stdout and stderr together. With a time limit, a command that hangs ends (killed by
// `timeout`) with status 124 instead of hanging the test.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace dentsph::testing {

struct CliResult {
  int code = -1;       // the exit status; -1 when the command did not exit (a signal)
  std::string output;  // stdout and stderr
};

inline CliResult run_command(const std::string& command, int timeout_s = 0) {
  const std::string cmd =
      (timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : std::string()) + command + " 2>&1";
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

#ifdef DENTSPH_CLI
// `dentsph ARGS` (the program this build made).
inline CliResult dentsph_cli(const std::string& args, int timeout_s = 0) {
  return run_command(std::string(DENTSPH_CLI) + " " + args, timeout_s);
}
#endif

}  // namespace dentsph::testing
