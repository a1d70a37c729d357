// A recording made by a build that wrote another snapshot version still replays: its snapshots are
// left out (the replay starts from step 0 and checks the recorded hashes), and the replay says so.
#pragma once

#include <optional>
#include <string>

#include "app/run_warnings.h"
#include "recording/recording_reader.h"

namespace serosa::replay {

/// Drops the snapshots of `rec` this build cannot read; when there were any, the warning (kind
/// "old_snapshots") naming `file`, how many, their version and this build's.
[[nodiscard]] std::optional<app::RunWarning> drop_old_snapshots(recording::Recording& rec,
                                                                const std::string& file);

}  // namespace serosa::replay
