// The fuzz targets (docs/fuzzing.md): each takes one input, as libFuzzer hands it, and returns 0.
// An input may be refused the way the library documents (a SceneError naming the file and the
// field, a MeshError, ...); anything else (a crash, a sanitizer's report, an exception of another
// kind, a hang, memory past the fuzzer's limit) is a defect. The same functions replay the seed
// corpora and the inputs of every defect found in the ordinary test suite
// (tests/unit/test_fuzz_inputs.cpp), so that each stays fixed without clang.
#pragma once

#include <cstddef>
#include <cstdint>

namespace dentsph::fuzz {

// A scene file, or a dental scene file: read, its initial state made, its time step checked.
int scene(const std::uint8_t* data, std::size_t size);
// A procedure file on the built-in crown.
int procedure(const std::uint8_t* data, std::size_t size);
// A recording: haptic.csv, steps.csv, events.csv and session.json, separated by NUL bytes;
// loaded, and replayed into a small scene when it holds a few steps.
int recording(const std::uint8_t* data, std::size_t size);
// A mesh file: the first byte chooses its name's extension (.stl, .obj, .ply, or .off, which
// load_mesh refuses by name) and its units, the rest is the file.
int mesh(const std::uint8_t* data, std::size_t size);
// Datagrams of the haptic bridge (each a length byte and its bytes): decoded, and sent to a UDP
// device that the haptic loop's calls then read and answer.
int protocol(const std::uint8_t* data, std::size_t size);
// A session store's address (--db): its backend and its masked form (report/session_store.hpp).
int store_address(const std::uint8_t* data, std::size_t size);
// A viewer input script (apps/viewer/input_script.cpp).
int input_script(const std::uint8_t* data, std::size_t size);
int report_folder(const std::uint8_t* data, std::size_t size);
int realtime_options(const std::uint8_t* data, std::size_t size);

}  // namespace dentsph::fuzz

// libFuzzer's entry point for a target built with -DDENTSPH_FUZZ_ENTRY=<function>.
#ifdef DENTSPH_FUZZ_ENTRY
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return dentsph::fuzz::DENTSPH_FUZZ_ENTRY(data, size);
}
#endif
