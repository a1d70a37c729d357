// `serosa bench` end to end: unknown parts and unusable output folders exit 1 naming them; the
// polar part (quick) writes its CSV files, gnuplot scripts, PNGs and summary.json and exits 0.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app_test_util.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;
using testing::out_dir;
using testing::run_serosa;
using testing::source;

TEST(CliBench, UnknownPartExitsOneNamingItAndTheValidOnes) {
  const fs::path dir = out_dir("cli_bench_unknown");
  const auto r = run_serosa("bench polar nonsense --quick --no-plots --out '" + dir.string() + "'");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("unknown part 'nonsense'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fem"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("polar"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "summary.json"));  // nothing ran
}

TEST(CliBench, BadOutFolderExitsOne) {
  const fs::path dir = out_dir("cli_bench_badout");
  const fs::path file = dir / "a_file";
  std::ofstream(file) << "x";
  const std::string assets = " --assets '" + source("assets").string() + "'";
  auto r = run_serosa("bench polar --quick --no-plots --out '" + file.string() + "'" + assets);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("--out"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not a folder"), std::string::npos) << r.out;
  r = run_serosa("bench polar --quick --no-plots --out '" + (file / "sub").string() + "'" + assets);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("cannot create"), std::string::npos) << r.out;
  r = run_serosa("bench polar --quick --no-plots --out '" + dir.string() + "' --assets '" +
                 (dir / "no_assets").string() + "'");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("--assets"), std::string::npos) << r.out;
}

TEST(CliBench, PolarQuickWritesTablesPlotsAndSummary) {
  const fs::path dir = out_dir("cli_bench_polar");
  const bool plots = std::system("gnuplot --version > /dev/null 2>&1") == 0;
  const auto r = run_serosa("bench polar --quick --out '" + dir.string() + "' --assets '" +
                            source("assets").string() + "'" + (plots ? "" : " --no-plots"));
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* kind : {"mild", "large", "flat", "inverted"}) {
    const std::string stem = std::string("polar_") + kind;
    EXPECT_TRUE(fs::exists(dir / (stem + ".csv"))) << stem;
    EXPECT_TRUE(fs::exists(dir / (stem + ".gp"))) << stem;
    if (plots) {
      EXPECT_GT(fs::file_size(dir / (stem + ".png")), 1000U) << stem;
    }
  }
  std::ifstream is(dir / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(is);
  EXPECT_TRUE(j.at("ok").get<bool>());
  EXPECT_TRUE(j.at("quick").get<bool>());
  ASSERT_EQ(j.at("parts").size(), 1U);
  EXPECT_EQ(j.at("parts")[0].at("name"), "polar");
  EXPECT_EQ(j.at("parts")[0].at("checks").size(), 8U);
  EXPECT_NE(r.out.find("every check held"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace serosa::app
