#include "engine/scene/toml_reader.h"

#include <algorithm>
#include <cmath>

#include "engine/input_error.h"

namespace serosa {

toml::table TomlReader::parse(const std::string& expected) const {
  if (!std::filesystem::is_regular_file(m_file))
    throw InputError(m_file.string(), 0, "no such file", expected);
  try {
    return toml::parse_file(m_file.string());
  } catch (const toml::parse_error& e) {
    throw InputError(m_file.string(), static_cast<std::int64_t>(e.source().begin.line),
                     "TOML syntax error: " + std::string(e.description()), expected);
  }
}

void TomlReader::check_keys(const toml::table& t, const std::string& path,
                            std::initializer_list<std::string_view> keys) const {
  for (const auto& [k, v] : t)
    if (std::find(keys.begin(), keys.end(), k.str()) == keys.end()) {
      std::string list;
      for (const auto key : keys) list.append(list.empty() ? "" : ", ").append(key);
      fail(v, path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()),
           "unknown key", "one of " + list);
    }
}

const toml::node& TomlReader::required(const toml::table& t, const std::string& path,
                                       std::string_view key) const {
  const auto* n = t.get(key);
  if (n == nullptr)
    throw InputError(m_file.string(), static_cast<std::int64_t>(t.source().begin.line),
                     path + ": missing key '" + std::string(key) + "'", "the key set");
  return *n;
}

double TomlReader::number(const toml::node& n, const std::string& path) const {
  const auto v = n.value<double>();
  if (!v || !std::isfinite(*v)) fail(n, path, "not a finite number", "a number");
  return *v;
}

std::int64_t TomlReader::integer(const toml::node& n, const std::string& path) const {
  if (!n.is_integer()) fail(n, path, "not an integer", "an integer");
  return *n.value<std::int64_t>();
}

std::string TomlReader::text(const toml::node& n, const std::string& path) const {
  const auto v = n.value<std::string>();
  if (!v) fail(n, path, "not a string", "a string");
  return *v;
}

bool TomlReader::boolean(const toml::node& n, const std::string& path) const {
  const auto v = n.value<bool>();
  if (!v) fail(n, path, "not a boolean", "true or false");
  return *v;
}

void TomlReader::fail(const toml::node& n, const std::string& path, const std::string& what,
                      const std::string& expected) const {
  throw InputError(m_file.string(), static_cast<std::int64_t>(n.source().begin.line),
                   path + ": " + what, expected);
}

}  // namespace serosa
