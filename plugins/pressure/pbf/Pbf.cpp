// pbf — position based fluids (Macklin & Müller 2013; docs/MODELS.md §pbf): the
// density constraint C_i = ρ_i/ρ0 − 1 solved by Jacobi iterations on the predicted positions,
// λ_i = −C_i/(Σ_k |∇_k C_i|² + ε), Δx_i = (1/ρ0) Σ_j (λ_i + λ_j + s_corr) m ∇W_ij with the
// artificial pressure s_corr = −k (W(r)/W(Δq))ⁿ against clustering. The position change is
// returned as the acceleration Δx/Δt², so symplectic Euler reproduces PBF exactly. Wall
// particles count with the volumes the boundary model gives them. The iterations
// stop when the density error (average by default, as in seed 002's PBF baseline) is at most η,
// or at maxIterations (set maxDensityError 0 for Macklin & Müller's fixed count). The solver
// itself is PositionBasedDensitySolver.hpp, shared with relaxedPbf.
// Deviation: the defaults are SPlisHSPlasH's PBF, not the paper's: the constraint clamped,
// C_i = max(ρ_i/ρ0 − 1, 0), and no s_corr. Unclamped, a free surface's deficit is corrected like
// a compression, a displacement whatever Δt: at a dam break's first step of 4 µs the column's
// edge left at 320 m/s. s_corr is a displacement per iteration too, sized for the paper's 16 ms
// steps: at 0.3 ms it throws surface particles out at 2–3 m/s (the tutorial's dam break, the
// hydrostatic contract column). The paper's form: `clampDensity no; sCorrK 0.1;`.
//
//   pressure { type pbf; epsilon 0.1; sCorrK 0; sCorrN 4; sCorrDeltaQ 0.2;
//              clampDensity yes; }
//   sphSolution: pressure { maxDensityError 0.001; densityErrorNorm average;
//                           minIterations 2; maxIterations 100; }
#include "Plugin.hpp"
#include "PositionBasedDensitySolver.hpp"

namespace {
using namespace spindrift;

PositionBasedOptions pbfDefaults() {
    PositionBasedOptions o;
    o.relaxed = false;
    o.clampDensity = true;
    o.sCorrK = 0;
    return o;
}

class Pbf final : public PositionBasedPressureModel {
public:
    explicit Pbf(const ModelContext& c) : PositionBasedPressureModel(c, pbfDefaults(), "pbf") {}
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Pbf)
