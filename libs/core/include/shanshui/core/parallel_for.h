// A minimal parallel loop for work items that do not depend on each other.
#pragma once

#include <functional>

namespace shanshui {

//! Number of worker threads to use for a request: `requested` if positive, otherwise one per
//! hardware thread (at least 1).
int resolveThreads(int requested);

//! Calls fn(i) for every i in [0, count) on up to `threads` threads (the caller's thread is
//! one of them) and returns when all are done. Items are handed out in order, one at a time;
//! the first exception thrown by fn is rethrown here after all threads stop.
void parallelFor(int count, int threads, const std::function<void(int)>& fn);

}  // namespace shanshui
