#pragma once
// Rows [0, rows) split into one contiguous band per hardware thread, fn(firstRow, endRow)
// run on each band at once; returns when every band is done. A caller that sums keeps one
// result per row and adds them in row order afterwards, so that its result does not depend
// on the thread count.
#include <algorithm>
#include <thread>
#include <vector>

namespace iblab {

// With minRowsPerThread, no more threads than give each that many rows, so that a loop of a
// few milliseconds does not start a thread per core (16 on the GPU machine's host) for rows of
// a few microseconds each.
template <typename Fn>
void parallelRows(int rows, const Fn& fn, int minRowsPerThread = 1)
{
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(std::max(rows / std::max(minRowsPerThread, 1), 1))));
    if (threads <= 1) {
        fn(0, rows);
        return;
    }
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] { fn(rows * t / threads, rows * (t + 1) / threads); });
    for (std::thread& thread : pool)
        thread.join();
}

} // namespace iblab
