#include "acquire/progress_json.h"

#include <gtest/gtest.h>

namespace brdfrig::acquire {
namespace {

TEST(ProgressJsonTest, WhatTheDaemonEncodesTheClientDecodes) {
  RunProgress p;
  p.state = RunState::kPaused;
  p.position = 2;
  p.positions = 6;
  p.frame = 1;
  p.frames_per_position = 3;
  p.frames_recorded = 7;
  p.frames_total = 18;
  p.eta_s = 12.5;
  p.last_saturation = 0.003;
  p.message = "paused by the operator";
  const RunProgress q = ProgressFromJson(nlohmann::json::parse(ProgressToJson(p).dump()));
  EXPECT_EQ(q.state, p.state);
  EXPECT_EQ(q.position, p.position);
  EXPECT_EQ(q.positions, p.positions);
  EXPECT_EQ(q.frame, p.frame);
  EXPECT_EQ(q.frames_per_position, p.frames_per_position);
  EXPECT_EQ(q.frames_recorded, p.frames_recorded);
  EXPECT_EQ(q.frames_total, p.frames_total);
  EXPECT_DOUBLE_EQ(q.eta_s, p.eta_s);
  EXPECT_DOUBLE_EQ(q.last_saturation, p.last_saturation);
  EXPECT_EQ(q.message, p.message);
}

TEST(ProgressJsonTest, MissingFieldsAndUnknownStatesReadAsDefaults) {
  const RunProgress q = ProgressFromJson(nlohmann::json{{"state", "dancing"}});
  EXPECT_EQ(q.state, RunState::kIdle);
  EXPECT_EQ(q.frames_total, 0);
  EXPECT_TRUE(q.message.empty());
}

}  // namespace
}  // namespace brdfrig::acquire
