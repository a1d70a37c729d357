// Headless regression: compare a run's report with a golden report (docs/headless-report.md).
//
// Tolerances: counts and flags (steps, tets, nodes, cuts, tets added, degenerate tets, rejected
// FEM steps, mesh validity) must be equal; the rest volume within 1e-9 relative; every metric
// within 1e-3 relative or its absolute floor (time 1e-9 s, lengths 1e-6 m, volumes 1e-12 m^3,
// forces 1e-4 N, stress 1 Pa); every final node position (nodes_final_m, when both hold them)
// within kGoldenPositionTolerance; timings are never compared. The state hash must be equal when
// the golden was written by the same binary (binary_id) with the same solver thread count;
// otherwise a difference is only noted (it is exact for the same binary and thread count, not
// across compilers or CPUs). A run paced to real time (a device in the loop: the emulated rig)
// is compared on its step counts, validity, cuts and volume only.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace serosa::batch {

/// How far a final node may lie from the golden's, m: a run on another thread count or CPU
/// rounds differently, and a long run carries that difference along (10 um is a tenth of the
/// finest mesh's smallest edge and far below anything a trainee sees).
inline constexpr double kGoldenPositionTolerance = 1e-5;

struct GoldenComparison {
  std::vector<std::string> failures;  ///< "key: golden G, got R (tolerance T)", in check order
  std::vector<std::string> notes;     ///< differences that do not fail (state hash)
  /// The failure furthest beyond its tolerance: difference over tolerance (the farthest node's
  /// distance over kGoldenPositionTolerance; an unequal count or an absent value counts as
  /// infinitely far, the first such wins; a state hash as not at all)
  std::size_t largest = 0;
  double largest_excess = 0.0;
  [[nodiscard]] bool ok() const { return failures.empty(); }
};

/// Compares `report` with `golden` (both as run_headless writes them).
[[nodiscard]] GoldenComparison compare_golden(const nlohmann::json& report,
                                              const nlohmann::json& golden);

/// Reads the golden file and compares; a missing or unreadable golden is a failure, unless
/// `update` is set: then the report is written as the new golden and the comparison is empty.
[[nodiscard]] GoldenComparison check_golden(const nlohmann::json& report,
                                            const std::filesystem::path& golden, bool update);

}  // namespace serosa::batch
