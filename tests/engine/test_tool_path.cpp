// Tool path CSV: parsing, interpolation (lerp + slerp, clamped) and every validation error.
#include "engine/scene/tool_path.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engine/input_error.h"
#include "engine/instrument_hold.h"
#include "engine/math.h"

namespace serosa {
namespace {

const std::string kHeader = "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n";

// Parses `text` and expects an InputError at `line` whose message contains `needle`.
void expect_error(const std::string& text, std::int64_t line, const std::string& needle) {
  try {
    (void)parse_tool_path_text(text, "path.csv");
    ADD_FAILURE() << "no error; expected one at line " << line << " about '" << needle << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "path.csv");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    if (line > 0) {
      EXPECT_NE(std::string(e.what()).find("path.csv:" + std::to_string(line) + ":"),
                std::string::npos)
          << e.what();
    }
  }
}

Quat quat_of(const ToolState& s) {
  return Quat(s.quat_wxyz[0], s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3]);
}

TEST(ToolPath, ParsesToolsInOrderOfFirstAppearance) {
  const ToolPath p = parse_tool_path_text(kHeader +
                                              "0,scissors,0,0,0,1,0,0,0,0\n"
                                              "0,grasper,1,0,0,1,0,0,0,0.5\n"
                                              "1,scissors,0,1,0,1,0,0,0,0\n",
                                          "p.csv");
  ASSERT_EQ(p.tools.size(), 2u);
  EXPECT_EQ(p.tools[0], "scissors");
  EXPECT_EQ(p.tools[1], "grasper");
  EXPECT_EQ(p.samples[0].size(), 2u);
  EXPECT_EQ(p.samples[1].size(), 1u);
  EXPECT_EQ(p.index_of("grasper"), 1u);
  EXPECT_FALSE(p.index_of("camera").has_value());
  EXPECT_DOUBLE_EQ(p.end_time_s(), 1.0);
  EXPECT_DOUBLE_EQ(p.samples[1][0].jaw_rad, 0.5);
}

TEST(ToolPath, NormalizesQuaternions) {
  const ToolPath p = parse_tool_path_text(kHeader + "0,g,0,0,0,1.2,0,0,0,0\n", "p.csv");
  EXPECT_DOUBLE_EQ(p.samples[0][0].quat_wxyz[0], 1.0);
  const ToolPath q = parse_tool_path_text(kHeader + "0,g,0,0,0,0.6,0.8,0,0,0\n", "p.csv");
  EXPECT_NEAR(quat_of(q.samples[0][0]).norm(), 1.0, 1e-15);
}

TEST(ToolPath, AcceptsCommentsBlankLinesSpacesAndCrlf) {
  const ToolPath p = parse_tool_path_text(
      "# scripted path\r\n\r\n t , tool ,px,py,pz,qw,qx,qy,qz,jaw\r\n"
      "0.0, g ,+1e-2,0,0,1,0,0,0,0\r\n# pause\n\n2.5,g,0,0,0,1,0,0,0,0\r\n",
      "p.csv");
  ASSERT_EQ(p.tools.size(), 1u);
  EXPECT_EQ(p.tools[0], "g");
  ASSERT_EQ(p.samples[0].size(), 2u);
  EXPECT_DOUBLE_EQ(p.samples[0][0].tip_m[0], 0.01);
  EXPECT_DOUBLE_EQ(p.samples[0][1].time_s, 2.5);
}

TEST(ToolPath, InterpolatesPositionAndJawLinearly) {
  const ToolPath p = parse_tool_path_text(kHeader +
                                              "1,g,0,0,0,1,0,0,0,0\n"
                                              "3,g,0.2,-0.4,0.6,1,0,0,0,1.0\n",
                                          "p.csv");
  const ToolState s = sample(p, 0, 1.5);
  EXPECT_DOUBLE_EQ(s.time_s, 1.5);
  EXPECT_NEAR(s.tip_m[0], 0.05, 1e-15);
  EXPECT_NEAR(s.tip_m[1], -0.1, 1e-15);
  EXPECT_NEAR(s.tip_m[2], 0.15, 1e-15);
  EXPECT_NEAR(s.jaw_rad, 0.25, 1e-15);
  EXPECT_EQ(s.tick, 0u);
  EXPECT_EQ(s.buttons, 0u);
}

