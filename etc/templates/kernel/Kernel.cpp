// Template kernel plugin: the Wendland C2 kernel on the support radius h (q = r/h),
// W = σ(1 − q)⁴(1 + 4q), σ = 7/(πh²) in 2D, 21/(2πh³) in 3D. Replace the three functions.
//   sphSchemes:  kernel { type <this folder's name>; }
#include "Kernel.hpp"
#include "Plugin.hpp"

#include <numbers>

namespace {
using namespace spindrift;

class TemplateKernel final : public Kernel {
public:
    explicit TemplateKernel(const ModelContext& c)
        : Kernel(c.constants.supportRadius, c.physics.dimension),
          sigma_(dim_ == 2 ? 7 / (std::numbers::pi * h_ * h_) : 21 / (2 * std::numbers::pi * h_ * h_ * h_)) {}

    Scalar W(Scalar r) const override {
        const Scalar q = r / h_, t = 1 - q;
        return q < 1 ? sigma_ * t * t * t * t * (1 + 4 * q) : 0;
    }
    Scalar dWdr(Scalar r) const override {
        const Scalar q = r / h_, t = 1 - q;
        return q < 1 ? -20 * sigma_ / h_ * q * t * t * t : 0;
    }
    Scalar laplacian(Scalar r) const override { // W'' + (d − 1) W'/r
        const Scalar q = r / h_, t = 1 - q, s = 20 * sigma_ / (h_ * h_);
        return q < 1 ? s * t * t * (4 * q - 1) - (dim_ - 1) * s * t * t * t : 0;
    }

private:
    Scalar sigma_;
};
} // namespace

SPINDRIFT_PLUGIN(Kernel, TemplateKernel)
