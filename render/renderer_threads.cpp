#include "render/renderer_threads.h"

#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace serosa::render {

int lower_software_renderer_threads(int nice) {
  int lowered = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    if (!std::getline(comm, name) || name.rfind("llvmpipe", 0) != 0) continue;
    const auto tid = static_cast<id_t>(std::stoul(task.path().filename().string()));
    if (setpriority(PRIO_PROCESS, tid, nice) == 0) ++lowered;
  }
  return lowered;
}

}  // namespace serosa::render
