#pragma once
#include <risknav/common/CQuadHeap.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace risknav::common {
/** A grid search's state (A*, Dijkstra), reused from search to search on
 * one thread: a cell's g and parent count only where reached[] holds this
 * search's number, its closed flag likewise, so a new search on the same
 * grid sets up nothing per cell (a speed-up: 360 kB on a 200 x 200 local
 * grid, 20 MB on a 1.7 M cell map). `Open` is the open list's entry,
 * ordered by std::greater (the least first). Shared by the adaptive
 * controller's local planner and the global planner. */
template <typename Open>
struct TGridSearchScratch {
    std::vector<float> g;
    std::vector<int32_t> parent;
    std::vector<uint32_t> reached, closed;
    uint32_t search = 0;
    CQuadHeap<Open, std::greater<>> open;
    /** A new search on a grid of `cells` cells. */
    void begin(size_t cells) {
        if (reached.size() != cells) {
            g.assign(cells, 0.0f);
            parent.assign(cells, -1);
            reached.assign(cells, 0);
            closed.assign(cells, 0);
            search = 0;
        }
        if (++search == 0) {  // wrapped: every mark is stale
            std::fill(reached.begin(), reached.end(), 0);
            std::fill(closed.begin(), closed.end(), 0);
            search = 1;
        }
        open.clear();
    }
    bool isReached(size_t i) const { return reached[i] == search; }
    bool isClosed(size_t i) const { return closed[i] == search; }
};
}  // namespace risknav::common
