#include "batch/golden.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace serosa::batch {
namespace {

using Json = nlohmann::json;

const Json* find(const Json& j, const std::string& pointer) {
  const Json::json_pointer p(pointer);
  return j.contains(p) ? &j.at(p) : nullptr;
}

std::string text(const Json& j) { return j.dump(); }

// A failure `excess` times its tolerance away (infinity: no tolerance applies).
void fail(GoldenComparison& out, std::string line, double excess) {
  if (out.failures.empty() || excess > out.largest_excess) {
    out.largest = out.failures.size();
    out.largest_excess = excess;
  }
  out.failures.push_back(std::move(line));
}

constexpr double kBeyondAnyTolerance = std::numeric_limits<double>::infinity();

void exact(const Json& r, const Json& g, const std::string& key, GoldenComparison& out) {
  const Json* a = find(r, key);
  const Json* b = find(g, key);
  if (b == nullptr && a == nullptr) return;
  if (a == nullptr || b == nullptr || *a != *b) {
    std::string line = key;
    line.append(": golden ").append(b ? text(*b) : "absent");
    line.append(", got ").append(a ? text(*a) : "absent").append(" (must be equal)");
    fail(out, std::move(line), kBeyondAnyTolerance);
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
    fail(out, std::move(line),
         numbers && tol > 0.0 && std::isfinite(x) ? std::abs(x - y) / tol : kBeyondAnyTolerance);
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

// Every final node within kGoldenPositionTolerance of the golden's; the first few beyond it named.
void near_positions(const Json& r, const Json& g, GoldenComparison& out) {
  const Json* a = find(r, "/nodes_final_m");
  const Json* b = find(g, "/nodes_final_m");
  if (a == nullptr || b == nullptr) return;
  if (a->size() != b->size()) {
    fail(out,
         "nodes_final_m: golden " + std::to_string(b->size()) + " nodes, got " +
             std::to_string(a->size()),
         kBeyondAnyTolerance);
    return;
  }
  std::size_t beyond = 0, worst = 0;
  double worst_d = 0.0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    double d2 = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = (*a)[i][k].get<double>() - (*b)[i][k].get<double>();
      d2 += d * d;
    }
    const double d = std::sqrt(d2);
    if (!(d <= kGoldenPositionTolerance)) ++beyond;
    if (!(d <= worst_d)) worst_d = d, worst = i;
  }
  if (beyond == 0) return;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "nodes_final_m: %zu of %zu nodes beyond %.0e m of the golden's; the farthest, "
                "node %zu, by %.3g m: golden %s, got %s",
                beyond, a->size(), kGoldenPositionTolerance, worst, worst_d,
                (*b)[worst].dump().c_str(), (*a)[worst].dump().c_str());
  fail(out, buf, worst_d / kGoldenPositionTolerance);
}

// The state hash: equal when the same binary ran with the same thread count, else only noted.
void same_hash(const Json& r, const Json& g, GoldenComparison& out) {
  const Json* h = find(r, "/state_hash");
  const Json* gh = find(g, "/state_hash");
  if (h == nullptr || gh == nullptr || *h == *gh) return;
  const Json* bin = find(r, "/binary_id");
  const Json* gbin = find(g, "/binary_id");
  const Json* th = find(r, "/solver/threads");
  const Json* gth = find(g, "/solver/threads");
  const bool same = bin != nullptr && gbin != nullptr && *bin == *gbin && th != nullptr &&
                    gth != nullptr && *th == *gth;
  std::string line = "state_hash: golden ";
  line.append(text(*gh)).append(", got ").append(text(*h));
  if (same) {
    line.append(" (must be equal: the same binary with the same thread count wrote the golden)");
    fail(out, std::move(line), 0.0);  // a consequence of any other difference, rarely the cause
  } else {
    line.append(" (not compared: exact only for the same binary and thread count)");
    out.notes.push_back(std::move(line));
  }
}

// The report indented for a person to read and diff, but the node positions on one line: a
// node a line would make a large mesh's golden megabytes long.
std::string golden_text(const Json& report) {
  if (!report.contains("nodes_final_m")) return report.dump(2) + '\n';
  Json rest = report;
  rest.erase("nodes_final_m");
  std::string text = rest.dump(2);
  text.erase(text.rfind('}'));
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text + ",\n  \"nodes_final_m\": " + report["nodes_final_m"].dump() + "\n}\n";
}

}  // namespace

GoldenComparison compare_golden(const Json& report, const Json& golden) {
  GoldenComparison out;
  // A run paced to wall time has a device in the loop (the emulated rig): what it sampled when
  // depends on the machine's timing, so only what timing cannot change is compared: the steps,
  // the blades' strokes (not the cuts: a stroke's sweep can land as one cut or two, as the
  // samples fall on a busy machine) and whether the procedure passed.
  if (golden.value("paced_to_real_time", false) || report.value("paced_to_real_time", false)) {
    for (const char* k :
         {"/steps", "/steps_taken", "/mesh_final/valid", "/cutting/strokes", "/assessment/passed"})
      exact(report, golden, k, out);
    near(report, golden, "/mesh_final/rest_volume_m3", 1e-9, 0.0, out);
    near(report, golden, "/simulated_time_s", 1e-12, 1e-12, out);
    out.notes.push_back(
        "paced to real time (a device in the loop): its metrics, node positions and state hash "
        "depend on the device's timing and are not compared");
    return out;
  }
  for (const char* k :
       {"/steps", "/steps_taken", "/mesh_final/tets", "/mesh_final/nodes", "/mesh_final/valid",
        "/cutting/cuts", "/cutting/tets_added", "/cutting/degenerate_tets", "/fem/rejected",
        "/contact/held_nodes", "/assessment/passed", "/assessment/domains"})
    exact(report, golden, k, out);
  near(report, golden, "/mesh_final/rest_volume_m3", 1e-9, 0.0, out);
  near(report, golden, "/simulated_time_s", 1e-12, 1e-12, out);
  near_all(report, golden, "/metrics", out);
  near(report, golden, "/assessment/score", 0.0, 0.5, out);  // half a point of 0-100
  near_positions(report, golden, out);
  same_hash(report, golden, out);
  return out;
}

GoldenComparison check_golden(const Json& report, const std::filesystem::path& golden,
                              bool update) {
  if (update) {
    if (golden.has_parent_path()) std::filesystem::create_directories(golden.parent_path());
    std::ofstream out(golden);
    out << golden_text(report);
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

}  // namespace serosa::batch
