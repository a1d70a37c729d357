// libFuzzer target: the gmsh reader on arbitrary bytes (with and without inverted-tet repair).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool repair : {false, true}) {
    serosa::MeshReadOptions options;
    options.repair_inverted = repair;
    try {
      serosa::MeshReadReport report;
      const serosa::TetMesh mesh =
          serosa::read_mesh_text(text, serosa::MeshFormat::kGmsh, "fuzz.msh", options, &report);
      serosa::fuzz::check_mesh(mesh);
      serosa::fuzz::require(repair || report.repaired_inverted == 0, "no repair unless asked");
    } catch (const serosa::InputError& e) {
      serosa::fuzz::require(e.file() == "fuzz.msh" && e.line() >= 0, "error names the file");
    }
  }
  return 0;
}
