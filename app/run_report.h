// The pieces of a run's report and recording that every driver writes the same way: the
// recording's header and closing record, the step times with the slowest steps' details, the
// cutting block, and the state hash as text (docs/headless-report.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.h"
#include "recording/recording_format.h"
#include "recording/recording_writer.h"

namespace serosa::app {

struct Composition;

[[nodiscard]] recording::Header recording_header(const Scene& scene, std::int64_t steps);

/// Closes the run's recording after `steps` steps and returns the report's "recording" object:
/// file, steps, chunks, bytes, hash_every, snapshots.
[[nodiscard]] nlohmann::json close_recording(recording::RecordingWriter& writer, const Scene& scene,
                                             std::uint64_t steps);

/// A state hash as the report writes it: 16 lower-case hex digits.
[[nodiscard]] std::string hash_hex(std::uint64_t hash);

/// Where one step's time went: the FEM stage's share and what its solve did.
struct StepDetail {
  double fem_ms = 0.0;          ///< wall time of the FEM stage, ms
  int cg_iterations = 0;        ///< CG iterations of its solve
  bool factor_refresh = false;  ///< a factor refresh was asked for (or computed) on this step
  bool factor_patch = false;    ///< changed rows got a factor of their own on this step
  double factor_wait_ms = 0.0;  ///< waited for the background refresh it installed, ms
};

/// The report's "step_time_ms" object: p50, p99 and max of the solver steps' wall times (ms),
/// and the eight slowest steps (`slowest`: step index from 0, ms), slowest first. With
/// `details` (one per step), each slowest step also says its FEM time, CG iterations and
/// factor work.
[[nodiscard]] nlohmann::json step_time_json(const std::vector<double>& ms,
                                            const std::vector<StepDetail>& details = {});

/// The report's "cutting" object (empty without a cutting stage).
[[nodiscard]] nlohmann::json cutting_json(const Composition& comp);

}  // namespace serosa::app
