// SIGINT/SIGTERM only record a stop request (the process keeps running).
#include <gtest/gtest.h>

#include <csignal>

#include "sphark/run/signals.hpp"

using namespace sphark;

TEST(StopSignals, RecordTheFirstSignalAndKeepRunning) {
  install_stop_handlers();
  clear_stop_request();
  EXPECT_EQ(stop_requested(), 0);
  std::raise(SIGTERM);
  EXPECT_EQ(stop_requested(), SIGTERM);
  std::raise(SIGINT);  // the first one is kept
  EXPECT_EQ(stop_requested(), SIGTERM);
  clear_stop_request();
  std::raise(SIGINT);
  EXPECT_EQ(stop_requested(), SIGINT);
  clear_stop_request();
}
