// serosa run SCENE: the trainee session in a window.
#include <cstdlib>
#include <memory>
#include <string>

#include "app/command.h"
#include "app/session.h"
#include "engine/input_error.h"

namespace serosa::app {

void add_run_command(CLI::App& app, Action& action) {
  auto scene = std::make_shared<std::string>();
  auto seconds = std::make_shared<double>(0.0);
  auto snapshot = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("run", "The trainee session: a window, the rig or the mouse");
  cmd->add_option("scene", *scene, "Scene TOML file")->required();
  cmd->add_option("--seconds", *seconds, "Close the window after this much wall time (0: never)");
  cmd->add_option("--snapshot", *snapshot,
                  "Also write the last picture drawn to this PNG (for checks and bug reports)");
  cmd->callback([&action, scene, seconds, snapshot] {
    action = [scene, seconds, snapshot] {
      const char* x = std::getenv("DISPLAY");
      const char* wl = std::getenv("WAYLAND_DISPLAY");
      if ((x == nullptr || *x == '\0') && (wl == nullptr || *wl == '\0'))
        throw InputError(*scene, 0, "serosa run needs a display and none is set",
                         "DISPLAY or WAYLAND_DISPLAY; without one use `serosa headless`");
      return run_session(*scene, *seconds, *snapshot);
    };
  });
}

}  // namespace serosa::app
