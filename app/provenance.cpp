#include "app/provenance.h"

#include <cstdio>
#include <set>

#include "app/version.h"
#include "engine/fnv1a.h"

namespace serosa::app {
namespace {

void hash_file(Fnv1a& f, const std::filesystem::path& p) {
  f.text(p.filename().string());
  f.file(p);
}

std::string inputs_hash(const Scene& scene, const std::vector<SceneOverride>& overrides) {
  Fnv1a f;
  hash_file(f, scene.file);
  for (const Organ& o : scene.organs) hash_file(f, o.mesh);
  std::set<std::filesystem::path> paths;
  for (const Tool& t : scene.tools)
    if (!t.device.script.empty()) paths.insert(t.device.script);
  for (const auto& p : paths) hash_file(f, p);
  for (const SceneOverride& o : overrides) {
    f.text(o.key);
    f.text(o.value);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
  return hex;
}

nlohmann::json material_json(const Material& m) {
  return {{"young_pa", m.young_pa},
          {"poisson", m.poisson},
          {"density_kgpm3", m.density_kgpm3},
          {"damping_mass_per_s", m.damping.mass_per_s},
          {"damping_stiffness_s", m.damping.stiffness_s},
          {"plastic_yield", m.plasticity.yield},
          {"plastic_creep_per_s", m.plasticity.creep_per_s},
          {"plastic_max", m.plasticity.max}};
}

}  // namespace

nlohmann::json provenance_json(const Scene& scene, const std::vector<SceneOverride>& overrides,
                               const AssembledScene& assembled) {
  nlohmann::json given = nlohmann::json::array();
  for (const SceneOverride& o : overrides) given.push_back({{"key", o.key}, {"value", o.value}});
  nlohmann::json materials = nlohmann::json::object();
  for (const auto& [id, info] : assembled.groups)
    materials[info.name] = material_json(assembled.material(scene, id));
  return {{"overrides", std::move(given)},
          {"inputs_hash", inputs_hash(scene, overrides)},
          {"binary_id", binary_id()},
          {"materials", std::move(materials)}};
}

}  // namespace serosa::app
