// Software GL's rasterizer threads yield to the solver (render/renderer_threads.h): on llvmpipe
// they are found by name and each gets the nice value asked for; nothing else is touched.
#include "render/renderer_threads.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/gl_context.h"

namespace serosa::render {
namespace {

std::string thread_name(const std::filesystem::path& task) {
  std::ifstream comm(task / "comm");
  std::string name;
  std::getline(comm, name);
  return name;
}

TEST(RendererThreads, LlvmpipeWorkersGetTheNiceValueAndNothingElseDoes) {
  OffscreenContext ctx(64, 64, 1);
  const int before = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  const int lowered = lower_software_renderer_threads(7);
  if (ctx.gl_renderer().find("llvmpipe") == std::string::npos) {
    EXPECT_EQ(lowered, 0);
    return;
  }
  EXPECT_GT(lowered, 0);
  int seen = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    const auto tid = static_cast<id_t>(std::stoul(task.path().filename().string()));
    errno = 0;
    const int nice = getpriority(PRIO_PROCESS, tid);
    ASSERT_EQ(errno, 0);
    if (thread_name(task.path()).rfind("llvmpipe", 0) == 0) {
      EXPECT_EQ(nice, 7);
      ++seen;
    } else if (tid == static_cast<id_t>(gettid())) {
      EXPECT_EQ(nice, before);  // the caller's own thread keeps its priority
    }
  }
  EXPECT_EQ(seen, lowered);
}

}  // namespace
}  // namespace serosa::render
