#include <gtest/gtest.h>

#include <thread>

#include "uwgrasp/core/timer.hpp"

namespace uwgrasp {

TEST(StageTimer, RecordsStagesInOrderAndSums) {
  StageTimer t;
  t.start("a");
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  t.start("b");
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  t.stop();
  t.stop();  // stopping twice is harmless
  ASSERT_EQ(t.stages().size(), 2u);
  EXPECT_EQ(t.stages()[0].name, "a");
  EXPECT_GE(t.ms("a"), 4.0);
  EXPECT_GE(t.ms("b"), 1.0);
  EXPECT_EQ(t.ms("missing"), 0.0);
  EXPECT_DOUBLE_EQ(t.total_ms(), t.ms("a") + t.ms("b"));
}

TEST(StageTimer, RepeatedStageAddsToItsFirstEntry) {
  StageTimer t;
  t.start("sample");
  t.start("check");
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  t.start("sample");
  t.start("check");
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  t.stop();
  ASSERT_EQ(t.stages().size(), 2u);
  EXPECT_EQ(t.stages()[1].name, "check");
  EXPECT_GE(t.stages()[1].ms, 3.5);
}

}  // namespace uwgrasp
