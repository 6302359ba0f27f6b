// CWorkerThread: one persistent thread, one job at a time.
#include <risknav/common/CWorkerThread.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
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

TEST(WorkerThread, ParallelForRunsEachPartOnceAndTheWaitingCallerTakesSome) {
    // The job splits 200 parts (nested: each of 20 parts splits 10); the
    // caller, blocked in wait() from the start, must run some of them, and
    // every part must run exactly once. Parts are slow enough (50 us) that a
    // caller which never helps runs none.
    CWorkerThread w;
    std::vector<std::atomic<int>> runs(200);
    std::atomic<int> byCaller{0};
    const auto caller = std::this_thread::get_id();
    std::atomic<bool> started{false};
    w.start([&] {
        started = true;
        w.parallelFor(20, [&](size_t outer) {
            w.parallelFor(10, [&](size_t inner) {
                runs[outer * 10 + inner]++;
                if (std::this_thread::get_id() == caller)
                    byCaller++;
                std::this_thread::sleep_for(std::chrono::microseconds(50));
            });
        });
    });
    while (!started)
        std::this_thread::yield();
    w.wait();
    for (size_t k = 0; k < runs.size(); k++)
        ASSERT_EQ(runs[k].load(), 1) << k;
    EXPECT_GT(byCaller.load(), 0);
    EXPECT_LT(byCaller.load(), 200);
}

TEST(WorkerThread, ParallelForRethrowsAPartsErrorAfterAllPartsEnded) {
    CWorkerThread w;
    std::atomic<int> ended{0};
    bool caught = false;
    w.start([&] {
        try {
            w.parallelFor(8, [&](size_t k) {
                std::this_thread::sleep_for(std::chrono::microseconds(100));
                ended++;
                if (k == 3)
                    throw std::runtime_error("part 3");
            });
        } catch (const std::runtime_error& e) {
            caught = std::string(e.what()) == "part 3" && ended == 8;
        }
    });
    w.wait();
    EXPECT_TRUE(caught);
    // without a waiting caller (never waited for until done): the job runs
    // every part itself
    std::atomic<int> parts{0};
    w.start([&] { w.parallelFor(5, [&](size_t) { parts++; }); });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    w.wait();
    EXPECT_EQ(parts.load(), 5);
}
