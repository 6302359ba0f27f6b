#pragma once
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace risknav::common {
/** std::priority_queue<T, std::vector<T>, Compare> as a heap with four
 * children per node (its interface: push, emplace, top, pop, empty, size;
 * plus clear(), which keeps the storage): the top is the entry that
 * compares after no other (with std::greater, the smallest). With a strict
 * total order (no two entries equal) it pops exactly what
 * std::priority_queue pops, entry for entry. Why: the planners' open lists
 * (A*, Dijkstra) pop most of their time; a four-way heap has half the
 * levels of a binary one and its children side by side (a speed-up,
 * the same search). */
template <typename T, typename Compare = std::less<T>>
class CQuadHeap {
  public:
    bool empty() const { return m_v.empty(); }
    size_t size() const { return m_v.size(); }
    const T& top() const { return m_v.front(); }
    void clear() { m_v.clear(); }

    void push(T x) {
        size_t i = m_v.size();
        m_v.push_back(std::move(x));
        T moving = std::move(m_v[i]);
        while (i > 0) {
            const size_t p = (i - 1) / 4;
            if (!m_cmp(m_v[p], moving))
                break;
            m_v[i] = std::move(m_v[p]);
            i = p;
        }
        m_v[i] = std::move(moving);
    }
    template <typename... A>
    void emplace(A&&... a) {
        push(T(std::forward<A>(a)...));
    }

    void pop() {
        T last = std::move(m_v.back());
        m_v.pop_back();
        const size_t n = m_v.size();
        if (n == 0)
            return;
        size_t i = 0;
        for (;;) {
            const size_t c0 = 4 * i + 1;
            if (c0 >= n)
                break;
            size_t best = c0;
            const size_t cEnd = c0 + 4 < n ? c0 + 4 : n;
            for (size_t c = c0 + 1; c < cEnd; c++)
                if (m_cmp(m_v[best], m_v[c]))
                    best = c;
            if (!m_cmp(last, m_v[best]))
                break;
            m_v[i] = std::move(m_v[best]);
            i = best;
        }
        m_v[i] = std::move(last);
    }

  private:
    std::vector<T> m_v;
    Compare m_cmp;
};
}  // namespace risknav::common
