// Parameter validation (one place for every check) and the step count.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/params.hpp"
#include "scenes/validate.hpp"

namespace mpmstab {
namespace {

std::vector<std::string> keys_of(const RunParams& p) {
  std::vector<std::string> keys;
  for (const auto& issue : validate(p))
    keys.push_back(issue.key);
  return keys;
}

TEST(Validate, DefaultsAreValid) {
  EXPECT_TRUE(validate(RunParams{}).empty());
}

TEST(Validate, EachBadValueIsNamedByItsKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::string, RunParams>> cases = [&] {
    std::vector<std::pair<std::string, RunParams>> c;
    auto add = [&](std::string key, auto f) {
      RunParams p;
      f(p);
      c.emplace_back(std::move(key), p);
    };
    add("E", [](RunParams& p) { p.E = -1; });
    add("E", [](RunParams& p) { p.E = 0; });
    add("E", [&](RunParams& p) { p.E = nan; });
    add("E", [&](RunParams& p) { p.E = inf; });
    add("A", [](RunParams& p) { p.A = -1e-3; });
    add("A", [&](RunParams& p) { p.A = nan; });
    add("dt", [](RunParams& p) { p.dt = 0; });
    add("dt", [](RunParams& p) { p.dt = -1e-3; });
    add("dt", [](RunParams& p) { p.dt = 2; });  // > T = 1
    add("dt", [&](RunParams& p) { p.dt = nan; });
    add("dt", [](RunParams& p) { p.dt = 1e-12; });  // 1e12 steps > max_steps
    add("T", [](RunParams& p) { p.T = 0; });
    add("T", [&](RunParams& p) { p.T = inf; });
    add("cells", [](RunParams& p) { p.cells = 0; });
    add("cells", [](RunParams& p) { p.cells = -3; });
    add("ppc", [](RunParams& p) { p.ppc = 0; });
    add("ppc", [](RunParams& p) { p.ppc = 1000; });
    add("max_steps", [](RunParams& p) { p.max_steps = 0; });
    add("history_stride", [](RunParams& p) { p.observe.history_stride = 0; });
    return c;
  }();
  for (const auto& [key, p] : cases) {
    const auto keys = keys_of(p);
    ASSERT_EQ(keys.size(), 1u) << key;
    EXPECT_EQ(keys[0], key);
  }
}

TEST(Validate, ReportsEveryProblemAtOnce) {
  RunParams p;
  p.E = -1;
  p.A = -1;
  p.cells = 0;
  EXPECT_EQ(keys_of(p), (std::vector<std::string>{"E", "A", "cells"}));
}

TEST(StepCount, LandsOnTWithoutASliverStep) {
  EXPECT_EQ(*step_count(1.0, 1e-5), 100000);
  EXPECT_EQ(*step_count(1.0, 1e-3), 1000);
  EXPECT_EQ(*step_count(1.0, 1e-7), 10000000);
  EXPECT_EQ(*step_count(1.0, 0.3), 4);       // 0.3, 0.6, 0.9, then 0.1 to land on T
  EXPECT_EQ(*step_count(1.0, 1.2e-3), 834);  // 833.33 -> 834
  EXPECT_EQ(*step_count(1.0, 1.0), 1);
  EXPECT_FALSE(step_count(1.0, 1e-300));  // does not fit in 64 bits
  EXPECT_FALSE(step_count(1.0, 0.0));
}

TEST(Names, RoundTrip) {
  for (Method m : {Method::mpm, Method::gimp})
    EXPECT_EQ(parse_method(to_string(m)), m);
  for (Boundary b : {Boundary::dirichlet, Boundary::periodic}) {
    EXPECT_EQ(parse_boundary(to_string(b)), b);
  }
  EXPECT_FALSE(parse_method("GIMP2"));
  EXPECT_FALSE(parse_boundary(""));
}

}  // namespace
}  // namespace mpmstab
