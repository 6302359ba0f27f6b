#pragma once
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace risknav::common {
/** One persistent worker thread that runs one job at a time: start() hands
 * it a job (waiting for the one before), wait() blocks until that job is
 * done and rethrows the exception it ended with. The thread is created at
 * the first start() and joined by the destructor. A job must not call
 * start() or wait() on its own worker. Not copyable.
 * The job may split work with parallelFor(): a caller blocked in wait()
 * meanwhile runs some of its parts, so the time it would spend waiting does
 * the job's work (on 2 cores, the navigator's thread idle at the end of its
 * step). */
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
    /** From the running job (or a part of it, nested): body(0..n-1), each
     * once, by this thread and by a thread in wait(); returns when all have
     * run, rethrowing the first exception a part ended with (after all have
     * ended). While its parts run on the other thread it helps with any
     * other parts queued (so nested calls cannot deadlock). */
    void parallelFor(size_t n, const std::function<void(size_t)>& body);

  private:
    void loop();
    /** A parallelFor() call's parts (under m_mutex). */
    struct TGroup {
        const std::function<void(size_t)>* body = nullptr;
        size_t n = 0, next = 0, done = 0;
        std::exception_ptr error;
    };
    /** Runs one queued part if there is one (m_mutex held by `lock`, which
     * it unlocks while the part runs); false if none is queued. */
    bool runQueuedPart(std::unique_lock<std::mutex>& lock);
    /** Part `i` of `g` (taken under the lock), run with the lock released. */
    void runPart(std::unique_lock<std::mutex>& lock, TGroup& g, size_t i);
    std::vector<TGroup*> m_groups;  ///< groups with parts not yet taken

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
