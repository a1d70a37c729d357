#include "trainee/cohort_csv.h"

#include <cstdio>

namespace serosa::trainee {

namespace {

std::string score(std::optional<double> s) {
  if (!s) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", *s);
  return buf;
}

}  // namespace

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string q = "\"";
  for (const char c : text) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string cohort_csv(const Cohort& cohort) {
  std::string out = "trainee,task,sessions,best,last,passed,last_passed,passes,pass_score\n";
  for (const TraineeCohort& t : cohort.trainees)
    for (const std::string& task : cohort.tasks) {
      const TaskProgress* p = t.on(task);
      out.append(csv_field(t.name)).append(",").append(csv_field(task)).append(",");
      if (p == nullptr) {
        out.append("0,,,no,no,0,\n");
        continue;
      }
      out.append(std::to_string(p->sessions))
          .append(",")
          .append(score(p->best))
          .append(",")
          .append(score(p->last))
          .append(p->passed > 0 ? ",yes" : ",no")
          .append(p->last_passed ? ",yes," : ",no,")
          .append(std::to_string(p->passed))
          .append(",")
          .append(score(p->pass_score))
          .append("\n");
    }
  return out;
}

}  // namespace serosa::trainee
