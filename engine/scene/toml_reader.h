// TomlReader: reads one TOML file of ours (a rubric, the task list) and names the file, the line
// and the key in every error: an unknown key, a missing one, a value of the wrong type.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace serosa {

class TomlReader {
 public:
  explicit TomlReader(std::filesystem::path file) : m_file(std::move(file)) {}

  /// The whole file; InputError when it is missing or not TOML (`expected` says what it holds).
  [[nodiscard]] toml::table parse(const std::string& expected) const;

  /// InputError at the first key of `t` not in `keys` (`path` names `t`: "" for the root).
  void check_keys(const toml::table& t, const std::string& path,
                  std::initializer_list<std::string_view> keys) const;
  [[nodiscard]] const toml::node& required(const toml::table& t, const std::string& path,
                                           std::string_view key) const;
  [[nodiscard]] double number(const toml::node& n, const std::string& path) const;
  [[nodiscard]] std::int64_t integer(const toml::node& n, const std::string& path) const;
  [[nodiscard]] std::string text(const toml::node& n, const std::string& path) const;
  [[nodiscard]] bool boolean(const toml::node& n, const std::string& path) const;
  [[noreturn]] void fail(const toml::node& n, const std::string& path, const std::string& what,
                         const std::string& expected) const;

  [[nodiscard]] const std::filesystem::path& file() const noexcept { return m_file; }

 private:
  std::filesystem::path m_file;
};

}  // namespace serosa
