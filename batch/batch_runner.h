// Running a batch's runs: each one a `serosa headless` process of its own (its report, recording,
// log and golden compare in DIR/runs/ID/), stopped when it outlives the manifest's timeout. A run
// that crashes, fails or times out is recorded as failed with its log; the others go on. Each
// finished run leaves DIR/runs/ID/result.json (written whole, then renamed into place), which
// --resume and a requeued Slurm array task take as done.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "batch/batch_manifest.h"

namespace serosa::batch {

struct BatchOptions {
  std::filesystem::path out;   ///< DIR
  std::filesystem::path exe;   ///< the serosa executable each run starts
  int jobs = 1;                ///< runs at once (local)
  bool resume = false;         ///< skip runs with a result
  bool update_golden = false;  ///< write each run's golden instead of comparing
  bool progress = true;        ///< a line per finished run on stderr
  std::string binary;          ///< the executable's id (app/version.h): part of a fingerprint
};

/// DIR/runs/ID: where a run keeps its files.
[[nodiscard]] std::filesystem::path run_dir(const BatchOptions& o, const BatchRun& r);

/// The run's finished result, if it has one (resume).
[[nodiscard]] std::optional<nlohmann::json> finished_result(const BatchOptions& o,
                                                            const BatchRun& r);

/// Runs one run (unless `resume` and it has a result with the run's fingerprint, then marked
/// "kept"; a result of a changed run is said and run again) and returns its result: id, group,
/// seed, fingerprint (batch/run_fingerprint.h),
/// status ("passed", "failed" or "timeout"), exit_code, signal, wall_s, real_time_factor,
/// simulated_time_s, golden ("match", "mismatch", "written" or "none"), reason (why not passed),
/// log, report, recording, metrics (the report's, for the spread over seeds).
nlohmann::json run_one(const BatchManifest& m, const BatchRun& r, const BatchOptions& o);

/// A progress line on stderr: a bar of `done` of `total`, and the run just finished.
void print_progress(std::size_t done, std::size_t total, const nlohmann::json& result);

/// Runs every run, `jobs` at once; returns their results in manifest order.
std::vector<nlohmann::json> run_all(const BatchManifest& m, const BatchOptions& o);

}  // namespace serosa::batch
