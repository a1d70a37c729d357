// The documents equal the program: every option a command's --help lists is in the README's
// synopsis of that command, and every key a real headless report writes (and the keys of its
// blocks) is documented in docs/headless-report.md.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app_test_util.h"
#include "engine/shell_command.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

bool option_char(char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-'; }

// The options (--name) a text names. (No std::regex: under ASan GCC 12 warns inside it.)
std::set<std::string> options_in(const std::string& text) {
  std::set<std::string> out;
  for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at + 2)) {
    std::size_t end = at + 2;
    if (end >= text.size() || text[end] < 'a' || text[end] > 'z') continue;
    while (end < text.size() && option_char(text[end])) ++end;
    out.insert(text.substr(at, end - at));
    at = end - 2;
  }
  out.erase("--help");
  return out;
}

// The README's synopsis cells of `serosa SUB` (first column of the commands table).
std::string readme_synopsis(const std::string& readme, const std::string& sub) {
  std::string cells;
  std::istringstream lines(readme);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("| `serosa " + sub + " ", 0) == 0 ||
        line.rfind("| `serosa " + sub + "`", 0) == 0)
      cells += line.substr(0, line.find("` |") + 1) + "\n";
  return cells;
}

// The options --help lists: the first long name on each of its option lines ("  --x" or
// "  -h,--help").
std::set<std::string> options_listed(const std::string& help) {
  std::set<std::string> out;
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first == 0 || first == std::string::npos || line[first] != '-') continue;
    const std::set<std::string> named =
        options_in(line.substr(first, line.find(' ', first) - first));
    out.insert(named.begin(), named.end());
  }
  return out;
}

TEST(DocsMatch, EveryOptionOfEveryCommandIsInTheReadmeSynopsis) {
  const std::string readme = file_text(source("README.md"));
  for (const char* sub : {"run", "headless", "replay", "batch", "check", "cut", "surface", "bench",
                          "tasks", "trainee", "cohort"}) {
    SCOPED_TRACE(sub);
    const CliResult help = run_serosa(std::string(sub) + " --help");
    ASSERT_EQ(help.code, 0) << help.out;
    const std::string synopsis = readme_synopsis(readme, sub);
    ASSERT_FALSE(synopsis.empty()) << "no README synopsis for serosa " << sub;
    const std::set<std::string> documented = options_in(synopsis);
    const std::set<std::string> listed = options_listed(help.out);
    EXPECT_GE(listed.size(), 1u) << help.out;
    for (const std::string& o : listed)
      EXPECT_TRUE(documented.count(o))
          << "serosa " << sub << " " << o << " is not in the README's synopsis:\n"
          << synopsis;
  }
}

TEST(DocsMatch, EveryKeyOfARealReportIsDocumented) {
  const fs::path dir = out_dir("docs_report");
  const CliResult r = run_serosa(
      "headless " + shell_quote(source("config/appendectomy.toml").string()) +
      " --steps 30 --report " + shell_quote((dir / "r.json").string()) + " --record " +
      shell_quote((dir / "r.lapr").string()) + " --export-final " +
      shell_quote((dir / "f.vtu").string()) + " --series " + shell_quote((dir / "s.csv").string()) +
      " --vtu-series " + shell_quote((dir / "vtu").string()) + " --golden " +
      shell_quote((dir / "g.json").string()) + " --update-golden");
  ASSERT_EQ(r.code, 0) << r.out;
  nlohmann::json report;
  std::ifstream(dir / "r.json") >> report;
  const std::string doc = file_text(source("docs/headless-report.md"));
  const auto documented = [&](const std::string& key) {
    return doc.find("`" + key + "`") != std::string::npos;
  };
  for (const auto& [key, value] : report.items()) {
    EXPECT_TRUE(documented(key)) << "report key " << key;
    if (!value.is_object() || key == "time_per_stage_ms" || key == "effects") continue;
    // The keys of a block; blocks keyed by names (tools, groups, stages) are not keys.
    if (key == "metrics" || key == "haptics" || key == "assessment") continue;
    for (const auto& [sub, inner] : value.items())
      EXPECT_TRUE(documented(sub) || documented(key + "." + sub))
          << "report key " << key << "." << sub;
  }
}

}  // namespace
}  // namespace serosa::app
