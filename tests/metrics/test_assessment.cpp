// Scoring a session against a rubric (metrics/assessment.h). Properties over thousands of random
// rubrics and sessions: the score stays within 0-100 and each domain within 1-5; making any one
// metric worse never raises the score, a domain's rating or a pass; a failed critical metric fails
// the session whatever the score; every metric at its good end scores 100, at its poor end 0.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>

#include "metrics/assessment.h"

namespace serosa::metrics {
namespace {

Rubric random_rubric(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Rubric r;
  r.pass_score = 100.0 * u(rng);
  const int n = 5 + static_cast<int>(6 * u(rng));
  for (int i = 0; i < n; ++i) {
    RubricMetric m;
    m.name = "metric_";
    m.name += std::to_string(i);
    m.domain = std::string(kGoalsDomains[static_cast<std::size_t>(i) % kGoalsDomains.size()]);
    m.good = 10.0 * u(rng);
    m.poor = m.good + (u(rng) < 0.5 ? -1.0 : 1.0) * (0.1 + 5.0 * u(rng));
    m.limit = m.good + u(rng) * (m.poor - m.good);
    m.weight = 0.1 + 3.0 * u(rng);
    m.critical = u(rng) < 0.2;
    r.metrics.push_back(m);
  }
  return r;
}

std::map<std::string, double> random_values(const Rubric& r, std::mt19937& rng) {
  std::map<std::string, double> v;
  for (const RubricMetric& m : r.metrics) {
    std::uniform_real_distribution<double> u(std::min(m.good, m.poor) - 2.0,
                                             std::max(m.good, m.poor) + 2.0);
    v[m.name] = u(rng);
  }
  return v;
}

TEST(Assessment, WorseNeverScoresHigherOverRandomRubricsAndSessions) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const Rubric r = random_rubric(rng);
    const auto v = random_values(r, rng);
    const Assessment a = assess(r, v);
    ASSERT_GE(a.score, 0.0);
    ASSERT_LE(a.score, 100.0);
    ASSERT_EQ(a.domains.size(), kGoalsDomains.size());
    for (const auto& [d, rating] : a.domains) {
      ASSERT_GE(rating, 1) << d;
      ASSERT_LE(rating, 5) << d;
    }
    ASSERT_EQ(a.passed, a.failed.empty());
    // One metric made worse by a random amount (towards and past its poor end).
    const RubricMetric& m = r.metrics[static_cast<std::size_t>(trial) % r.metrics.size()];
    auto worse = v;
    worse[m.name] += (m.poor > m.good ? 1.0 : -1.0) * 3.0 * u(rng);
    const Assessment b = assess(r, worse);
    ASSERT_LE(b.score, a.score + 1e-9) << m.name;
    ASSERT_LE(b.domains.at(m.domain), a.domains.at(m.domain)) << m.name;
    if (!a.passed) {
      ASSERT_FALSE(b.passed) << m.name;
    }
  }
}

TEST(Assessment, ACriticalFailureFailsWhateverTheScore) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 1000; ++trial) {
    Rubric r = random_rubric(rng);
    r.pass_score = 0.0;
    r.metrics[0].critical = true;
    auto v = random_values(r, rng);
    const RubricMetric& m = r.metrics[0];
    v[m.name] = m.poor + (m.poor > m.good ? 1e-3 : -1e-3);  // just past its poor end
    const Assessment a = assess(r, v);
    ASSERT_FALSE(a.passed);
    ASSERT_FALSE(a.metrics[0].passed);
    bool named = false;  // other random metrics may be critical and failed too
    for (const std::string& f : a.failed) named = named || f.rfind(m.name + " = ", 0) == 0;
    ASSERT_TRUE(named) << m.name;
    v[m.name] = m.good;  // and at its good end it passes, all else equal
    const Assessment b = assess(r, v);
    ASSERT_TRUE(b.metrics[0].passed);
  }
}

TEST(Assessment, TheEndsOfEveryMetricScoreTheEndsOfTheScale) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 500; ++trial) {
    const Rubric r = random_rubric(rng);
    std::map<std::string, double> best, worst;
    for (const RubricMetric& m : r.metrics) {
      best[m.name] = m.good;
      worst[m.name] = m.poor;
    }
    const Assessment a = assess(r, best);
    EXPECT_NEAR(a.score, 100.0, 1e-9);
    for (const auto& [d, rating] : a.domains) EXPECT_EQ(rating, 5) << d;
    EXPECT_EQ(a.passed, true);
    const Assessment b = assess(r, worst);
    EXPECT_NEAR(b.score, 0.0, 1e-9);
    for (const auto& [d, rating] : b.domains) EXPECT_EQ(rating, 1) << d;
  }
}

TEST(Assessment, AMissingValueIsAnErrorNamingIt) {
  std::mt19937 rng(1);
  const Rubric r = random_rubric(rng);
  auto v = random_values(r, rng);
  v.erase(r.metrics[2].name);
  try {
    (void)assess(r, v);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    std::string quoted = r.metrics[2].name;
    quoted.insert(quoted.begin(), '\'');
    quoted.push_back('\'');
    EXPECT_NE(std::string(e.what()).find(quoted), std::string::npos);
  }
}

TEST(Assessment, TheReportCarriesTheContract) {
  std::mt19937 rng(2);
  Rubric r = random_rubric(rng);
  r.metrics[0].unit = "m";
  const auto v = random_values(r, rng);
  const nlohmann::json j = assessment_json(assess(r, v), r);
  for (const char* key : {"score", "passed", "domains", "metrics", "failed", "pass_score"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const std::string_view d : kGoalsDomains) EXPECT_TRUE(j["domains"].contains(d)) << d;
  const auto& m0 = j["metrics"][r.metrics[0].name];
  EXPECT_EQ(m0["value"].get<double>(), v.at(r.metrics[0].name));
  EXPECT_EQ(m0["threshold"].get<double>(), r.metrics[0].limit);
  EXPECT_EQ(m0["unit"], "m");
}

}  // namespace
}  // namespace serosa::metrics
