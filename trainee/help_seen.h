// The controls panel shows by itself the first time a trainee starts a session: who has seen it
// is kept in a small text file beside the progress database (one trainee name a line, "*" for
// sessions run without a name, per machine).
#pragma once

#include <filesystem>
#include <string>

namespace serosa::trainee {

/// The file that remembers who has seen the controls: beside the progress database `db` (empty:
/// default_progress_db()), named help_seen.txt.
[[nodiscard]] std::filesystem::path help_seen_file(const std::filesystem::path& db = {});

/// Whether `trainee` (empty: whoever runs without a name on this machine) has not been shown the
/// controls yet according to `file`; marks them shown. A file that cannot be written is warned
/// about once (naming it) and the panel is shown: a trainee is never left without the controls.
[[nodiscard]] bool first_time_help(const std::filesystem::path& file, const std::string& trainee);

}  // namespace serosa::trainee
