#include <risknav/common/CWorkerThread.h>

#include <algorithm>
#include <utility>

namespace risknav::common {
CWorkerThread::~CWorkerThread() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_cv.notify_all();
    if (m_thread.joinable())
        m_thread.join();
}

void CWorkerThread::start(std::function<void()> job) {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_cv.wait(lock, [&] { return !m_job && !m_running; });
    // the thread first: if it cannot be made, nothing is pending
    if (!m_thread.joinable())
        m_thread = std::thread([this] { loop(); });
    m_error = nullptr;
    m_job = std::move(job);
    m_pending = true;
    lock.unlock();
    m_cv.notify_all();
}

void CWorkerThread::wait() {
    if (!m_pending)
        return;
    std::unique_lock<std::mutex> lock(m_mutex);
    // the job's queued parts are run here while it runs
    while (m_job || m_running)
        if (!runQueuedPart(lock))
            m_cv.wait(lock);
    m_pending = false;
    if (auto e = std::exchange(m_error, nullptr))
        std::rethrow_exception(e);
}

void CWorkerThread::runPart(std::unique_lock<std::mutex>& lock, TGroup& g, size_t i) {
    if (g.next == g.n)
        m_groups.erase(std::find(m_groups.begin(), m_groups.end(), &g));
    lock.unlock();
    std::exception_ptr error;
    try {
        (*g.body)(i);
    } catch (...) {
        error = std::current_exception();
    }
    lock.lock();
    if (error && !g.error)
        g.error = error;
    g.done++;
    m_cv.notify_all();
}

bool CWorkerThread::runQueuedPart(std::unique_lock<std::mutex>& lock) {
    if (m_groups.empty())
        return false;
    TGroup& g = *m_groups.front();
    runPart(lock, g, g.next++);
    return true;
}

void CWorkerThread::parallelFor(size_t n, const std::function<void(size_t)>& body) {
    if (n == 0)
        return;
    TGroup g;
    g.body = &body;
    g.n = n;
    std::unique_lock<std::mutex> lock(m_mutex);
    m_groups.push_back(&g);
    m_cv.notify_all();
    while (g.done < g.n) {
        if (g.next < g.n)
            runPart(lock, g, g.next++);  // its own parts first
        else if (!runQueuedPart(lock))
            m_cv.wait(lock);  // its last parts run on the other thread
    }
    if (g.error)
        std::rethrow_exception(g.error);
}

void CWorkerThread::loop() {
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_cv.wait(lock, [&] { return m_stop || bool(m_job); });
        if (!m_job)
            return;  // stopped with nothing left to run
        auto job = std::move(m_job);
        m_job = nullptr;
        m_running = true;
        lock.unlock();
        std::exception_ptr error;
        try {
            job();
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        m_error = error;
        m_running = false;
        m_cv.notify_all();
    }
}
}  // namespace risknav::common
