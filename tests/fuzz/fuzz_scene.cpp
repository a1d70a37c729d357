// libFuzzer target: the scene loader on arbitrary bytes. parse_scene_text is what load_scene and a
// recording's embedded scene_text (serosa replay) both go through. Only InputError may escape, and
// a scene that loads must hold what load_scene promises its users.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "fuzz_check.h"

namespace {

using serosa::fuzz::require;

void check_material(const serosa::Material& m) {
  require(m.young_pa > 0.0 && m.density_kgpm3 > 0.0, "material positive");
  require(m.poisson > -1.0 && m.poisson < 0.5, "poisson within (-1, 0.5)");
}

void check_scene(const serosa::Scene& s) {
  require(!s.organs.empty(), "at least one organ");
  require(std::isfinite(s.settings.dt_s) && s.settings.dt_s > 0.0 && s.settings.dt_s <= 1.0,
          "dt within (0, 1]");
  require(s.settings.gravity_mps2.allFinite(), "finite gravity");
  for (const serosa::Organ& o : s.organs) {
    require(!o.name.empty(), "organ named");
    require(std::filesystem::is_regular_file(o.mesh), "organ mesh exists");
    check_material(o.material);
    for (const auto& [group, m] : o.group_materials) check_material(m);
  }
  for (const serosa::Tool& t : s.tools) {
    require(!t.name.empty(), "tool named");
    require(!t.trocar_m || t.trocar_m->allFinite(), "finite trocar");
  }
  require(s.record.hash_every >= 1, "hash_every >= 1");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A scene file in config/: relative mesh and script paths in the seeds (config/*.toml copies)
  // resolve to the repository's assets/ and config/paths/, so the fuzzer gets past them.
  static const std::filesystem::path scene_path =
      std::filesystem::path(SEROSA_SOURCE_DIR) / "config" / "fuzz.toml";
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    check_scene(serosa::parse_scene_text(text, scene_path));
  } catch (const serosa::InputError& e) {
    // The scene itself or a tool path CSV it names.
    require(!e.file().empty() && e.line() >= 0, "error names the file");
  }
  return 0;
}
