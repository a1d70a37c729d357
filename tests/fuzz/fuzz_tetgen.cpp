// libFuzzer target: the TetGen reader on arbitrary bytes. The input is the .node text, then the
// separator line "@@ele@@", then the .ele text (no separator: all of it is the .node text).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string sep = "\n@@ele@@\n";
  const std::size_t at = input.find(sep);
  const std::string node = input.substr(0, at);
  const std::string ele = at == std::string::npos ? std::string() : input.substr(at + sep.size());
  for (const bool repair : {false, true}) {
    serosa::MeshReadOptions options;
    options.repair_inverted = repair;
    try {
      const serosa::TetMesh mesh = serosa::read_mesh_text(node, serosa::MeshFormat::kTetGen,
                                                          "fuzz.node", options, nullptr, ele);
      serosa::fuzz::check_mesh(mesh);
    } catch (const serosa::InputError& e) {
      serosa::fuzz::require((e.file() == "fuzz.node" || e.file() == "fuzz.ele") && e.line() >= 0,
                            "error names the file");
    }
  }
  return 0;
}