TEST(ToolPath, SlerpsOrientation) {
  // Identity to 90 degrees about z: halfway is 45 degrees about z.
  const double h = std::sqrt(0.5);
  const ToolPath p =
      parse_tool_path_text(kHeader + "0,g,0,0,0,1,0,0,0,0\n" + "1,g,0,0,0," + std::to_string(h) +
                               ",0,0," + std::to_string(h) + ",0\n",
                           "p.csv");
  const Quat q = quat_of(sample(p, "g", 0.5));
  const Quat expected(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
  EXPECT_NEAR(q.angularDistance(expected), 0.0, 1e-6);
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  // A quarter of the way: 22.5 degrees (slerp is uniform in angle).
  const Quat q4 = quat_of(sample(p, "g", 0.25));
  EXPECT_NEAR(q4.angularDistance(Quat::Identity()), std::numbers::pi / 8, 1e-6);
}

TEST(ToolPath, SlerpTakesTheShortestArc) {
  // q and -q are the same rotation: halfway must stay the identity, not swing through 180.
  const ToolPath p = parse_tool_path_text(kHeader +
                                              "0,g,0,0,0,1,0,0,0,0\n"
                                              "1,g,0,0,0,-1,0,0,0,0\n",
                                          "p.csv");
  EXPECT_NEAR(quat_of(sample(p, 0, 0.5)).angularDistance(Quat::Identity()), 0.0, 1e-9);
}

TEST(ToolPath, ClampsAtBothEnds) {
  const ToolPath p = parse_tool_path_text(kHeader +
                                              "1,g,1,2,3,1,0,0,0,0.1\n"
                                              "2,g,4,5,6,1,0,0,0,0.2\n",
                                          "p.csv");
  const ToolState before = sample(p, 0, -10.0);
  EXPECT_DOUBLE_EQ(before.tip_m[0], 1.0);
  EXPECT_DOUBLE_EQ(before.jaw_rad, 0.1);
  EXPECT_DOUBLE_EQ(before.time_s, -10.0);
  EXPECT_EQ(before.tick, 0u);
  const ToolState after = sample(p, 0, 99.0);
  EXPECT_DOUBLE_EQ(after.tip_m[2], 6.0);
  EXPECT_DOUBLE_EQ(after.jaw_rad, 0.2);
  EXPECT_EQ(after.tick, 1u);
  EXPECT_DOUBLE_EQ(sample(p, 0, 2.0).tip_m[0], 4.0);  // exactly at the last sample
}

TEST(ToolPath, SingleSampleIsConstant) {
  const ToolPath p = parse_tool_path_text(kHeader + "0.5,cam,0,0.1,0,1,0,0,0,0\n", "p.csv");
  for (const double t : {0.0, 0.5, 7.0}) EXPECT_DOUBLE_EQ(sample(p, "cam", t).tip_m[1], 0.1);
}

TEST(ToolPath, ButtonsAreHeldFromTheirRowToTheNext) {
  // The pedal (bit 1) pressed from 1 s to 2 s, the clutch (bit 0) at 3 s; without the column, 0.
  const ToolPath p = parse_tool_path_text(
      "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n"
      "0,g,0,0,0,1,0,0,0,0,0\n"
      "1,g,1,0,0,1,0,0,0,0,2\n"
      "2,g,2,0,0,1,0,0,0,0,0\n"
      "3,g,3,0,0,1,0,0,0,0,1\n",
      "p.csv");
  const std::vector<std::pair<double, std::uint32_t>> expected{
      {0.0, 0u}, {0.99, 0u}, {1.0, 2u}, {1.5, 2u}, {2.0, 0u}, {2.9, 0u}, {3.0, 1u}, {9.0, 1u}};
  for (const auto& [t, b] : expected) EXPECT_EQ(sample(p, "g", t).buttons, b) << t;
  EXPECT_NEAR(sample(p, "g", 1.5).tip_m[0], 1.5, 1e-12);  // the pose still interpolates
  const ToolPath plain = parse_tool_path_text(kHeader + "0,g,0,0,0,1,0,0,0,0\n", "q.csv");
  EXPECT_EQ(sample(plain, "g", 0.0).buttons, 0u);
}

TEST(ToolPathErrors, ButtonsMustBeAMask) {
  const std::string h = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n";
  for (const std::string bad : {"-1", "1.5", "65536", "x"})
    expect_error(h + "0,g,0,0,0,1,0,0,0,0," + bad + "\n", 2, "buttons");
  expect_error(h + "0,g,0,0,0,1,0,0,0,0\n", 2, "11 columns");  // the header promised buttons
}

TEST(ToolPath, TheHandColumnSaysWhoHoldsTheToolFromItsRowOn) {
  const ToolPath p = parse_tool_path_text(
      "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n"
      "0,g,0,0,0,1,0,0,0,0,2,port\n"
      "1,g,1,0,0,1,0,0,0,0,2,right\n"
      "2,g,2,0,0,1,0,0,0,0,0,left\n"
      "3,g,3,0,0,1,0,0,0,0,0,\n",
      "p.csv");
  const ToolState waiting = sample(p, "g", 0.5);
  EXPECT_TRUE(in_port(waiting));
  EXPECT_FALSE(holder(waiting));
  EXPECT_EQ(waiting.buttons & kDeviceButtons, 2u);  // the device's buttons stay as they were
  EXPECT_EQ(holder(sample(p, "g", 1.5)), Hand::kRight);
  EXPECT_FALSE(in_port(sample(p, "g", 1.5)));
  EXPECT_EQ(holder(sample(p, "g", 2.0)), Hand::kLeft);
  EXPECT_FALSE(holder(sample(p, "g", 3.0)));  // empty: played directly
  EXPECT_FALSE(in_port(sample(p, "g", 3.0)));
}

TEST(ToolPathErrors, TheHandMustBeAHand) {
  const std::string h = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n";
  for (const std::string bad : {"middle", "LEFT", "1"})
    expect_error(h + "0,g,0,0,0,1,0,0,0,0,0," + bad + "\n", 2, "hand");
  expect_error(h + "0,g,0,0,0,1,0,0,0,0,0\n", 2, "12 columns");
}

// A hand holds one instrument at a time: a second taken before the first is put in its port is
// an error naming the hand, both tools and the time; an exchange at one instant (the first's
// row saying port at the time the second's says the hand) is not.
TEST(ToolPathErrors, AHandHoldsOneToolAtATime) {
  const std::string h = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n";
  expect_error(h + "0,a,0,0,0,1,0,0,0,0,0,right\n"
                   "2,a,0,0,0,1,0,0,0,0,0,port\n"
                   "1.5,b,0,0,0,1,0,0,0,0,0,right\n",
               0, "the right hand holds both \"a\" and \"b\" at 1.500 s");
  expect_error(h + "0,a,0,0,0,1,0,0,0,0,0,left\n"
                   "3,b,0,0,0,1,0,0,0,0,0,left\n",
               0, "the left hand holds both");  // a never put down
  const ToolPath ok = parse_tool_path_text(h + "0,a,0,0,0,1,0,0,0,0,0,right\n"
                                               "1,a,0,0,0,1,0,0,0,0,0,right\n"
                                               "2,a,0,0,0,1,0,0,0,0,0,port\n"
                                               "0,b,0,0,0,1,0,0,0,0,0,port\n"
                                               "2,b,0,0,0,1,0,0,0,0,0,right\n"
                                               "0,c,0,0,0,1,0,0,0,0,0,left\n",
                                           "p.csv");
  EXPECT_EQ(holder(sample(ok, "b", 2.0)), Hand::kRight);
}

TEST(ToolPath, EqualTimesMakeAJump) {
  const ToolPath p = parse_tool_path_text(kHeader +
                                              "0,g,0,0,0,1,0,0,0,0\n"
                                              "1,g,1,0,0,1,0,0,0,0\n"
                                              "1,g,5,0,0,1,0,0,0,0\n"
                                              "2,g,6,0,0,1,0,0,0,0\n",
                                          "p.csv");
  EXPECT_NEAR(sample(p, 0, 0.999999).tip_m[0], 1.0, 1e-5);
  EXPECT_DOUBLE_EQ(sample(p, 0, 1.0).tip_m[0], 5.0);  // the later row at the shared time
  EXPECT_DOUBLE_EQ(sample(p, 0, 1.5).tip_m[0], 5.5);
}

TEST(ToolPath, UnknownToolThrowsOutOfRange) {
  const ToolPath p = parse_tool_path_text(kHeader + "0,g,0,0,0,1,0,0,0,0\n", "p.csv");
  EXPECT_THROW((void)sample(p, "scissors", 0.0), std::out_of_range);
  EXPECT_THROW((void)sample(p, std::size_t{1}, 0.0), std::out_of_range);
}

TEST(ToolPath, ReadsAFile) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("serosa_tool_path_" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream out(file);
    out << kHeader << "0,g,0,0,0,1,0,0,0,0\n";
  }
  const ToolPath p = read_tool_path(file);
  EXPECT_EQ(p.file, file.string());
  EXPECT_EQ(p.tools.size(), 1u);
  std::filesystem::remove(file);
}

