// Writing the cohort's page (trainee/cohort_html.h) safely: every text escaped for HTML (trainee
// names and file paths may hold <, & and quotes), links to the sessions' files that open from the
// file system, and numbers as the page prints them.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace serosa::trainee {

/// `text` with &, <, >, " and ' replaced by entities: safe in element text and quoted attributes.
[[nodiscard]] std::string html_escape(std::string_view text);

/// `path` percent-encoded for a URL (letters, digits, '/', '-', '_', '.', '~' as they are).
[[nodiscard]] std::string url_path(std::string_view path);

/// The link from a page in `page_dir` to `file`: relative when the file lies in the folder that
/// holds `page_dir` (so the page, the database's folder and the recordings move together), else
/// an absolute file:// URL. Not HTML-escaped: pass it through html_escape().
[[nodiscard]] std::string file_href(const std::filesystem::path& file,
                                    const std::filesystem::path& page_dir);

/// A score as the page prints it: "77.4", "80"; "–" when none.
[[nodiscard]] std::string score_text(std::optional<double> score);

/// "2026-12-03T14:25:00Z" as "2026-12-03 14:25:00 UTC".
[[nodiscard]] std::string date_text(const std::string& started_utc);

}  // namespace serosa::trainee
