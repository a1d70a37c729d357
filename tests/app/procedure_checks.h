// Checks the appendectomy scenes' tests share on a headless report.
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>

namespace serosa::app::testing {

/// Whether the JSON array `names` holds `name`.
inline bool lists(const nlohmann::json& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// No error (nothing bled, burnt, cut above the securing, dropped), and the final mesh valid with
/// the rest volume it started with.
inline void expect_clean_procedure(const nlohmann::json& r) {
  const auto& m = r["metrics"];
  EXPECT_TRUE(m["errors"].empty()) << m["errors"].dump();
  for (const char* count :
       {"bleeding_events", "thermal_injuries", "transections_above_securing", "specimens_dropped"})
    EXPECT_EQ(m[count].get<int>(), 0) << count;
  EXPECT_TRUE(r["mesh_final"]["valid"].get<bool>());
  EXPECT_NEAR(r["mesh_final"]["rest_volume_m3"].get<double>(),
              r["mesh_initial"]["rest_volume_m3"].get<double>(),
              1e-9 * r["mesh_initial"]["rest_volume_m3"].get<double>());
}

}  // namespace serosa::app::testing
