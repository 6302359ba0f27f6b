#include <risknav/common/CAllocationBudget.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <new>
#include <string>
#include <vector>

using risknav::common::CAllocationBudget;

TEST(CAllocationBudget, RefusesWhatPassesTheLimitAndCountsEveryRequest) {
    CAllocationBudget b(1 << 20);
    std::vector<char> small(1000);
    EXPECT_FALSE(b.exceeded());
    EXPECT_GE(b.requested(), 1000u);
    // frees are not subtracted: many small vectors add up
    bool refused = false;
    try {
        for (int i = 0; i < 2000; i++)
            std::vector<char> v(1000);
    } catch (const std::bad_alloc&) {
        refused = true;
    }
    EXPECT_TRUE(refused);
    EXPECT_TRUE(b.exceeded());
}

TEST(CAllocationBudget, AHugeRequestThrowsOrReturnsNullWithoutReachingTheSystem) {
    CAllocationBudget b(1 << 20);
    EXPECT_THROW(std::string(std::size_t(3) << 30, 'x'), std::bad_alloc);
    EXPECT_EQ(::operator new(std::size_t(1) << 40, std::nothrow), nullptr);
    EXPECT_THROW((void)::operator new(1, std::align_val_t(64)), std::bad_alloc);  // spent
}

TEST(CAllocationBudget, OutsideABudgetAndAfterItNothingIsRefused) {
    {
        CAllocationBudget b(100);
        EXPECT_THROW(std::vector<char>(200), std::bad_alloc);
    }
    std::vector<char> v(std::size_t(64) << 20);  // 64 MiB, no budget
    EXPECT_EQ(v.size(), std::size_t(64) << 20);
    auto* p = new (std::align_val_t(256)) double[4];
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % 256, 0u);
    ::operator delete[](p, std::align_val_t(256));
}

TEST(CAllocationBudget, NestedBudgetsChargeTheOuterOneWhenTheyEnd) {
    CAllocationBudget outer(10000);
    {
        CAllocationBudget inner(8000);
        std::vector<char> v(6000);
        EXPECT_FALSE(inner.exceeded());
    }
    EXPECT_GE(outer.requested(), 6000u);
    EXPECT_THROW(std::vector<char>(5000), std::bad_alloc);
    EXPECT_TRUE(outer.exceeded());
}
