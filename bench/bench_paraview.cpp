// ParaView output at scale: one frame of a pile of N coins (bench_scenes.hpp, 12
// nodes and 20 triangles a coin) written by ParaviewOutput::write, as `tem run` writes it: the
// bodies file, the contacts file and the line in tem.pvd, into a folder under TMPDIR (or /tmp).
// Time per frame, and the sizes of the two files against the ASCII files of the same frame as
// TEM wrote them before the binary ones (the values formatted as the ASCII writer did: shortest
// round-trip digits, one tuple per line; the tags counted as the binary file's XML, within a few
// hundred bytes of the ASCII tags). Run: build/release/bench/tem_bench --benchmark_filter=Paraview
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "bench_scenes.hpp"
#include "io/paraview_output.hpp"
#include "support/vtu_reader.hpp"
#include "support/parallel.hpp"
#include "simulation/step.hpp"

namespace tem::bench {
namespace {

namespace fs = std::filesystem;
using testing_support::read_vtu;
using testing_support::VtuArray;
using testing_support::VtuFile;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Characters of one value as the ASCII writer wrote it.
template <class T>
size_t text_size(T value) {
  char buffer[32];
  if constexpr (std::is_floating_point_v<T>)
    return static_cast<size_t>(std::to_chars(buffer, buffer + sizeof buffer, value + 0.0).ptr -
                               buffer);
  else
    return static_cast<size_t>(std::to_chars(buffer, buffer + sizeof buffer, +value).ptr - buffer);
}

// Every value with the byte after it (a space, or the newline that ends a line).
template <class T>
size_t values_text_size(const VtuArray& array) {
  size_t size = 0;
  for (const T& v : array.values<T>()) size += text_size(v) + 1;
  return size;
}

// The size of the ASCII file of the same frame.
size_t ascii_size(const std::string& binary) {
  const VtuFile file = read_vtu(binary);
  size_t size = binary.find("<AppendedData");  // the XML: about as long as the ASCII tags
  for (const std::string& name : file.names) {
    const VtuArray& a = file.arrays.at(name);
    if (a.type == "Float64") size += values_text_size<double>(a);
    if (a.type == "Int32") size += values_text_size<std::int32_t>(a);
    if (a.type == "Int64") size += values_text_size<std::int64_t>(a);
    if (a.type == "UInt8") size += values_text_size<std::uint8_t>(a);
  }
  return size;
}

void BM_ParaviewFrame(benchmark::State& st) {
  Model model = coin_pile(static_cast<int>(st.range(0)));
  model.scene.time_step = 1e-4;
  model.scene.contact.friction = 0.3;
  model.scene.contact.tolerance = 1e-3;
  model.scene.contact.max_sweeps = 20;
  State state = initial_state(model);
  Workspace workspace;
  // Two steps, so that every coin moves and turns with a speed of its own (the velocity fields
  // of a frame at rest would be zeros, which compress to nothing); then the step's patches.
  step(model, state, workspace);
  step(model, state, workspace);
  find_contact_forces(model, state, workspace);

  const char* tmp = std::getenv("TMPDIR");
  const std::string dir =
      std::string(tmp ? tmp : "/tmp") + "/tem_bench_paraview_" + std::to_string(getpid());
  set_threads(static_cast<int>(st.range(1)));
  {
    ParaviewOutput output(dir, model, std::nullopt);
    for (auto _ : st) output.write(model, state, workspace);
  }
  set_threads(1);

  const std::string bodies = slurp(dir + "/" + ParaviewOutput::bodies_file(state.step));
  const std::string contacts = slurp(dir + "/" + ParaviewOutput::contacts_file(state.step));
  fs::remove_all(dir);
  const double binary = static_cast<double>(bodies.size() + contacts.size());
  const double ascii = static_cast<double>(ascii_size(bodies) + ascii_size(contacts));
  st.counters["points"] = static_cast<double>(read_vtu(bodies).points);
  st.counters["patches"] = static_cast<double>(workspace.patches.size());
  st.counters["bodies_MB"] = static_cast<double>(bodies.size()) / 1e6;
  st.counters["contacts_MB"] = static_cast<double>(contacts.size()) / 1e6;
  st.counters["ascii_MB"] = ascii / 1e6;
  st.counters["ascii_per_binary"] = ascii / binary;
}
BENCHMARK(BM_ParaviewFrame)
    ->ArgsProduct({{1000, 10000, 100000}, {1, 2}})
    ->ArgNames({"coins", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace
}  // namespace tem::bench
