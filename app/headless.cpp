#include "app/headless.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numeric>
#include <sstream>

#include "app/compose.h"
#include "app/simulation.h"
#include "app/version.h"
#include "cutting/cutting_stage.h"
#include "engine/scene/scene.h"
#include "recording/recording_writer.h"

namespace serosa::app {
namespace {

using Json = nlohmann::json;

void progress_bar(std::int64_t done, std::int64_t total) {
  const int width = 40;
  const int filled = static_cast<int>(width * done / std::max<std::int64_t>(total, 1));
  std::fprintf(stderr, "\r[%.*s%*s] %lld/%lld steps", filled,
               "########################################", width - filled, "",
               static_cast<long long>(done), static_cast<long long>(total));
  if (done == total) std::fputc('\n', stderr);
}

}  // namespace

Json run_headless(const HeadlessOptions& options) {
  Simulation sim(options);
  const std::int64_t steps = sim.planned_steps();
  const bool bar = options.progress && isatty(STDERR_FILENO);
  std::int64_t taken = 0;
  for (; taken < steps; ++taken) {
    if (options.stop && options.stop->load()) break;
    sim.step();
    if (bar && ((taken + 1) % 10 == 0 || taken + 1 == steps)) progress_bar(taken + 1, steps);
  }
  if (bar && taken < steps) std::fputc('\n', stderr);
  return sim.finish(taken < steps);
}

}  // namespace serosa::app
