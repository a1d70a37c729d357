// serosa bench [PART...] [--out DIR] [--quick] [--assets DIR] [--no-plots]
// The accuracy-versus-time suite: runs the named parts (none: all of them, in the
// registry's order, bench/suite/bench_registry.cpp), writes each part's tables as
// <out>/<table>.csv, a gnuplot script <out>/<plot>.gp per plot and, with gnuplot, <out>/<plot>.png;
// runs every monotonicity check; prints a summary and writes <out>/summary.json. Exit 0 only when
// every part returned, every curve was produced and every check held; 1 otherwise (an unknown part,
// an output folder that cannot be written, missing gnuplot without --no-plots, a failed part).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bench/suite/cmd_bench.h"

#include "bench/suite/bench_registry.h"
#include "engine/input_error.h"

namespace serosa::bench {

namespace {

namespace fs = std::filesystem;

struct BenchArgs {
  std::vector<std::string> parts;  // names; empty: all
  std::string out = "bench-out";   // output folder (created)
  std::string assets = "assets";   // the project's assets/ folder
  bool quick = false;
  bool no_plots = false;
};

std::string valid_names() {
  std::string s;
  for (const auto& p : bench::registered_parts()) {
    if (!s.empty()) s.append(" ");
    s.append(p.name);
  }
  return s;
}

// The output folder, created and writable, or an InputError naming --out.
fs::path prepare_out(const std::string& out) {
  const fs::path dir(out);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError("--out " + out, 0, "exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--out " + out, 0, "cannot create the folder: " + ec.message());
  const fs::path probe = dir / ".serosa-bench-probe";
  {
    std::ofstream os(probe);
    if (!os) throw InputError("--out " + out, 0, "cannot write into the folder");
  }
  fs::remove(probe, ec);
  return dir;
}

int run_bench(const BenchArgs& args) {
  std::vector<bench::PartEntry> selected;
  for (const std::string& name : args.parts) {
    const auto& all = bench::registered_parts();
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const bench::PartEntry& p) { return p.name == name; });
    if (it == all.end())
      throw InputError("bench", 0, "unknown part '" + name + "'", "one of: " + valid_names());
    const bool dup = std::any_of(selected.begin(), selected.end(),
                                 [&](const bench::PartEntry& p) { return p.name == name; });
    if (!dup) selected.push_back(*it);
  }
  if (args.parts.empty()) selected = bench::registered_parts();
  if (!fs::is_directory(args.assets))
    throw InputError("--assets " + args.assets, 0, "is not a folder",
                     "the project's assets/ folder (organ and box meshes)");
  bench::RunnerOptions options;
  options.plots = !args.no_plots;
  if (options.plots && !bench::program_runs(options.gnuplot)) {
    std::cerr << "error: gnuplot not found (it draws the plots): install it (Debian package "
                 "gnuplot-nox) or pass --no-plots\n";
    return 1;
  }
  options.bench.out = prepare_out(args.out);
  options.bench.assets_dir = fs::path(args.assets);
  options.bench.quick = args.quick;
  const bench::BenchReport report = bench::run_parts(selected, options, std::cout);
  const fs::path summary = options.bench.out / "summary.json";
  bench::write_summary_json(report, summary);
  bench::print_summary(report, std::cout);
  std::cout << "bench: summary written to " << summary.string() << '\n';
  return report.ok() ? 0 : 1;
}

}  // namespace

void add_bench_command(CLI::App& app, app::Action& action) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Accuracy versus time: CSV tables, gnuplot plots and monotonicity checks per knob");
  cmd->add_option("parts", args->parts, "Parts to run (default: all): " + valid_names());
  cmd->add_option("--out", args->out, "Output folder (created)")->capture_default_str();
  cmd->add_option("--assets", args->assets, "The project's assets/ folder")->capture_default_str();
  cmd->add_flag("--quick", args->quick, "Small sizes: the CI smoke run (< 2 min on 2 cores)");
  cmd->add_flag("--no-plots", args->no_plots, "Write the gnuplot scripts but do not run gnuplot");
  cmd->callback([&action, args] { action = [args] { return run_bench(*args); }; });
}

}  // namespace serosa::bench
