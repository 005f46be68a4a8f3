// The cost of writing the tutor's report of the built-in procedure: the pictures, procedure.json
// and report.html (report::finish_run), and the HTML alone from the folder's files (what
// `dentsph report DIR` does). The procedure runs once first (about 15 s on two cores), or
// DENTSPH_REPORT_RUN names a folder `dentsph run --out` wrote for it.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "dentsph/dental.hpp"
#include "dentsph/report/session_report.hpp"
#include "dentsph/run.hpp"
#include "io/preview.hpp"
#include "report/run_outputs.hpp"

namespace {

using namespace dentsph;
namespace fs = std::filesystem;

const fs::path& procedure_run() {
  static const fs::path dir = [] {
    if (const char* given = std::getenv("DENTSPH_REPORT_RUN")) return fs::path(given);
    const fs::path d = fs::temp_directory_path() / "dentsph_bench_report";
    fs::remove_all(d);
    RunOptions o;
    o.out_dir = d;
    o.threads = 2;
    run_offline(default_dental_procedure(), o);
    return d;
  }();
  return dir;
}

// The whole report at the end of a run: the end state's pictures (here the built-in filled scene:
// the same tooth, 1600 particles of paste), procedure.json and report.html from the folder.
void BM_ReportFinishRun(benchmark::State& bs) {
  const fs::path& dir = procedure_run();
  const Scene scene = default_dental_procedure();
  const Scene filled = default_dental_scene();
  const State state = make_state(filled);
  const report::ProcedureLog log(state);
  for (auto _ : bs) report::finish_run(dir, scene, state.pos, state.role, log);
}
BENCHMARK(BM_ReportFinishRun)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

// report.html alone from the folder's files (the 54,560 rows of tool_force.csv among them).
void BM_ReportHtmlFromFolder(benchmark::State& bs) {
  const fs::path& dir = procedure_run();
  for (auto _ : bs) report::write_session_report(dir);
}
BENCHMARK(BM_ReportHtmlFromFolder)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);

// The baseline measured beside them (this host's speed drifts): preview.png, the particles-only
// picture every run writes.
void BM_PreviewPng(benchmark::State& bs) {
  const Scene filled = default_dental_scene();
  const State state = make_state(filled);
  const fs::path file = fs::temp_directory_path() / "dentsph_bench_preview.png";
  for (auto _ : bs) io::write_preview_png(file, state, -filled.model.gravity, filled.model.kernel.h);
}
BENCHMARK(BM_PreviewPng)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
