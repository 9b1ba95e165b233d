// poly6Spiky — the kernel set of Müller, Charypar & Gross (2003) (docs/MODELS.md §poly6Spiky), on the
// support radius h, 2D and 3D, each use with its own shape (MullerKernels.hpp):
//   W (density, interpolation)  poly6      σ (h² − r²)³
//   dW/dr (pressure gradient)   spiky      −3σ (h − r)²   (non-zero at r = 0: keeps close
//                                                         particles apart instead of clustering)
//   ∇²W (viscosity)             viscosity  45/(π h⁶)(h − r) in 3D, 40/(π h⁵)(h − r) in 2D (≥ 0)
// Because dW/dr is not the derivative of W, gradientIsDerivativeOfW() is false.
//
//   kernel { type poly6Spiky; }
#include "Kernel.hpp"
#include "MullerKernels.hpp"
#include "Plugin.hpp"

namespace {
using spindrift::Scalar;

class Poly6Spiky final : public spindrift::Kernel {
public:
    explicit Poly6Spiky(const spindrift::ModelContext& c)
        : Kernel(c.constants.supportRadius, c.physics.dimension), poly6_(h_, dim_), spiky_(h_, dim_),
          viscosity_(h_, dim_) {}

    Scalar W(Scalar r) const override { return Scalar(poly6_.W(r)); }
    Scalar dWdr(Scalar r) const override { return Scalar(spiky_.dWdr(r)); }
    Scalar laplacian(Scalar r) const override { return Scalar(viscosity_.laplacian(r)); }
    bool gradientIsDerivativeOfW() const override { return false; }

private:
    spindrift::muller::Poly6 poly6_;
    spindrift::muller::Spiky spiky_;
    spindrift::muller::Viscosity viscosity_;
};
} // namespace

SPINDRIFT_PLUGIN(Kernel, Poly6Spiky)