// ---- errors: one test per kind, each naming the line ----

TEST(ToolPathErrors, MissingFile) {
  try {
    (void)read_tool_path("/nonexistent/serosa/path.csv");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/serosa/path.csv"), std::string::npos);
  }
}

TEST(ToolPathErrors, EmptyFile) { expect_error("", 0, "empty tool path"); }
TEST(ToolPathErrors, OnlyComments) { expect_error("# nothing\n\n", 0, "empty tool path"); }

TEST(ToolPathErrors, WrongHeader) {
  expect_error("# c\nt,tool,x,y,z,qw,qx,qy,qz,jaw\n", 2, "header");
  expect_error("t,tool,px,py,pz,qw,qx,qy,qz\n", 1, "header");
}

TEST(ToolPathErrors, NoRows) { expect_error(kHeader + "# none\n", 2, "no rows"); }

TEST(ToolPathErrors, WrongColumnCount) {
  expect_error(kHeader + "0,g,0,0,0,1,0,0,0,0\n0,g,0,0,0,1,0,0,0\n", 3, "9 columns");
  expect_error(kHeader + "0,g,0,0,0,1,0,0,0,0,7\n", 2, "11 columns");
}

TEST(ToolPathErrors, NotANumber) {
  expect_error(kHeader + "0,g,0,abc,0,1,0,0,0,0\n", 2, "column 'py'");
  expect_error(kHeader + "0,g,0,0,0,1,0,0,0,\n", 2, "column 'jaw'");
  expect_error(kHeader + "1s,g,0,0,0,1,0,0,0,0\n", 2, "column 't'");
}

