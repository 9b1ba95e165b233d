// relaxedPbf — position based fluids with the relaxed density-invariant condition of Duan,
// Ren & Li (2019, seed 002; docs/MODELS.md §pbf): the PBF density constraint with
//   - over-relaxation of the position update, x* += (1 + ω) Δx (§3.1; ω = 0 is plain PBF,
//     the paper uses 0.5 and reports instability above it),
//   - warm start of the multiplier at warmStart × the previous step's λ (§6.2: 0.5),
//   - termination when the AVERAGE density error is at most η, with a maximum count (§3.2),
//   - density clamped to ρ0 from below: only compression is corrected (§3.2),
//   - wall particles in both the density and the position correction (§3.2, eqs. 13–16), with
//     the volumes of the boundary model (akinci's adaptive volume, as the paper, on thin walls).
// The position change is returned as the acceleration Δx/Δt². The solver itself is
// PositionBasedDensitySolver.hpp, shared with pbf.
//
//   pressure { type relaxedPbf; omega 0.5; warmStart 0.5; epsilon 0.1; sCorrK 0;
//              clampDensity yes; gradientCorrection no; }
//   sphSolution: pressure { maxDensityError 0.001; densityErrorNorm average;
//                           minIterations 0; maxIterations 100; }
#include "Plugin.hpp"
#include "PositionBasedDensitySolver.hpp"

namespace {
using namespace spindrift;

PositionBasedOptions relaxedDefaults() {
    PositionBasedOptions o;
    o.relaxed = true;
    o.omega = Scalar(0.5);
    o.warmStart = Scalar(0.5);
    o.clampDensity = true;
    o.sCorrK = 0; // the clamped density already prevents clustering at the free surface
    return o;
}

class RelaxedPbf final : public PositionBasedPressureModel {
public:
    explicit RelaxedPbf(const ModelContext& c) : PositionBasedPressureModel(c, relaxedDefaults(), "relaxedPbf") {}
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, RelaxedPbf)
