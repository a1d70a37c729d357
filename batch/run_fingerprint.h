// What a batch run is, as one hash: its scene's text, its tool path's text, its steps, overrides,
// seed, perturbation, golden, strictness and the binary that runs it. `serosa batch --resume`
// keeps a result only when the run's fingerprint is still the one written into it.
#pragma once

#include <string>

#include "batch/batch_manifest.h"

namespace serosa::batch {

/// 16 hex digits; `binary` is the running executable's id (app/version.h binary_id()).
[[nodiscard]] std::string run_fingerprint(const BatchRun& r, const std::string& binary);

}  // namespace serosa::batch
