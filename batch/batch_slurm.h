// A batch on a Slurm cluster: one job array, an index per run, each array task the same
// `serosa batch MANIFEST --out DIR --index $SLURM_ARRAY_TASK_ID --resume` (DIR on storage every
// node sees). The array is throttled by the manifest's `throttle`; its tasks may be requeued
// (--requeue): a task whose run has a result skips it, one interrupted before it starts the run
// over. The submitting process follows the job until no task is left, then merges the results.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "batch/batch_manifest.h"
#include "batch/batch_runner.h"

namespace serosa::batch {

struct SlurmOptions {
  std::optional<std::string> partition;  ///< --partition; default: the cluster's
  double poll_s = 1.0;                   ///< how often squeue is asked
};

/// Writes DIR/slurm/array.sh, submits it with sbatch and waits until the array has left the
/// queue. Throws std::runtime_error naming the command when sbatch or squeue fails.
void run_on_slurm(const std::filesystem::path& manifest, const BatchManifest& m,
                  const BatchOptions& o, const SlurmOptions& s);

}  // namespace serosa::batch
