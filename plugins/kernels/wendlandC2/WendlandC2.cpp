// wendlandC2 — Wendland (1995) C² kernel on the support radius h (q = r/h):
// W = σ(1 − q)⁴(1 + 4q); σ = 7/(πh²) in 2D, 21/(2πh³) in 3D. (docs/MODELS.md §wendlandC2)
#include "Kernel.hpp"
#include "Plugin.hpp"

#include <cmath>
#include <numbers>

namespace {
using spindrift::Scalar;

class WendlandC2 final : public spindrift::Kernel {
public:
    explicit WendlandC2(const spindrift::ModelContext& c)
        : Kernel(c.constants.supportRadius, c.physics.dimension),
          sigma_(dim_ == 2 ? 7.0 / (std::numbers::pi * h_ * h_) : 21.0 / (2.0 * std::numbers::pi * h_ * h_ * h_)) {}

    Scalar W(Scalar r) const override {
        const Scalar q = r / h_;
        if (q >= 1) return 0;
        const Scalar t = 1 - q;
        return sigma_ * t * t * t * t * (1 + 4 * q);
    }
    // dW/dr = −20 σ q (1 − q)³ / h
    Scalar dWdr(Scalar r) const override {
        const Scalar q = r / h_;
        if (q >= 1) return 0;
        const Scalar t = 1 - q;
        return -20 * sigma_ / h_ * q * t * t * t;
    }
    // W'' = 20 σ/h² (1 − q)² (4q − 1),  W'/r = −20 σ/h² (1 − q)³
    Scalar laplacian(Scalar r) const override {
        const Scalar q = r / h_;
        if (q >= 1) return 0;
        const Scalar t = 1 - q, s = 20 * sigma_ / (h_ * h_);
        return s * t * t * (4 * q - 1) - (dim_ - 1) * s * t * t * t;
    }

private:
    Scalar sigma_;
};
} // namespace

SPINDRIFT_PLUGIN(Kernel, WendlandC2)
