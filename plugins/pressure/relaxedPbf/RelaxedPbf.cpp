// relaxedPbf — position based fluids with the relaxed density-invariant condition of Duan,
// Ren & Li (2019, seed 002; MODELS.md "pbf and relaxedPbf"): the PBF density constraint with
//   - over-relaxation of the position update, x* += (1 + ω) Δx (§3.1; ω = 0 is plain PBF,
//     the paper uses 0.5 and reports instability above it),
//   - warm start of the multiplier at warmStart × the previous step's λ (§6.2: 0.5),
//   - termination when the AVERAGE density error is at most η, with a maximum count (§3.2),
//   - density clamped to ρ0 from below: only compression is corrected (§3.2),
//   - wall particles with adaptive volume V_b = Ψ_b/ρ0 (Akinci's 1/Σ_k W_bk) in both the
//     density and the position correction (§3.2, eqs. 13–16).
// The position change is returned as the acceleration Δx/Δt². The solver itself is
// PositionBasedDensitySolver.hpp, shared with pbf.
//
//   pressure { type relaxedPbf; omega 0.5; warmStart 0.5; epsilon 0.1; sCorrK 0;
//              clampDensity yes; boundaryVolume adaptive; }
//   sphSolution: pressure { maxDensityError 0.001; densityErrorNorm average;
//                           minIterations 0; maxIterations 100; }
#include "Plugin.hpp"
#include "PositionBasedDensitySolver.hpp"
#include "PressureModel.hpp"

namespace {
using namespace spindrift;

PositionBasedOptions relaxedDefaults() {
    PositionBasedOptions o;
    o.relaxed = true;
    o.omega = Scalar(0.5);
    o.warmStart = Scalar(0.5);
    o.clampDensity = true;
    o.adaptiveBoundaryVolume = true;
    o.sCorrK = 0; // the clamped density already prevents clustering at the free surface
    return o;
}

IterativeSolverControls relaxedControls() {
    IterativeSolverControls c;
    c.maxDensityError = Scalar(0.001);
    c.norm = IterativeSolverControls::Norm::Average;
    c.minIterations = 0;
    c.maxIterations = 100;
    return c;
}

class RelaxedPbf final : public PressureModel {
public:
    explicit RelaxedPbf(const ModelContext& c) : solver_(c, relaxedDefaults(), relaxedControls(), "relaxedPbf") {}
    void initialise(SphSystem& s) override { solver_.initialise(s); }
    void computeDensity(SphSystem& s) override { solver_.computeDensity(s); }
    void addPressureAcceleration(SphSystem& s, Scalar dt) override { solver_.solve(s, dt); }
    Scalar soundSpeed() const override { return 0; }
    bool isIterative() const override { return true; }
    SolverStats lastSolve() const override { return solver_.stats(); }

private:
    PositionBasedDensitySolver solver_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, RelaxedPbf)
