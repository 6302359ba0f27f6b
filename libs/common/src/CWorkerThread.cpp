#include <risknav/common/CWorkerThread.h>

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
    m_cv.wait(lock, [&] { return !m_job && !m_running; });
    m_pending = false;
    if (auto e = std::exchange(m_error, nullptr))
        std::rethrow_exception(e);
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
