// Work shared out over threads: the engine's one pool.
#pragma once

#include <cstddef>
#include <functional>

namespace simlab::engine {

/// Calls work(0), ..., work(count - 1) on up to `threads` threads at once (at least one, never more than `count`;
/// the calling thread is one of them), each thread taking the next index when it is free, and waits for them all.
/// A thread whose call throws takes no more; the first exception is thrown here, once every thread has ended.
void forEachInParallel(std::size_t count, int threads, const std::function<void(std::size_t)>& work);

}  // namespace simlab::engine
