#include "simlab/common/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace simlab::engine {

void forEachInParallel(std::size_t count, int threads, const std::function<void(std::size_t)>& work) {
    std::atomic<std::size_t> next{0};
    std::mutex lock;
    std::exception_ptr failure;
    auto worker = [&] {
        try {
            for (std::size_t i = next++; i < count; i = next++) work(i);
        } catch (...) {
            std::lock_guard<std::mutex> guard(lock);
            if (!failure) failure = std::current_exception();
        }
    };
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), count);
    std::vector<std::thread> others;
    for (std::size_t k = 1; k < n; ++k) others.emplace_back(worker);
    worker();
    for (std::thread& t : others) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace simlab::engine
