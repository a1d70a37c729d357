// A cantilever beam scene for the instrument tests: 10 cm along +x, 1 cm square (5 mm tets),
// fixed at x = 0, group 1 named "artery", solved with CHOLMOD, its tools scripted by one CSV.
#pragma once

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app_test_util.h"

namespace serosa::app::testing {

/// Pointing down (-y) with the jaws opening (a hook's crook) along +z, the pin along -x.
inline const std::string kBeamAcross = "0.5,0.5,-0.5,0.5";
/// Pointing down with the jaws opening along the beam (+x), the pin along +z.
inline const std::string kBeamDown = "0.7071067811865476,0.7071067811865476,0,0";

struct BeamRun {
  Scene scene;
  AssembledScene assembled;
  Composition comp;
};

/// Writes dir/path.csv (`csv`: header and rows) and dir/scene.toml (the beam, `effects` as the
/// inside of the TOML list, `tools` and `extra` appended), loads and composes it.
inline std::unique_ptr<BeamRun> beam_scene(const fs::path& dir, const std::string& csv,
                                           const std::string& effects, const std::string& tools,
                                           const std::string& extra = "") {
  std::ofstream(dir / "path.csv") << csv;
  std::string toml = "[scene]\ndt = 0.005\neffects = [" + effects + "]\n";
  toml.append("[[organ]]\nname = \"beam\"\ngroups = { 1 = \"artery\" }\nmesh = \"")
      .append(source("assets/beam_coarse.msh").string())
      .append("\"\nyoung = 2e4\npoisson = 0.3\ndensity = 1000\n")
      .append("fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n[solver]\nkind = ")
      .append("\"cholmod\"\n")
      .append(tools)
      .append(extra);
  std::ofstream(dir / "scene.toml") << toml;
  auto run = std::make_unique<BeamRun>();
  run->scene = load_scene(dir / "scene.toml");
  run->assembled = assemble_state(run->scene);
  run->comp = compose(run->scene, run->assembled);
  return run;
}

/// A fresh pipeline for `run`'s scene with `snapshot` restored into it.
inline std::unique_ptr<BeamRun> restored(const BeamRun& run,
                                         const std::vector<std::uint8_t>& snapshot,
                                         const std::string& what) {
  auto other = std::make_unique<BeamRun>();
  other->scene = run.scene;
  other->assembled = assemble_state(other->scene);
  other->comp = compose(other->scene, other->assembled);
  other->comp.runner->restore(snapshot, other->assembled.state, what);
  return other;
}

/// A [[tool]] table of that name and kind, scripted by path.csv.
inline std::string scripted_tool(const std::string& name, const std::string& kind) {
  return "[[tool]]\nname = \"" + name + "\"\nkind = \"" + kind +
         "\"\ndevice = \"script:path.csv\"\n";
}

}  // namespace serosa::app::testing
