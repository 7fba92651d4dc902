#pragma once
// record(key, printf-format, args...): a measured figure written into the test's XML report
// (GoogleTest RecordProperty), so a passing run still shows how close it came to its bound.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace shudder::test {

template <typename... Args>
void record(const std::string& key, const char* format, Args... args) {
  char buf[768];
  std::snprintf(buf, sizeof buf, format, args...);
  ::testing::Test::RecordProperty(key, buf);
}

}  // namespace shudder::test
