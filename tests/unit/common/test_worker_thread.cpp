// CWorkerThread: one persistent thread, one job at a time.
#include <risknav/common/CWorkerThread.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

using risknav::common::CWorkerThread;

TEST(WorkerThread, RunsJobsOneAfterAnotherOffTheCallersThread) {
    CWorkerThread w;
    EXPECT_FALSE(w.pending());
    w.wait();  // nothing started: returns at once
    std::vector<int> order;
    std::thread::id ran;
    for (int k = 0; k < 50; k++) {
        w.start([&, k] {
            order.push_back(k);
            ran = std::this_thread::get_id();
        });
        EXPECT_TRUE(w.pending());
        if (k % 7 == 0)
            w.wait();
    }
    w.wait();
    EXPECT_FALSE(w.pending());
    ASSERT_EQ(order.size(), 50u);
    for (int k = 0; k < 50; k++)
        EXPECT_EQ(order[size_t(k)], k);
    EXPECT_NE(ran, std::this_thread::get_id());
}

TEST(WorkerThread, WaitRethrowsTheJobsErrorOnceAndTheWorkerGoesOn) {
    CWorkerThread w;
    w.start([] { throw std::runtime_error("cycle failed"); });
    EXPECT_THROW(w.wait(), std::runtime_error);
    w.wait();  // once only
    int x = 0;
    w.start([&] { x = 3; });
    w.wait();
    EXPECT_EQ(x, 3);
}

TEST(WorkerThread, TheDestructorLetsARunningJobEnd) {
    std::atomic<bool> done{false};
    {
        CWorkerThread w;
        w.start([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(30));
            done = true;
        });
    }
    EXPECT_TRUE(done);
}
