// Spindrift — smoothing kernel interface (plugins/kernels).
//
// A kernel plugin gives the analytic W(r), dW/dr and ∇²W for a support radius h (W = 0 for
// r >= h) in dimension 2 or 3. Hot loops never call it: the core tabulates it once
// (KernelTable) and pair loops use the table, so swapping kernels costs nothing per pair.
#pragma once

#include "Types.hpp"

#include <string>

namespace spindrift {

class Kernel {
public:
    Kernel(Scalar supportRadius, int dimension) : h_(supportRadius), dim_(dimension) {}
    virtual ~Kernel() = default;

    virtual Scalar W(Scalar r) const = 0;
    virtual Scalar dWdr(Scalar r) const = 0;
    virtual Scalar laplacian(Scalar r) const = 0; // ∇²W = W'' + (d − 1) W'/r

    // False for kernel sets whose gradient shape differs from W (poly6 density with a spiky
    // gradient): tests then do not compare dWdr with the derivative of W.
    virtual bool gradientIsDerivativeOfW() const { return true; }

    Scalar supportRadius() const { return h_; }
    int dimension() const { return dim_; }

protected:
    Scalar h_;
    int dim_;
};

} // namespace spindrift
