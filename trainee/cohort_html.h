// The instructor's cohort page: one static HTML file with its CSS and SVG charts inline, no
// script and nothing fetched, that opens from the file system. In order: (a) every trainee x
// every task (sessions, best and last score, passed ever / the last session passed); (b) each
// trainee's learning curve; (c) the group's pass rate per task; (d) the criteria most often
// missed; (e) every session with its date, score, pass, why it failed, links to its recording and
// report and the command that replays it. A recording or report that is no longer where the
// database says is shown as missing, not linked.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "trainee/cohort.h"

namespace serosa::trainee {

struct PageContext {
  std::filesystem::path page_dir;  ///< where index.html goes: links are made relative to it
  std::filesystem::path db;        ///< the database it was gathered from, named on the page
  std::string written_utc;         ///< when, named on the page
};

[[nodiscard]] std::string cohort_html(const Cohort& cohort, const PageContext& context);

/// The recordings and reports the sessions name that are not there (moved or deleted).
[[nodiscard]] std::vector<std::string> missing_files(const Cohort& cohort);

}  // namespace serosa::trainee
