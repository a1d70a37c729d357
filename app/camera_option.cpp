#include "app/camera_option.h"

#include <string>

namespace serosa::app {

void add_camera_option(CLI::App& cmd, bool& fitted) {
  cmd.add_option_function<std::string>(
         "--camera", [&fitted](const std::string& v) { fitted = v == "fitted"; },
         "Pictures' camera: endoscope (default; what the trainee saw) or fitted (to the organs)")
      ->check(CLI::IsMember({"endoscope", "fitted"}));
}

}  // namespace serosa::app
