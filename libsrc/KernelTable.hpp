// Spindrift — tabulated kernel for hot loops.
//
// W(r), dW/dr and (on demand) ∇²W are stored as piecewise cubic Hermite polynomials on
// 'intervals' equal intervals of [0, h]: one contiguous block of four coefficients per
// interval, evaluated with Horner's rule. Node values come from the analytic kernel, node
// slopes from one-sided differences inside each interval, so kinks at interval nodes (the
// cubic spline at q = 1/2) are reproduced. Tests hold the table against the analytic kernel.
//
// Pair loops use the tables in the squared distance s = r² (WSq, gradWSq): W(√s) and
// dW/dr(√s)/√s on equal intervals of [0, h²) (a quarter as many as in r, small enough for L1),
// so a pair costs neither a square root nor a division. Below r = h/4, where √s is not smooth
// enough to interpolate and particles are rarely found, they fall back to the tables in r.
#pragma once

#include "Kernel.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace spindrift {

class KernelTable {
public:
    KernelTable() = default;
    explicit KernelTable(const Kernel& kernel, int intervals = 1024) { build(kernel, intervals); }

    void build(const Kernel& kernel, int intervals = 1024);
    // Tabulates ∇²W too (models that need it call this in their initialise()).
    void enableLaplacian();
    bool hasLaplacian() const { return !lap_.empty(); }

    Scalar supportRadius() const { return h_; }
    int dimension() const { return dim_; }

    Scalar W(Scalar r) const { return evaluate(w_, r); }
    Scalar dWdr(Scalar r) const { return evaluate(dw_, r); }
    Scalar laplacian(Scalar r) const { return evaluate(lap_, r); }

    // ∇_i W_ij for r_ij = x_i − x_j with |r_ij| = r (zero at r = 0).
    Vec3 gradW(const Vec3& rij, Scalar r) const {
        return r > Scalar(0) ? Vec3(rij * (dWdr(r) / r)) : Vec3::Zero();
    }
    Vec3 gradW(const Vec3& rij) const { return gradW(rij, rij.norm()); }

    // The same from r² = |r_ij|² (no square root, no division on the hot path).
    Scalar WSq(Scalar r2) const {
        const Scalar s = r2 * invDs_;
        // compared before the conversion: a NaN or huge r² (a diverging run's) is outside, not
        // an index out of range
        if (!(s < Scalar(sqIntervals_)) || r2 < Scalar(0)) [[unlikely]]
            return Scalar(0);
        const int k = static_cast<int>(s);
        if (k < nearIntervals_) [[unlikely]] return W(std::sqrt(r2));
        return horner(wSq_[k], s - Scalar(k));
    }
    // dW/dr / r as a function of r² (0 at r = 0): ∇_i W_ij = r_ij · gradFactorSq(r²).
    Scalar gradFactorSq(Scalar r2) const {
        const Scalar s = r2 * invDs_;
        if (!(s < Scalar(sqIntervals_)) || r2 < Scalar(0)) [[unlikely]]
            return Scalar(0);
        const int k = static_cast<int>(s);
        if (k < nearIntervals_) [[unlikely]] {
            const Scalar r = std::sqrt(r2);
            return r > Scalar(0) ? dWdr(r) / r : Scalar(0);
        }
        return horner(gradSq_[k], s - Scalar(k));
    }
    Vec3 gradWSq(const Vec3& rij, Scalar r2) const { return rij * gradFactorSq(r2); }
    // (dW/dr / r) / (r² + η²), η² = 0.01 h² (Monaghan's η, h the support radius): the factor of
    // the viscous and density-diffusion terms, ∇_i W_ij / (r² + η²) = r_ij · dampedGradFactorSq(r²),
    // tabulated so that a pair costs no division.
    Scalar eta2() const { return eta2_; }
    Scalar dampedGradFactorSq(Scalar r2) const { return valuesSq(r2).dampedGradFactor; }

    // W, dW/dr / r and the damped factor from one lookup of r²'s interval (a pair loop takes
    // the ones its term asks for; the others are never computed once inlined, so always inlined).
    struct Values {
        Scalar W, gradFactor, dampedGradFactor;
    };
    [[gnu::always_inline]] Values valuesSq(Scalar r2) const {
        const Scalar s = r2 * invDs_;
        // both rare in a pair loop (its lists hold the pairs within h; few are closer than h/4):
        // the hints keep the table path a straight run of instructions; outside is tested before
        // the conversion, so that a NaN or huge r² (a diverging run's) reads zero, not out of range
        if (!(s < Scalar(sqIntervals_)) || r2 < Scalar(0)) [[unlikely]]
            return {0, 0, 0};
        const int k = static_cast<int>(s);
        if (k < nearIntervals_) [[unlikely]] {
            const Scalar r = std::sqrt(r2);
            const Scalar F = r > Scalar(0) ? dWdr(r) / r : Scalar(0);
            return {W(r), F, F / (r2 + eta2_)};
        }
        const Scalar t = s - Scalar(k);
        return {horner(wSq_[k], t), horner(gradSq_[k], t), horner(dampedSq_[k], t)};
    }

    Scalar W0() const { return w0_; } // W(0), the self contribution

private:
    using Block = std::array<Scalar, 4>; // f(t) = c0 + t (c1 + t (c2 + t c3)), t in [0, 1)

    Scalar evaluate(const std::vector<Block>& table, Scalar r) const {
        const Scalar s = r * invDr_;
        if (!(s < Scalar(intervals_)) || r < Scalar(0)) return Scalar(0); // NaN too
        const int k = static_cast<int>(s);
        return horner(table[k], s - Scalar(k));
    }
    static Scalar horner(const Block& c, Scalar t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }
    // f on 'intervals' equal intervals of [0, end)
    template <class F> std::vector<Block> tabulate(F&& f, double end, int intervals) const;

    const Kernel* kernel_ = nullptr; // for enableLaplacian(); owned by the caller
    Scalar h_ = 0, invDr_ = 0, invDs_ = 0, w0_ = 0, eta2_ = 0;
    int dim_ = 3, intervals_ = 0, sqIntervals_ = 0, nearIntervals_ = 0; // r² intervals below (h/4)²
    std::vector<Block> w_, dw_, lap_, wSq_, gradSq_, dampedSq_;
};

} // namespace spindrift
