// libFuzzer target: any bytes given to the scene reader. What must hold for every input:
// - the reader returns (no crash, no hang, no sanitizer report: ASan and UBSan are on), and
//   never throws (it promises to collect problems instead);
// - a rejected scene has at least one problem, each with a non-empty message;
// - an accepted scene, written back out as `scene.json` (what `tem run` does), reads back as a
//   valid scene, and writing that gives the same text again.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const tem::SceneReadResult read = tem::read_scene_text(text, "fuzz.json");
  if (!read.ok()) {
    for (const tem::SceneProblem& p : read.problems)
      if (p.message.empty()) std::abort();
    return 0;
  }
  const std::string written = tem::write_scene_text(read.scene);
  const tem::SceneReadResult again = tem::read_scene_text(written, "scene.json");
  if (!again.ok()) std::abort();
  if (tem::write_scene_text(again.scene) != written) std::abort();
  return 0;
}
