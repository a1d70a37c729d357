#include "app/golden.h"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace serosa::app {
namespace {

using Json = nlohmann::json;

const Json* find(const Json& j, const std::string& pointer) {
  const Json::json_pointer p(pointer);
  return j.contains(p) ? &j.at(p) : nullptr;
}

std::string text(const Json& j) { return j.dump(); }

void exact(const Json& r, const Json& g, const std::string& key, GoldenComparison& out) {
  const Json* a = find(r, key);
  const Json* b = find(g, key);
  if (b == nullptr && a == nullptr) return;
  if (a == nullptr || b == nullptr || *a != *b) {
    std::string line = key;
    line.append(": golden ").append(b ? text(*b) : "absent");
    line.append(", got ").append(a ? text(*a) : "absent").append(" (must be equal)");
    out.failures.push_back(std::move(line));
  }
}

// Absolute floor of a metric by its key's unit suffix.
double floor_of(const std::string& key) {
  auto ends = [&](const char* s) {
    const std::string e(s);
    return key.size() >= e.size() && key.compare(key.size() - e.size(), e.size(), e) == 0;
  };
  if (ends("_m3")) return 1e-12;
  if (ends("_n")) return 1e-4;
  if (ends("_pa")) return 1.0;
  if (ends("_s")) return 1e-9;
  return 1e-6;  // lengths (_m) and anything else
}

void near(const Json& r, const Json& g, const std::string& key, double rel, double abs,
          GoldenComparison& out) {
  const Json* a = find(r, key);
  const Json* b = find(g, key);
  if (b == nullptr) return;
  const bool numbers = a != nullptr && a->is_number() && b->is_number();
  const double x = numbers ? a->get<double>() : 0.0, y = numbers ? b->get<double>() : 0.0;
  const double tol = std::max(abs, rel * std::abs(y));
  if (!numbers || !(std::abs(x - y) <= tol)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " (tolerance %.3g)", tol);
    std::string line = key;
    line.append(": golden ").append(text(*b)).append(", got ").append(a ? text(*a) : "absent");
    line.append(buf);
    out.failures.push_back(std::move(line));
  }
}

// Every numeric leaf under g's object at `prefix`.
void near_all(const Json& r, const Json& g, const std::string& prefix, GoldenComparison& out) {
  const Json* b = find(g, prefix);
  if (b == nullptr) return;
  if (b->is_object()) {
    for (const auto& [k, v] : b->items()) {
      std::string key = prefix;
      key.append("/").append(k);
      near_all(r, g, key, out);
    }
  } else if (b->is_number()) {
    const std::string leaf = prefix.substr(prefix.rfind('/') + 1);
    near(r, g, prefix, 1e-3, floor_of(leaf), out);
  }
}

}  // namespace

GoldenComparison compare_golden(const Json& report, const Json& golden) {
  GoldenComparison out;
  for (const char* k :
       {"/steps", "/steps_taken", "/mesh_final/tets", "/mesh_final/nodes", "/mesh_final/valid",
        "/cutting/cuts", "/cutting/tets_added", "/cutting/degenerate_tets", "/fem/rejected",
        "/contact/held_nodes", "/assessment/passed", "/assessment/domains"})
    exact(report, golden, k, out);
  near(report, golden, "/mesh_final/rest_volume_m3", 1e-9, 0.0, out);
  near(report, golden, "/simulated_time_s", 1e-12, 1e-12, out);
  near_all(report, golden, "/metrics", out);
  near(report, golden, "/assessment/score", 0.0, 0.5, out);  // half a point of 0-100
  const Json* h = find(report, "/state_hash");
  const Json* gh = find(golden, "/state_hash");
  if (h && gh && *h != *gh) {
    std::string line = "state_hash: golden ";
    line.append(text(*gh)).append(", got ").append(text(*h));
    line.append(" (not compared: exact only for the same binary and thread count)");
    out.notes.push_back(std::move(line));
  }
  return out;
}

GoldenComparison check_golden(const Json& report, const std::filesystem::path& golden,
                              bool update) {
  if (update) {
    if (golden.has_parent_path()) std::filesystem::create_directories(golden.parent_path());
    std::ofstream out(golden);
    out << report.dump(2) << '\n';
    GoldenComparison c;
    if (!out) c.failures.push_back("cannot write golden " + golden.string());
    return c;
  }
  GoldenComparison c;
  std::ifstream in(golden);
  if (!in) {
    c.failures.push_back("golden file " + golden.string() +
                         " is missing (run with --update-golden to create it)");
    return c;
  }
  Json g;
  try {
    in >> g;
  } catch (const Json::exception& e) {
    std::string line = "golden file ";
    line.append(golden.string()).append(" is not JSON: ").append(e.what());
    c.failures.push_back(std::move(line));
    return c;
  }
  return compare_golden(report, g);
}

}  // namespace serosa::app
