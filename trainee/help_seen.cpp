#include "trainee/help_seen.h"

#include <spdlog/spdlog.h>

#include <fstream>
#include <system_error>

#include "trainee/progress_db.h"

namespace serosa::trainee {

std::filesystem::path help_seen_file(const std::filesystem::path& db) {
  const std::filesystem::path base = db.empty() ? default_progress_db() : db;
  return base.parent_path() / "help_seen.txt";
}

bool first_time_help(const std::filesystem::path& file, const std::string& trainee) {
  const std::string who = trainee.empty() ? "*" : trainee;
  {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
      if (line == who) return false;
  }
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  std::ofstream out(file, std::ios::app);
  out << who << '\n';
  if (!out)
    spdlog::warn("cannot remember that the controls were shown ({}): they show again next time",
                 file.string());
  return true;
}

}  // namespace serosa::trainee
