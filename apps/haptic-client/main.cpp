// dentsph-haptic-client: the reference client of the haptic bridge (docs/haptic-protocol.md).
// It plays a haptic device: at a fixed rate it sends a pose (a scripted motion in the device
// frame), and reads the forces dentsph sends back, checking each one (finite, within the limit,
// answering a pose it sent). A program written with a haptic SDK does the same with the device's
// pose and renders the force. It numbers its poses as the protocol says (+1 per pose; its hello,
// heartbeats and bye carry the newest pose's number). Faults can be injected (dropped,
// duplicated, reordered, truncated and garbage packets, a silence, a restart of its numbering,
// an absurd pose, positions in the wrong units, a button toggled too fast) to exercise the
// runtime; --report writes what it saw as JSON.
#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "client.hpp"
#include "options.hpp"

using namespace dentsph::haptic_client;

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"dentsph-haptic-client: plays a haptic device over UDP against `dentsph run --realtime --device udp`"};
  add_options(app, o);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // a refused command line exits 2, as every refusal (CLI11's codes are 100 and up)
  }
  if (const std::string problem = check_options(o); !problem.empty()) {
    fmt::print(stderr, "error: {}\n", problem);
    return 2;
  }

  // Like a device SDK's servo thread: real-time priority where allowed (root or CAP_SYS_NICE).
  sched_param sp{};
  sp.sched_priority = 20;
  pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);

  try {
    Client client(o);
    std::this_thread::sleep_for(std::chrono::duration<double>(o.start_after_s));
    if (o.wait_s > 0 && !client.wait_for_dentsph()) {
      fmt::print(stderr, "error: dentsph at {}:{} did not answer within {} s (--wait); is it running with --device udp?\n",
                 o.host, o.port, o.wait_s);
      return 3;
    }
    if (o.hello) client.hello();
    client.play();
    client.leave();
    const nlohmann::json j = client.report();
    if (o.report.empty())
      fmt::print("{}\n", j.dump(2));
    else
      std::ofstream(o.report) << j.dump(2) << "\n";
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  return 0;
}
