#include "bench/suite/bench_registry.h"
#include "bench/suite/bench_parts.h"

namespace serosa::bench {

// One line per part, in run order. A part's file adds its line here once it compiles.
const std::vector<PartEntry>& registered_parts() {
  static const std::vector<PartEntry> parts{
      {"scenes", run_scenes_part},   {"fem", run_fem_part},
      {"polar", run_polar_part},     {"cutting", run_cutting_part},
      {"surface", run_surface_part}, {"tessellation", run_tessellation_part},
      {"haptics", run_haptics_part}, {"render", run_render_part},
  };
  return parts;
}

}  // namespace serosa::bench
