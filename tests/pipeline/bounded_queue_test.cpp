// The queue between pipeline threads: blocking push keeps every item in
// order (offline determinism), tryPush refuses when full (real-time drops),
// close ends the stream after the queued items and releases a producer
// waiting on a full queue or on the clock.
#include "edgevio/pipeline/bounded_queue.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

namespace edgevio::pipeline {
namespace {

TEST(BoundedQueue, BlockingPushKeepsEveryItemInOrder) {
  BoundedQueue<int> q(2);
  std::thread producer([&] {
    for (int i = 0; i < 1000; ++i) q.push(i);
    q.close();
  });
  std::vector<int> got;
  while (auto v = q.pop()) got.push_back(*v);
  producer.join();
  ASSERT_EQ(got.size(), 1000u);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(got[static_cast<std::size_t>(i)], i);
}

TEST(BoundedQueue, TryPushRefusesWhenFullAndCloseEndsTheStream) {
  BoundedQueue<int> q(2);
  EXPECT_TRUE(q.tryPush(1));
  EXPECT_TRUE(q.tryPush(2));
  EXPECT_FALSE(q.tryPush(3));  // full: a real-time producer drops this one
  q.close();
  EXPECT_FALSE(q.tryPush(4));
  EXPECT_EQ(q.pop(), 1);
  EXPECT_EQ(q.pop(), 2);
  EXPECT_FALSE(q.pop().has_value());
}

TEST(BoundedQueue, CloseReleasesAProducerWaitingOnAFullQueueOrOnTheClock) {
  BoundedQueue<int> q(1);
  ASSERT_TRUE(q.push(1));
  bool pushed = true;
  std::thread producer([&] { pushed = q.push(2); });  // blocks: the queue is full
  const auto now = std::chrono::steady_clock::now();
  EXPECT_FALSE(q.closedBy(now));  // a deadline passed: at once, not closed
  q.close();
  producer.join();
  EXPECT_FALSE(pushed);
  EXPECT_TRUE(q.closedBy(now + std::chrono::hours(1)));  // closed: at once, not in an hour
  EXPECT_EQ(q.pop(), 1);
  EXPECT_FALSE(q.pop().has_value());
}

}  // namespace
}  // namespace edgevio::pipeline
