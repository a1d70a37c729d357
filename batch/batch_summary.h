// What a batch leaves in DIR besides each run's folder: summary.json (every run's result and the
// totals), junit.xml (one testcase per run, for CI dashboards) and summary.md (a table per run,
// the spread of each metric across a run's seeds, and gnuplot plots of the time and real-time
// factor per run and of the spread).
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "batch/batch_manifest.h"

namespace serosa::batch {

/// Writes the three files; returns summary.json's content. `results` in manifest order (a run
/// with no result yet stands as failed: "no result"). gnuplot: the program plots are drawn
/// with; a failure to draw is noted in the page, never fails the batch.
nlohmann::json write_batch_summary(const BatchManifest& m, std::vector<nlohmann::json> results,
                                   const std::filesystem::path& out,
                                   const std::string& gnuplot = "gnuplot");

}  // namespace serosa::batch
