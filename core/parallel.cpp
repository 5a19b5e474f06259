#include "core/parallel.h"

#include <memory>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__unix__)
#include <pthread.h>
#endif

namespace rtc {

unsigned hardware_threads() {
    // hardware_concurrency() may report 0 when it cannot tell.
    return std::max(1u, std::thread::hardware_concurrency());
}

namespace detail {
namespace {

using Body = void (*)(const void*, unsigned) noexcept;

// Set on a thread while it runs a body: a parallel_for inside it must not
// wait for the pool it is part of.
thread_local bool t_in_body = false;

void run_on_fresh_threads(unsigned threads, Body body, const void* context) {
    std::vector<std::thread> started;
    started.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) {
        try {
            started.emplace_back([=] {
                t_in_body = true;
                body(context, t);
            });
        } catch (const std::system_error&) {
            break;  // out of threads: the ones started (and this one) do all the work
        }
    }
    const bool was = std::exchange(t_in_body, true);
    body(context, 0);
    t_in_body = was;
    for (std::thread& t : started) t.join();
}

void pause() {
#if defined(__SSE2__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

// Spins before sleeping on a futex: a build's calls come tens of
// microseconds apart, and waking a sleeping thread costs about that much.
// 2,000 pauses are 10-50 us, depending on the processor.
constexpr int kSpins = 2000;

template <class Atomic, class Value>
void wait_while_equal(const Atomic& a, Value v) {
    for (int spin = 0; a.load(std::memory_order_acquire) == v; ++spin) {
        if (spin < kSpins) pause();
        else a.wait(v, std::memory_order_acquire);
    }
}

// The pool: worker i (thread id i + 1) waits on its own flag, so a call on
// fewer threads wakes only the workers it uses, and a late worker cannot
// take part in a call it was not given. The body and context are written
// before the flags are raised (release) and read after (acquire); the next
// call writes them only after every worker of this one has lowered its flag.
class Pool {
public:
    // Returns false (the caller runs fresh threads) when the pool is busy.
    bool run(unsigned threads, Body body, const void* context) {
        const std::unique_lock lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock()) return false;
        const unsigned helpers = grow(threads - 1);
        body_ = body;
        context_ = context;
        pending_.store(helpers, std::memory_order_relaxed);
        for (unsigned i = 0; i < helpers; ++i) {
            workers_[i]->go.store(1, std::memory_order_release);
            workers_[i]->go.notify_one();
        }
        t_in_body = true;
        body(context, 0);
        t_in_body = false;
        for (unsigned p; (p = pending_.load(std::memory_order_acquire)) != 0;) wait_while_equal(pending_, p);
        return true;
    }

private:
    struct alignas(64) Worker {
        std::atomic<unsigned> go{0};
        std::thread thread;
    };

    // Starts workers up to `helpers`; returns how many there are (fewer when
    // the system has no more threads).
    unsigned grow(unsigned helpers) {
        while (workers_.size() < helpers) {
            auto w = std::make_unique<Worker>();
            const auto id = static_cast<unsigned>(workers_.size()) + 1;
            try {
                w->thread = std::thread([this, self = w.get(), id] { loop(*self, id); });
            } catch (const std::system_error&) {
                break;
            }
            workers_.push_back(std::move(w));
        }
        return std::min(helpers, static_cast<unsigned>(workers_.size()));
    }

    void loop(Worker& self, unsigned id) {
        t_in_body = true;
        for (;;) {
            wait_while_equal(self.go, 0u);
            body_(context_, id);
            self.go.store(0, std::memory_order_relaxed);
            if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
        }
    }

    std::mutex mutex_;  // one call at a time
    std::vector<std::unique_ptr<Worker>> workers_;
    Body body_ = nullptr;
    const void* context_ = nullptr;
    std::atomic<unsigned> pending_{0};  // workers of this call not done yet
};

// Never destroyed: its workers wait for good, and the process's exit ends
// them (a destructor would join threads at static destruction, where a
// late parallel_for could still come). A forked child has none of the
// parent's threads: it starts a pool of its own.
std::atomic<Pool*> g_pool{nullptr};
Pool* g_parent_pool = nullptr;  // a forked child's copy of its parent's, kept reachable
std::once_flag g_at_fork;

Pool& pool() {
    std::call_once(g_at_fork, [] {
#if defined(__unix__)
        pthread_atfork(nullptr, nullptr, [] { g_parent_pool = g_pool.exchange(nullptr); });
#endif
    });
    Pool* p = g_pool.load(std::memory_order_acquire);
    if (p) return *p;
    static std::mutex creating;
    const std::lock_guard lock(creating);
    p = g_pool.load(std::memory_order_acquire);
    if (!p) {
        p = new Pool;  // NOLINT(cppcoreguidelines-owning-memory): see g_pool
        g_pool.store(p, std::memory_order_release);
    }
    return *p;
}

}  // namespace

void run_on_threads(unsigned threads, Body body, const void* context) {
    if (threads <= 1) {
        body(context, 0);
        return;
    }
    if (t_in_body || !pool().run(threads, body, context)) run_on_fresh_threads(threads, body, context);
}

}  // namespace detail
}  // namespace rtc
