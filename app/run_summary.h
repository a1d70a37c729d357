// The few lines a person wants after a headless run (did the procedure complete, the score, how
// fast it ran, where the files went), read from the run's report; `--json` prints the report
// itself for scripts.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace serosa::app {

/// Where the run wrote what the report does not name itself.
struct SummaryPaths {
  std::optional<std::filesystem::path> report;  ///< the JSON report file, if written
  std::optional<std::filesystem::path> frames;  ///< the pictures' folder, if asked
};

/// A short human summary of a headless run's report (at most a dozen lines, each ending in a
/// newline).
[[nodiscard]] std::string run_summary(const nlohmann::json& report, const SummaryPaths& paths);

}  // namespace serosa::app
