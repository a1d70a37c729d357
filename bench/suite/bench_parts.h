// The parts of `serosa bench`, one file each (bench/suite/part_<name>.cpp). Each measures
// its knobs, accuracy against time, and returns tables, plots and monotonicity checks
// (bench_table.h). With options.quick a part must finish in well under 30 s on the 2-core machine.
#pragma once

#include "bench/suite/bench_table.h"

namespace serosa::bench {

/// Cutting: pattern vs element removal vs node snapping — volume lost, distance of the cut surface
/// from the blade path, tets created, minimum quality — against ms per cut.
PartResult run_cutting_part(const BenchOptions& options);
/// FEM: CG tolerance and iteration cap, CHOLMOD, CHOLMOD-preconditioned CG (displacement error
/// against a converged reference vs ms per step); mesh resolution vs error against the analytical
/// beam; corotational vs linear FEM under rotation (spurious volume growth).
PartResult run_fem_part(const BenchOptions& options);
/// Polar decomposition method / iteration count: orthogonality error against time.
PartResult run_polar_part(const BenchOptions& options);
/// Phong tessellation level: distance to a finer reference surface against frame time.
PartResult run_tessellation_part(const BenchOptions& options);
/// Haptic coupling stiffness: force error and stability margin against loop time.
PartResult run_haptics_part(const BenchOptions& options);
/// The shipped appendectomy scenes, every stage: real-time factor and step-time distribution
/// against the accuracy of each solver setting and dt (positions against the exact solve).
PartResult run_scenes_part(const BenchOptions& options);
/// The endoscopic picture: the cost per frame of each feature (pattern, optic, anti-aliasing) at
/// two tessellations and resolutions, against its detail (the share of flat tiles).
PartResult run_render_part(const BenchOptions& options);
/// Surface extraction full vs incremental, CPU vs GPU: the same result, time only.
PartResult run_surface_part(const BenchOptions& options);

}  // namespace serosa::bench
