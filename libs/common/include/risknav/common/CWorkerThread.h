#pragma once
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace risknav::common {
/** One persistent worker thread that runs one job at a time: start() hands
 * it a job (waiting for the one before), wait() blocks until that job is
 * done and rethrows the exception it ended with. The thread is created at
 * the first start() and joined by the destructor. A job must not call
 * start() or wait() on its own worker. Not copyable. */
class CWorkerThread {
  public:
    CWorkerThread() = default;
    CWorkerThread(const CWorkerThread&) = delete;
    CWorkerThread& operator=(const CWorkerThread&) = delete;
    ~CWorkerThread();

    /** Runs `job` on the worker (after the job before it has ended; that
     * job's exception, if any, is dropped: wait() for it first). */
    void start(std::function<void()> job);
    /** Until the last started job has ended; rethrows its exception (once).
     * Returns at once when no job is pending. */
    void wait();
    /** A started job has not been waited for. */
    bool pending() const { return m_pending; }

  private:
    void loop();

    std::thread m_thread;
    std::mutex m_mutex;
    std::condition_variable m_cv;
    std::function<void()> m_job;  ///< set: to run; empty: none
    std::exception_ptr m_error;
    bool m_running = false;  ///< the worker holds a job
    bool m_stop = false;
    bool m_pending = false;  ///< started and not waited for (caller's side)
};
}  // namespace risknav::common
