// Rubric: what a session is scored on (docs/assessment.md). Each metric is a value the session
// reports, scored from 1 (at or beyond `good`) to 0 (at or beyond `poor`) in between linearly; it
// passes on the good side of `limit`. The metrics' weighted mean gives each of the five GOALS
// domains (Vassiliou 2005) a rating of 1-5 and the session a score of 0-100; the session passes
// at `pass_score` or more with every critical metric passed. An instructor edits the rubric's
// TOML file (config/assessment/); the scene names it ([metrics] rubric).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace serosa {

/// The five GOALS domains, as the report names them.
inline constexpr std::array<std::string_view, 5> kGoalsDomains = {
    "depth_perception", "bimanual_dexterity", "efficiency", "tissue_handling", "autonomy"};

struct RubricMetric {
  std::string name;       ///< a value the session reports (docs/assessment.md lists them)
  std::string domain;     ///< one of kGoalsDomains
  std::string unit;       ///< its unit as reported (SI; "1" for counts and fractions)
  double good = 0.0;      ///< full marks at or beyond this, in `unit`
  double poor = 1.0;      ///< no marks at or beyond this; good < poor: lower is better
  double limit = 0.5;     ///< passes on the good side of this (inclusive); default halfway
  double weight = 1.0;    ///< its share of its domain and of the score; > 0
  bool critical = false;  ///< failing it fails the session whatever the score
  int line = 0;           ///< where it is defined in the rubric file (errors name it)
};

struct Rubric {
  std::filesystem::path file;         ///< the rubric file as loaded
  std::string title;                  ///< what it scores, shown to the trainee
  double pass_score = 70.0;           ///< the score (0-100) that passes
  std::vector<RubricMetric> metrics;  ///< at least one per GOALS domain
};

/// Reads and checks a rubric file. Throws InputError naming the file, line and key on a syntax
/// error, an unknown key, a domain not among the five, a metric name the session does not
/// report, good == poor, a limit outside [good, poor], a weight <= 0 or a domain left empty.
/// Whether the named tools and groups exist is the scene's check (they belong to it).
[[nodiscard]] Rubric load_rubric(const std::filesystem::path& file);

/// Whether `name` is a metric the session reports: a fixed name, or a family with a tool or
/// group suffix ("path_length_m.grasper"). The suffix, if any, goes to `suffix`.
[[nodiscard]] bool known_metric(std::string_view name, std::string& family, std::string& suffix);

}  // namespace serosa
