// Shared by the test executables that talk to the umockdev-emulated rig (tests/haptics,
// tests/app): umockdev's preload library must be in the process from its start, so such a test
// re-runs itself in a child under umockdev-wrapper.
#pragma once

#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

extern char** environ;

namespace serosa::test_support {

// Runs the current test in a child process under umockdev-wrapper; returns its exit status.
inline int rerun_under_umockdev() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string filter = "--gtest_filter=";
  filter.append(info->test_suite_name());
  filter.append(".");
  filter.append(info->name());
  std::vector<char> exe(4096, '\0');
  const ssize_t n = readlink("/proc/self/exe", exe.data(), exe.size() - 1);
  if (n <= 0) return -1;
  std::string asan = std::getenv("ASAN_OPTIONS") ? std::getenv("ASAN_OPTIONS") : "";
  if (!asan.empty()) asan.append(":");
  asan.append("verify_asan_link_order=0");
  setenv("ASAN_OPTIONS", asan.c_str(), 1);
  std::string wrapper = "umockdev-wrapper";
  std::vector<char*> argv{wrapper.data(), exe.data(), filter.data(), nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, "umockdev-wrapper", nullptr, nullptr, argv.data(), environ) != 0) {
    return -2;
  }
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -3;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace serosa::test_support
