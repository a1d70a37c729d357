#include "replay/old_snapshots.h"

#include <cstdint>

#include "engine/runner.h"

namespace serosa::replay {

std::optional<app::RunWarning> drop_old_snapshots(recording::Recording& rec,
                                                  const std::string& file) {
  std::size_t dropped = 0;
  std::uint32_t version = 0;
  for (auto it = rec.snapshots.begin(); it != rec.snapshots.end();) {
    const std::uint32_t v = snapshot_version(it->second);
    if (v == snapshot_version()) {
      ++it;
      continue;
    }
    version = v;
    ++dropped;
    it = rec.snapshots.erase(it);
  }
  if (dropped == 0) return std::nullopt;
  return app::RunWarning{
      "old_snapshots",
      file + ": its " + std::to_string(dropped) + " snapshot" + (dropped == 1 ? " is" : "s are") +
          " of version " + std::to_string(version) + ", this build reads version " +
          std::to_string(snapshot_version()) +
          ": they are skipped; the replay starts from step 0 and checks the recorded hashes"};
}

}  // namespace serosa::replay