TEST(ToolPathErrors, NotFinite) {
  expect_error(kHeader + "0,g,nan,0,0,1,0,0,0,0\n", 2, "not finite");
  expect_error(kHeader + "0,g,0,0,inf,1,0,0,0,0\n", 2, "column 'pz'");
}

TEST(ToolPathErrors, EmptyToolName) { expect_error(kHeader + "0, ,0,0,0,1,0,0,0,0\n", 2, "tool"); }

TEST(ToolPathErrors, NegativeTime) {
  expect_error(kHeader + "-0.1,g,0,0,0,1,0,0,0,0\n", 2, "negative");
}

TEST(ToolPathErrors, TimeGoesBackwardsPerTool) {
  // Another tool's rows in between are fine; the same tool going back is not.
  expect_error(kHeader +
                   "0,g,0,0,0,1,0,0,0,0\n"
                   "2,g,0,0,0,1,0,0,0,0\n"
                   "0,s,0,0,0,1,0,0,0,0\n"
                   "1,g,0,0,0,1,0,0,0,0\n",
               5, "backwards (line 3");
}

TEST(ToolPathErrors, QuaternionNotUnit) {
  expect_error(kHeader + "0,g,0,0,0,0.1,0,0,0,0\n", 2, "quaternion");
  expect_error(kHeader + "0,g,0,0,0,0,0,0,0,0\n", 2, "norm 0");
  expect_error(kHeader + "0,g,0,0,0,2,2,0,0,0\n", 2, "quaternion");
}

TEST(ToolPathErrors, JawOutOfRange) {
  expect_error(kHeader + "0,g,0,0,0,1,0,0,0,-0.1\n", 2, "column 'jaw'");
  expect_error(kHeader + "0,g,0,0,0,1,0,0,0,4\n", 2, "column 'jaw'");
}

}  // namespace
}  // namespace serosa
