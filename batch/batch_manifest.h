// A regression batch's manifest (docs/batch.md): the runs of `serosa batch`, each a
// `serosa headless` of a scene with its path, steps, overrides of scene keys, perturbed-path seeds
// and golden. Read and checked whole before anything runs.
//
//   title = "Regression"       # optional
//   timeout = 600              # s per run (default 600); a run past it is stopped and failed
//   throttle = 4               # Slurm: array tasks at once (0, the default: no limit)
//   [[run]]
//   name = "appendectomy"      # unique; lower case, digits, '-' and '_'
//   scene = "appendectomy.toml"            # relative to the manifest's folder
//   steps = 400                            # default: the scene's headless.steps
//   path = "paths/x.csv"                   # default: the scene's own scripts
//   set = { "solver.tolerance" = 1e-4 }    # overrides of scene keys (scene_override.h)
//   sweep = { "solver.tolerance" = [1e-3, 1e-4] }  # one run per combination of the values,
//                                          # named NAME.tolerance-0.001 (not with a golden)
//   seeds = [1, 2, 3]                      # one run per seed, the path perturbed by it
//   perturb = 2e-4                         # m: the perturbation's amplitude (default 2e-4)
//   golden = "goldens/appendectomy.json"   # compared with the report (not with seeds)
//   strict = true                          # a run that warns fails (serosa headless --strict)
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene_override.h"

namespace serosa::batch {

/// One headless run of the batch.
struct BatchRun {
  std::string id;                               ///< the run's name, ".seed-N" for a seed
  std::string group;                            ///< the [[run]] it came from (its name)
  std::filesystem::path scene;                  ///< absolute
  std::optional<std::filesystem::path> path;    ///< tool path CSV, absolute
  std::optional<std::int64_t> steps;            ///< solver steps
  std::vector<SceneOverride> overrides;         ///< scene keys set
  std::optional<std::uint64_t> seed;            ///< the path perturbed with this seed
  double perturb_m = 2e-4;                      ///< its amplitude, m
  std::optional<std::filesystem::path> golden;  ///< absolute
  std::int64_t line = 0;                        ///< where its [[run]] is in the manifest
  bool strict = false;                          ///< a warning fails the run (--strict)
  /// Its scene has a rig in the loop, so it steps at the wall clock's pace: it runs alone, as
  /// a run beside it would slow it below real time and the rig's hands would outrun the tissue.
  bool paced = false;
};

struct BatchManifest {
  std::filesystem::path file;  ///< as given
  std::string title;
  double timeout_s = 600.0;  ///< per run
  int throttle = 0;          ///< Slurm array tasks at once; 0: no limit
  std::vector<BatchRun> runs;
};

/// Reads and checks the manifest: keys, types, names, files, and each run's scene loaded with its
/// overrides (a key the scene does not have is an error). Throws InputError naming the manifest,
/// the line and the key. A golden that does not exist yet is an error unless `new_goldens`
/// (--update-golden writes it).
[[nodiscard]] BatchManifest load_manifest(const std::filesystem::path& file, bool new_goldens);

}  // namespace serosa::batch
