#pragma once
// Scenes built in code for the verification tests (benchmarks.md §A).
#include <string>

#include <gtest/gtest.h>

#include "ddaslope/io/run_case.hpp"
#include "ddaslope/model/incline_scene.hpp"

namespace ddaslope::scenes {

using InclineSpec = model::InclineSpec;
inline model::Scene makeIncline(const InclineSpec& s) { return model::makeInclineScene(s); }
inline double slidingAcceleration(const InclineSpec& s) { return model::slidingAcceleration(s); }

/// Runs a scene without output files; the test fails if the run does not complete.
inline io::Trace runTrace(const model::Scene& s) {
  const io::RunOutcome o = io::runScene(s, {});
  EXPECT_TRUE(o.completed) << o.failure;
  return o.trace;
}

/// A monitor quantity at a time (interpolated) or, without a time, its maximum over the run.
inline double measureAt(const io::Trace& t, const std::string& monitor, const std::string& quantity,
                        std::optional<double> time) {
  model::Expectation e;
  e.monitor = monitor;
  e.quantity = quantity;
  e.time = time;
  return io::measure(t, e);
}

}  // namespace ddaslope::scenes
