#include "app/compose.h"

#include <algorithm>

#include "app/script_tool_stage.h"
#include "fem/fem_stage.h"

namespace serosa::app {
namespace {

fem::SolverKind to_fem(SolverKind k) {
  switch (k) {
    case SolverKind::kPcg:
      return fem::SolverKind::pcg;
    case SolverKind::kCholmod:
      return fem::SolverKind::cholmod;
    case SolverKind::kPcgCholmod:
      return fem::SolverKind::pcg_cholmod;
  }
  return fem::SolverKind::pcg;
}

fem::FemMaterial to_fem(const Material& m) {
  fem::FemMaterial f;
  f.young_pa = m.young_pa;
  f.poisson = m.poisson;
  f.density_kgpm3 = m.density_kgpm3;
  f.damping_mass = m.damping.mass_per_s;
  f.damping_stiffness = m.damping.stiffness_s;
  return f;
}

fem::FemConfig fem_config(const Scene& scene, const AssembledScene& assembled) {
  fem::FemConfig c;
  for (const auto& [g, info] : assembled.groups)
    c.materials[static_cast<std::uint16_t>(g)] = to_fem(assembled.material(scene, g));
  c.solver.kind = to_fem(scene.solver.kind);
  c.solver.tolerance = scene.solver.tolerance;
  c.solver.max_iterations = scene.solver.max_iterations;
  c.gravity_on = scene.settings.has(Effect::kGravity);
  c.gravity_mps2 = scene.settings.gravity_mps2;
  return c;
}

}  // namespace

Composition compose(const Scene& scene, const AssembledScene& assembled) {
  Composition c;
  c.runner = std::make_unique<Runner>(scene.settings.dt_s);
  const auto listed = [&](Effect e) { return scene.settings.has(e); };

  // take tool states
  if (std::any_of(scene.tools.begin(), scene.tools.end(),
                  [](const Tool& t) { return t.device.kind == DeviceKind::kScript; })) {
    auto tools = std::make_unique<ScriptToolStage>(scene);
    c.tools = tools.get();
    c.runner->add(std::move(tools));
  }
  // FEM (gravity is one of its terms)
  if (listed(Effect::kFem)) {
    auto stage = std::make_unique<fem::FemStage>(fem_config(scene, assembled));
    c.fem = stage.get();
    c.runner->add(std::move(stage));
    c.built.push_back(Effect::kFem);
    if (listed(Effect::kGravity)) c.folded.push_back(Effect::kGravity);
  }
  if (listed(Effect::kRender)) c.folded.push_back(Effect::kRender);

  // Everything else the scene lists waits for its stage to land.
  for (Effect e : scene.settings.effects) {
    const bool handled = std::find(c.built.begin(), c.built.end(), e) != c.built.end() ||
                         std::find(c.folded.begin(), c.folded.end(), e) != c.folded.end();
    if (!handled) c.unavailable.push_back(e);
  }
  return c;
}

}  // namespace serosa::app
