#include <risknav/common/CAllocationBudget.h>

#include <mrpt/core/aligned_allocator.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>

namespace {
struct TBudgetState {
    bool active = false;
    bool exceeded = false;
    std::size_t limit = 0;
    std::size_t used = 0;
};
thread_local TBudgetState tl_budget;

/** false when the request must be refused. */
bool charge(std::size_t size) {
    TBudgetState& b = tl_budget;
    if (!b.active)
        return true;
    b.used = size > b.limit - std::min(b.used, b.limit) ? b.limit + 1 : b.used + size;
    if (b.used <= b.limit)
        return true;
    b.exceeded = true;
    return false;
}

void* allocate(std::size_t size, std::size_t align, bool nothrow) {
    if (!charge(size)) {
        if (nothrow)
            return nullptr;
        throw std::bad_alloc();
    }
    if (size == 0)
        size = 1;
    for (;;) {
        void* p = nullptr;
        if (align <= alignof(std::max_align_t))
            p = std::malloc(size);
        else if (posix_memalign(&p, align, size) != 0)
            p = nullptr;
        if (p)
            return p;
        // the standard contract: call the new handler until it gives up
        const std::new_handler h = std::get_new_handler();
        if (!h) {
            if (nothrow)
                return nullptr;
            throw std::bad_alloc();
        }
        h();
    }
}
}  // namespace

namespace risknav::common {
CAllocationBudget::CAllocationBudget(std::size_t limit)
    : m_limit(limit),
      m_prevActive(tl_budget.active),
      m_prevLimit(tl_budget.limit),
      m_prevUsed(tl_budget.used),
      m_prevExceeded(tl_budget.exceeded) {
    tl_budget = TBudgetState{true, false, limit, 0};
}

CAllocationBudget::~CAllocationBudget() {
    // what this budget spent also counts against the enclosing one
    const std::size_t spent = tl_budget.used;
    tl_budget = TBudgetState{m_prevActive, m_prevExceeded, m_prevLimit, m_prevUsed};
    if (m_prevActive)
        charge(spent);
}

bool CAllocationBudget::exceeded() const {
    return tl_budget.exceeded;
}
std::size_t CAllocationBudget::requested() const {
    return tl_budget.used;
}
}  // namespace risknav::common

// The replaceable global allocation functions (every form, so that new and
// delete always pair malloc with free, also under the sanitizers).
void* operator new(std::size_t n) {
    return allocate(n, 0, false);
}
void* operator new[](std::size_t n) {
    return allocate(n, 0, false);
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    try {
        return allocate(n, 0, true);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
    try {
        return allocate(n, 0, true);
    } catch (...) {
        return nullptr;
    }
}
void* operator new(std::size_t n, std::align_val_t a) {
    return allocate(n, static_cast<std::size_t>(a), false);
}
void* operator new[](std::size_t n, std::align_val_t a) {
    return allocate(n, static_cast<std::size_t>(a), false);
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
    try {
        return allocate(n, static_cast<std::size_t>(a), true);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
    try {
        return allocate(n, static_cast<std::size_t>(a), true);
    } catch (...) {
        return nullptr;
    }
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
    std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
    std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
    std::free(p);
}

// MRPT's own aligned allocator (mrpt::aligned_allocator_cpp11: the range,
// intensity and validity arrays of its scans, its matrices) does not go
// through operator new but through mrpt::aligned_malloc, exported by
// libmrpt-core; this definition in the executable takes its calls from MRPT's
// other libraries (ELF symbol interposition), so those arrays count against
// the budget too. Same contract as MRPT's: memory that mrpt::aligned_free
// (free) releases. It throws std::bad_alloc rather than returning null:
// MRPT's allocator does not check for null.
void* mrpt::aligned_malloc(size_t size, size_t alignment) {
    if (!charge(size))
        throw std::bad_alloc();
    void* p = nullptr;
    if (posix_memalign(&p, std::max(alignment, sizeof(void*)), size ? size : 1) != 0)
        throw std::bad_alloc();
    return p;
}

void* mrpt::aligned_calloc(size_t bytes, size_t alignment) {
    void* p = mrpt::aligned_malloc(bytes, alignment);
    if (p)
        std::memset(p, 0, bytes);
    return p;
}
