// The controls panel shows by itself once per trainee (trainee/help_seen.h): the first session of a
// name, or of this machine without one, and never again for them; a file that cannot be written
// shows it every time rather than never.
#include <gtest/gtest.h>

#include <filesystem>

#include "app_test_util.h"
#include "trainee/help_seen.h"

namespace serosa::app {
namespace {

using namespace serosa::trainee;

using testing::out_dir;

TEST(HelpSeen, OncePerTraineeAndOncePerMachineWithoutAName) {
  const std::filesystem::path file = out_dir("help_seen") / "nested" / "help_seen.txt";
  EXPECT_TRUE(first_time_help(file, ""));
  EXPECT_FALSE(first_time_help(file, ""));
  EXPECT_TRUE(first_time_help(file, "ada"));
  EXPECT_FALSE(first_time_help(file, "ada"));
  EXPECT_TRUE(first_time_help(file, "grace"));
  EXPECT_FALSE(first_time_help(file, ""));
  EXPECT_EQ(help_seen_file("/some/where/progress.sqlite"),
            std::filesystem::path("/some/where/help_seen.txt"));
}

TEST(HelpSeen, AFileThatCannotBeWrittenShowsTheControlsEveryTime) {
  const std::filesystem::path dir = out_dir("help_unwritable");
  const std::filesystem::path file = dir / "is_a_directory";
  std::filesystem::create_directories(file);  // a directory where the file should be
  EXPECT_TRUE(first_time_help(file, "ada"));
  EXPECT_TRUE(first_time_help(file, "ada"));
}

}  // namespace
}  // namespace serosa::app
