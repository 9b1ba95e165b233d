#include "KernelTable.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spindrift {

template <class F> std::vector<KernelTable::Block> KernelTable::tabulate(F&& f, double end, int intervals) const {
    // Cubic Hermite on each interval [r0, r1] from values and one-sided slopes, computed in
    // double precision whatever Scalar is. The kernel takes its argument as Scalar: in single
    // precision the difference step must be far above float's resolution (1e-4 dr would be one
    // ulp of r near h), and the left limit at h is taken just below h as float resolves it.
    constexpr bool single = sizeof(Scalar) < sizeof(double);
    const double dr = end / intervals;
    const double e = dr * (single ? 0.1 : 1e-4);
    std::vector<Block> table(intervals);
    for (int k = 0; k < intervals; ++k) {
        const double r0 = k * dr, r1 = (k + 1) * dr;
        const double below = single ? double(std::nextafter(Scalar(r1), Scalar(0))) : r1 - 1e-12 * dr;
        const double f0 = f(r0), f1 = f(k + 1 == intervals ? below : r1);
        // one-sided second-order differences, staying inside the interval
        const double s0 = (-3.0 * f0 + 4.0 * f(r0 + e) - f(r0 + 2 * e)) / (2 * e) * dr;
        const double s1 = (3.0 * f1 - 4.0 * f(r1 - e) + f(r1 - 2 * e)) / (2 * e) * dr;
        table[k] = {Scalar(f0), Scalar(s0), Scalar(3 * (f1 - f0) - 2 * s0 - s1),
                    Scalar(2 * (f0 - f1) + s0 + s1)};
    }
    return table;
}

void KernelTable::build(const Kernel& kernel, int intervals) {
    if (intervals < 8) throw std::invalid_argument("KernelTable: too few intervals");
    kernel_ = &kernel;
    h_ = kernel.supportRadius();
    dim_ = kernel.dimension();
    intervals_ = intervals;
    invDr_ = Scalar(intervals) / h_;
    w0_ = kernel.W(0);
    const double h = h_;
    w_ = tabulate([&](double r) { return double(kernel.W(Scalar(r))); }, h, intervals);
    dw_ = tabulate([&](double r) { return double(kernel.dWdr(Scalar(r))); }, h, intervals);
    // in s = r², on a quarter of the intervals: the two tables of the pair loops (8 KiB each for
    // the default 1024 in r) stay in L1 beside the particle data, which made the kernel passes
    // 6–10 % faster, and are within 1e-6 of the kernel once r < h/4 (s < h²/16) goes to the
    // tables in r. The kink of the cubic spline at q = 1/2 (s = h²/4) is a node when 16 | intervals.
    const double h2 = h * h;
    sqIntervals_ = std::max(intervals / 4, 16);
    invDs_ = Scalar(sqIntervals_ / h2);
    nearIntervals_ = (sqIntervals_ + 15) / 16;
    wSq_ = tabulate([&](double s) { return double(kernel.W(Scalar(std::sqrt(s)))); }, h2, sqIntervals_);
    const auto gradFactor = [&](double s) {
        const double r = std::sqrt(s);
        return r > 0 ? double(kernel.dWdr(Scalar(r))) / r : 0.0;
    };
    gradSq_ = tabulate(gradFactor, h2, sqIntervals_);
    const double eta2 = 0.01 * h2;
    eta2_ = Scalar(eta2);
    dampedSq_ = tabulate([&](double s) { return gradFactor(s) / (s + eta2); }, h2, sqIntervals_);
    lap_.clear();
}

void KernelTable::enableLaplacian() {
    if (!lap_.empty()) return;
    if (!kernel_) throw std::logic_error("KernelTable::enableLaplacian before build");
    lap_ = tabulate([&](double r) { return double(kernel_->laplacian(Scalar(r))); }, h_, intervals_);
}

} // namespace spindrift
