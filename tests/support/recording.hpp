#pragma once
// Test accessors for a Recording: a missing signal or scalar is a test failure (not a crash).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dynamics/recording.hpp"

namespace shudder::test {

inline const std::vector<double>& signal(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find(name);
  EXPECT_NE(s, nullptr) << name;
  static const std::vector<double> empty;
  return s ? s->values : empty;
}

inline double scalar(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find_scalar(name);
  EXPECT_NE(s, nullptr) << name;
  return s ? s->value : std::nan("");
}

}  // namespace shudder::test
