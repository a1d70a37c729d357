// A headless run of a scene: no window, no device; the solver pipeline as fast as it goes, with
// a report, the final mesh and pictures on request (docs/headless-report.md).
#pragma once

#include <nlohmann/json.hpp>

#include "app/headless_options.h"
#include "app/run_report.h"

namespace serosa::app {

/// Runs the scene and returns the report (also written to options.report when set). Throws
/// InputError on bad input (scene, meshes, tool paths).
nlohmann::json run_headless(const HeadlessOptions& options);

}  // namespace serosa::app
