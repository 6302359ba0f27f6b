// CQuadHeap: the planners' open list; the same pops as std::priority_queue.
#include <risknav/common/CQuadHeap.h>

#include <gtest/gtest.h>

#include <queue>
#include <random>
#include <utility>
#include <vector>

using risknav::common::CQuadHeap;

TEST(QuadHeap, PopsWhatStdPriorityQueuePopsEntryForEntry) {
    // (key, id) pairs as the planners push them: keys with many ties (a
    // grid's path lengths) and ids that tell the tied ones apart, pushes and
    // pops interleaved; against std::priority_queue with std::greater (a
    // min-heap). A heap that picked the wrong child, or took a tie by its
    // key alone, pops a different sequence.
    std::mt19937 rng(5);
    using TEntry = std::pair<double, int>;
    for (int round = 0; round < 40; round++) {
        std::priority_queue<TEntry, std::vector<TEntry>, std::greater<>> ref;
        CQuadHeap<TEntry, std::greater<>> heap;
        std::uniform_int_distribution<int> key(0, round % 2 ? 20 : 100000);
        std::uniform_int_distribution<int> op(0, 9);
        int id = 0;
        std::vector<TEntry> popped, expected;
        for (int step = 0; step < 3000; step++) {
            if (op(rng) < 6 || ref.empty()) {
                const TEntry e{0.5 * key(rng), id++};
                ref.push(e);
                heap.push(e);
            } else {
                ASSERT_EQ(heap.top(), ref.top()) << round << " " << step;
                expected.push_back(ref.top());
                popped.push_back(heap.top());
                ref.pop();
                heap.pop();
            }
            ASSERT_EQ(heap.size(), ref.size());
        }
        while (!ref.empty()) {
            ASSERT_EQ(heap.top(), ref.top());
            ref.pop();
            heap.pop();
        }
        EXPECT_TRUE(heap.empty());
        EXPECT_EQ(popped, expected);
    }
    CQuadHeap<int, std::greater<int>> h;
    h.emplace(3);
    h.clear();
    EXPECT_TRUE(h.empty());
}
