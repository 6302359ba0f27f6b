#pragma once
#include <cstddef>

namespace risknav::common {
/** Bounds what untrusted deserialization may allocate.
 *
 * While an instance is alive, every `operator new` on this thread adds its
 * size to a running total; once the total would pass `limit`, `operator new`
 * throws std::bad_alloc (the nothrow forms return nullptr) instead of asking
 * the system. Frees are not subtracted: the budget bounds the work as well as
 * the memory. Used around MRPT's `CArchive::ReadObject` on rawlog entries,
 * where lengths and counts come from the file (a 37-byte file can ask MRPT
 * for a 4 G-element deque): MRPT unwinds as from any bad_alloc and the reader
 * reports the entry.
 *
 * Why a replaced global operator new: the allocations happen inside MRPT's
 * serializeFrom of each class, which offers no hook; the replacement (in the
 * same translation unit, so it is linked wherever a budget is used) forwards
 * to malloc / free and costs one thread-local test per allocation. Nested
 * budgets restore the outer one. */
class CAllocationBudget {
  public:
    explicit CAllocationBudget(std::size_t limit);
    ~CAllocationBudget();
    CAllocationBudget(const CAllocationBudget&) = delete;
    CAllocationBudget& operator=(const CAllocationBudget&) = delete;

    /** True once an allocation was refused. */
    bool exceeded() const;
    /** Bytes requested so far (including a refused request). */
    std::size_t requested() const;
    std::size_t limit() const { return m_limit; }

  private:
    std::size_t m_limit;
    // the enclosing budget, restored on destruction
    bool m_prevActive;
    std::size_t m_prevLimit, m_prevUsed;
    bool m_prevExceeded;
};
}  // namespace risknav::common
