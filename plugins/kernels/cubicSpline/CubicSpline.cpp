// cubicSpline — the M4 cubic B-spline (Monaghan & Lattanzio 1985), written on the support
// radius h (q = r/h): W = σ(6q³ − 6q² + 1) for q ≤ ½, 2σ(1 − q)³ for ½ < q ≤ 1;
// σ = 40/(7πh²) in 2D, 8/(πh³) in 3D. (docs/MODELS.md §cubicSpline)
#include "Kernel.hpp"
#include "Plugin.hpp"

#include <cmath>
#include <numbers>

namespace {
using spindrift::Scalar;

class CubicSpline final : public spindrift::Kernel {
public:
    explicit CubicSpline(const spindrift::ModelContext& c)
        : Kernel(c.constants.supportRadius, c.physics.dimension),
          sigma_(dim_ == 2 ? 40.0 / (7.0 * std::numbers::pi * h_ * h_) : 8.0 / (std::numbers::pi * h_ * h_ * h_)) {}

    Scalar W(Scalar r) const override {
        const Scalar q = r / h_;
        if (q <= 0.5) return sigma_ * (6 * q * q * q - 6 * q * q + 1);
        if (q < 1) return 2 * sigma_ * (1 - q) * (1 - q) * (1 - q);
        return 0;
    }
    Scalar dWdr(Scalar r) const override {
        const Scalar q = r / h_;
        if (q <= 0.5) return sigma_ / h_ * (18 * q * q - 12 * q);
        if (q < 1) return -6 * sigma_ / h_ * (1 - q) * (1 - q);
        return 0;
    }
    Scalar laplacian(Scalar r) const override {
        const Scalar q = r / h_;
        if (q >= 1) return 0;
        const Scalar d2 = q <= 0.5 ? sigma_ / (h_ * h_) * (36 * q - 12) : 12 * sigma_ / (h_ * h_) * (1 - q);
        const Scalar dOverR = q <= 0.5 ? sigma_ / (h_ * h_) * (18 * q - 12) : (q > 0 ? dWdr(r) / r : 0);
        return d2 + (dim_ - 1) * dOverR;
    }

private:
    Scalar sigma_;
};
} // namespace

SPINDRIFT_PLUGIN(Kernel, CubicSpline)
