#include "app/emulated_rig_process.h"

#include <unistd.h>

#include <algorithm>
#include <climits>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "haptics/emulated_rig.h"

namespace serosa::app {
namespace {

// This process's command line, its program replaced by the executable's own path (so the rerun
// finds it whatever the working directory and PATH).
std::vector<std::string> own_command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  std::vector<std::string> args;
  for (std::size_t b = 0; b < all.size();) {
    const std::size_t e = std::min(all.find('\0', b), all.size());
    args.push_back(all.substr(b, e - b));
    b = e + 1;
  }
  if (args.empty()) throw std::runtime_error("cannot read /proc/self/cmdline");
  char exe[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) args[0].assign(exe, static_cast<std::size_t>(n));
  return args;
}

}  // namespace

bool emulates_rig(const Scene& scene) {
  return std::any_of(scene.tools.begin(), scene.tools.end(), [](const Tool& t) {
    return t.device.kind == DeviceKind::kRigEmulated && !t.device.script.empty();
  });
}

void run_under_umockdev_if_rig_emulated(const Scene& scene) {
  if (!emulates_rig(scene) || haptics::umockdev_preload_active()) return;
  std::vector<std::string> args = own_command_line();
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  haptics::ensure_umockdev_preload(argv.data());
}

}  // namespace serosa::app
