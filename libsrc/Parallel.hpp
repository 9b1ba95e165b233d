// Spindrift — the core's parallel loops and reductions. Plugins use these, never an OpenMP
// pragma of their own, so that the parallel back-end (OpenMP today; an MPI reduction across
// ranks tomorrow) is one change here. Every reduction is deterministic: the same result for the
// same input whatever the thread count (a restart must reproduce an uninterrupted run bit for bit).
#pragma once

#include "Types.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace spindrift {

// f(i) for every i in [0, n), in parallel (static schedule: thread t always gets the same block).
// f(i) must write only i's results.
template <class F> void forEachIndex(std::size_t n, F&& f) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) f(i);
}

// Sum over i in [0, n) of f(i), independent of the thread count: partial sums over fixed
// blocks, combined in order. T: double (the default), or a 3-vector (Vec3, Eigen::Vector3d: then
// summed in double precision component by component, and returned as T).
template <class T = double, class F> T deterministicSum(std::size_t n, F&& f) {
    constexpr std::size_t block = 4096;
    const std::size_t blocks = (n + block - 1) / block;
    if constexpr (std::is_same_v<T, double>) {
        std::vector<double> partial(blocks, 0.0);
#pragma omp parallel for schedule(static)
        for (std::size_t b = 0; b < blocks; ++b) {
            double s = 0;
            const std::size_t end = std::min(n, (b + 1) * block);
            for (std::size_t i = b * block; i < end; ++i) s += f(i);
            partial[b] = s;
        }
        double total = 0;
        for (double s : partial) total += s;
        return total;
    } else {
        using Sum = Eigen::Matrix<double, 3, 1>;
        std::vector<Sum> partial(blocks, Sum::Zero());
#pragma omp parallel for schedule(static)
        for (std::size_t b = 0; b < blocks; ++b) {
            Sum s = Sum::Zero();
            const std::size_t end = std::min(n, (b + 1) * block);
            for (std::size_t i = b * block; i < end; ++i) s += f(i).template cast<double>();
            partial[b] = s;
        }
        Sum total = Sum::Zero();
        for (const Sum& s : partial) total += s;
        return total.template cast<typename T::Scalar>();
    }
}

// The sum and the maximum over i of f(i) in one pass (deterministic: the sum over fixed blocks,
// combined in order); {0, 0} for n = 0.
struct SumAndMax {
    double sum = 0, max = 0;
};
template <class F> SumAndMax deterministicSumAndMax(std::size_t n, F&& f) {
    constexpr std::size_t block = 4096;
    const std::size_t blocks = (n + block - 1) / block;
    std::vector<SumAndMax> partial(blocks);
#pragma omp parallel for schedule(static)
    for (std::size_t b = 0; b < blocks; ++b) {
        SumAndMax s;
        for (std::size_t i = b * block, end = std::min(n, (b + 1) * block); i < end; ++i) {
            const double e = f(i);
            s.sum += e;
            s.max = std::max(s.max, e);
        }
        partial[b] = s;
    }
    SumAndMax total;
    for (const SumAndMax& s : partial) {
        total.sum += s.sum;
        total.max = std::max(total.max, s.max);
    }
    return total;
}

// Max over i of f(i) (deterministic by nature); 0 for n = 0.
template <class F> double parallelMax(std::size_t n, F&& f) {
    double m = 0;
#pragma omp parallel for schedule(static) reduction(max : m)
    for (std::size_t i = 0; i < n; ++i) m = std::max(m, double(f(i)));
    return m;
}

// Min over i of f(i); +∞ for n = 0.
template <class F> double parallelMin(std::size_t n, F&& f) {
    double m = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : m)
    for (std::size_t i = 0; i < n; ++i) m = std::min(m, double(f(i)));
    return m;
}

// Whether f(i) holds for any i (every i is evaluated; f without side effects).
template <class F> bool parallelAny(std::size_t n, F&& f) {
    int any = 0;
#pragma omp parallel for schedule(static) reduction(| : any)
    for (std::size_t i = 0; i < n; ++i) any |= int(bool(f(i)));
    return any != 0;
}

} // namespace spindrift
