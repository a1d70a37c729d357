#include "batch/batch_slurm.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "engine/shell_command.h"

namespace serosa::batch {
namespace {

namespace fs = std::filesystem;

fs::path write_script(const fs::path& manifest, const BatchManifest& m, const BatchOptions& o,
                      const SlurmOptions& s) {
  const fs::path dir = o.out / "slurm";
  fs::create_directories(dir);
  const fs::path script = dir / "array.sh";
  const long minutes = std::lround(std::ceil(m.timeout_s / 60.0)) + 1;
  std::ofstream out(script);
  out << "#!/bin/sh\n"
      << "#SBATCH --job-name=serosa-batch\n"
      << "#SBATCH --array=0-" << m.runs.size() - 1;
  if (m.throttle > 0) out << '%' << m.throttle;
  out << "\n"
      << "#SBATCH --output=" << (dir / "task_%a.log").string() << "\n"
      << "#SBATCH --time=" << minutes << "\n"
      << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n#SBATCH --requeue\n"
      << (s.partition ? "#SBATCH --partition=" + *s.partition + "\n" : "") << "exec "
      << shell_quote(o.exe.string()) << " batch " << shell_quote(manifest.string()) << " --out "
      << shell_quote(o.out.string()) << " --index \"$SLURM_ARRAY_TASK_ID\" --resume"
      << (o.update_golden ? " --update-golden" : "") << "\n";
  if (!out) throw std::runtime_error("cannot write " + script.string());
  return script;
}

std::size_t finished(const BatchManifest& m, const BatchOptions& o) {
  std::size_t n = 0;
  for (const BatchRun& r : m.runs) n += fs::exists(run_dir(o, r) / "result.json") ? 1 : 0;
  return n;
}

}  // namespace

void run_on_slurm(const fs::path& manifest, const BatchManifest& m, const BatchOptions& o,
                  const SlurmOptions& s) {
  const fs::path script = write_script(manifest, m, o, s);
  const Command submit = run_command("sbatch --parsable " + shell_quote(script.string()));
  const std::string id = first_line(submit.output);
  if (submit.code != 0 || id.empty() || id.find_first_not_of("0123456789;") != std::string::npos)
    throw std::runtime_error("sbatch " + script.string() + " failed: " + first_line(submit.output));
  const std::string job = id.substr(0, id.find(';'));  // "JOBID;CLUSTER" on a federation
  if (o.progress)
    std::fprintf(stderr, "submitted job array %s (%zu runs)\n", job.c_str(), m.runs.size());
  std::size_t shown = 0;
  while (true) {
    const Command q = run_command("squeue -h -r -j " + job + " -o %i");
    if (q.code != 0 && q.output.find("Invalid job id") == std::string::npos)
      throw std::runtime_error("squeue -j " + job + " failed: " + first_line(q.output));
    const std::size_t done = finished(m, o);
    if (o.progress && done != shown)
      std::fprintf(stderr, "%zu of %zu runs finished\n", shown = done, m.runs.size());
    if (q.code != 0 || q.output.find_first_not_of(" \n") == std::string::npos) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(s.poll_s));
  }
}

}  // namespace serosa::batch
