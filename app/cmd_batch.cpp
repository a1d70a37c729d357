// serosa batch MANIFEST.toml --out DIR [--jobs N] [--resume] [--slurm [--partition P]]
//                                      [--index I] [--update-golden]
// Runs a manifest's headless runs (batch/batch_manifest.h), N at once here or as one Slurm job
// array, and merges their results into DIR/summary.json, DIR/junit.xml and DIR/summary.md
// (docs/batch.md). --index I runs run I alone (what each array task does; a Kubernetes Indexed
// Job passes $JOB_COMPLETION_INDEX) and merges nothing.
// Exit codes: 0 every run passed; 1 bad input (the manifest, before anything runs); 3 some run
// failed, timed out or differs from its golden.
#include <cstdio>
#include <memory>

#include "app/command.h"
#include "app/version.h"
#include "batch/batch_manifest.h"
#include "batch/batch_runner.h"
#include "batch/batch_slurm.h"
#include "batch/batch_summary.h"
#include "engine/input_error.h"

namespace serosa::app {
namespace {

using namespace serosa::batch;

struct BatchArgs {
  std::string manifest, out, partition;
  int jobs = 1;
  int index = -1;
  bool resume = false, slurm = false, update_golden = false;
};

int run_batch(const BatchArgs& a) {
  const BatchManifest m = load_manifest(a.manifest, a.update_golden);
  BatchOptions o;
  o.out = std::filesystem::absolute(a.out);
  o.exe = std::filesystem::read_symlink("/proc/self/exe");
  o.jobs = a.jobs;
  o.resume = a.resume;
  o.update_golden = a.update_golden;
  o.binary = binary_id();
  if (a.index >= 0) {
    if (static_cast<std::size_t>(a.index) >= m.runs.size())
      throw InputError("--index", 0, std::to_string(a.index) + " is past the manifest's runs",
                       "0 to " + std::to_string(m.runs.size() - 1));
    const auto r = run_one(m, m.runs[static_cast<std::size_t>(a.index)], o);
    std::fprintf(stderr, "%s: %s\n", r.value("id", "").c_str(), r.value("status", "").c_str());
    return r.value("status", "") == "passed" ? 0 : 3;
  }
  std::vector<nlohmann::json> results;
  if (a.slurm) {
    SlurmOptions s;
    if (!a.partition.empty()) s.partition = a.partition;
    run_on_slurm(std::filesystem::absolute(a.manifest), m, o, s);
    for (const BatchRun& r : m.runs) results.push_back(finished_result(o, r).value_or(nullptr));
  } else {
    results = run_all(m, o);
  }
  const auto summary = write_batch_summary(m, std::move(results), o.out);
  std::fprintf(stderr, "%d of %zu runs passed: %s\n", summary["passed"].get<int>(),
               summary["runs"].size(), (o.out / "summary.md").c_str());
  return summary["failed"].get<int>() == 0 ? 0 : 3;
}

}  // namespace

void add_batch_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<BatchArgs>();
  CLI::App* cmd = app.add_subcommand("batch", "Run a manifest of headless runs and merge them");
  cmd->add_option("manifest", a->manifest, "Batch manifest TOML")->required();
  cmd->add_option("--out", a->out, "Folder for the runs and the merged results")->required();
  cmd->add_option("--jobs", a->jobs, "Runs at once on this machine")->check(CLI::Range(1, 256));
  cmd->add_flag("--resume", a->resume, "Skip runs that already have a result in --out");
  cmd->add_flag("--slurm", a->slurm, "Submit the runs as one Slurm job array and follow it");
  cmd->add_option("--partition", a->partition, "Slurm partition (with --slurm)");
  cmd->add_option("--index", a->index, "Run only run I (an array task's index), merge nothing")
      ->check(CLI::Range(0, 1000000));
  cmd->add_flag("--update-golden", a->update_golden, "Write each run's golden instead");
  cmd->callback([&action, a] {
    action = [a] {
      if (!a->partition.empty() && !a->slurm)
        throw InputError("--partition", 0, "needs --slurm", "--slurm --partition P");
      return run_batch(*a);
    };
  });
}

}  // namespace serosa::app
