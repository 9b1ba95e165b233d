// Spindrift — template part of NeighbourSearch.hpp.
#pragma once

#include <algorithm>
#include <numeric>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spindrift {

template <class Query> void buildNeighbourList(std::size_t n, NeighbourList& list, Query&& query) {
    list.offsets.assign(n + 1, 0);
    int threads = 1;
#ifdef _OPENMP
    threads = omp_get_max_threads();
#endif
    // Each thread fills its own buffer for a contiguous block of points; buffers are then
    // concatenated in block order, so the result is independent of the thread count.
    std::vector<std::vector<Index>> buffers(threads);
#pragma omp parallel num_threads(threads)
    {
        int t = 0;
#ifdef _OPENMP
        t = omp_get_thread_num();
#endif
        const std::size_t begin = n * t / threads, end = n * (t + 1) / threads;
        std::vector<Index>& buffer = buffers[t];
        buffer.clear();
        buffer.reserve((end - begin) * 32);
        for (std::size_t i = begin; i < end; ++i) {
            const std::size_t before = buffer.size();
            query(i, [&](Index j) { buffer.push_back(j); });
            list.offsets[i + 1] = std::uint32_t(buffer.size() - before);
        }
    }
    for (std::size_t i = 0; i < n; ++i) list.offsets[i + 1] += list.offsets[i];
    list.indices.resize(list.offsets[n]);
#pragma omp parallel for schedule(static, 1) num_threads(threads)
    for (int t = 0; t < threads; ++t) {
        const std::size_t begin = n * t / threads;
        std::copy(buffers[t].begin(), buffers[t].end(), list.indices.begin() + list.offsets[begin]);
    }
}

} // namespace spindrift
