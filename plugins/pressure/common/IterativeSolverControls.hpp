// Tolerances of the iterative (incompressible) pressure solvers pcisph, pbf and relaxedPbf,
// read from system/sphSolution (docs/MODELS.md §sphSolution):
//
//   pressure
//   {
//       maxDensityError   0.01;      // η: stop when the density error is at most this
//       densityErrorNorm  maximum;   // maximum | average: which error is held below η
//       peakDensityError  0.01;      // and the largest error of any particle at most this
//       minIterations     3;
//       maxIterations     100;       // stop here even if not converged (the log says so)
//       maxDisplacement   0.4;       // the furthest a particle moves in a step, in particle spacings
//   }
//
// The density error of a particle is the compression max(0, ρ* − ρ0)/ρ0 of its predicted
// density (the deficit at a free surface is not an error of the pressure solver); 'maximum'
// and 'average' are taken over all fluid particles. With the average, the peak is held as well
// (peakDensityError, 1 % by default): an average alone let a few particles go uncorrected while
// it was met in two iterations (the Colagrossi dam break at H/80: dfsph's largest error 5.6 %,
// iisph's 3.9 %, relaxedPbf's 3.1 %, at 2.0-3.3 iterations a step on average; issue 35). A
// missing sphSolution or keyword falls back to the solver's defaults, echoed once in the log.
// Unknown keywords are errors.
// maxDisplacement is the solvers' own time-step limit, Δt ≤ maxDisplacement Δx / |v|max (the CFL
// condition of Ihmsen et al. 2014, IISPH, λ = 0.4 of a particle's diameter; SPlisHSPlasH's
// 0.4 × cflFactor): their prediction of where a step takes the particles is linear in the step, and
// the controlDict's maxCo, on the kernel's support, let a wide kernel move them further (0.6 Δx at
// maxCo 0.15 on 4 Δx: iisph's largest compression in the Colagrossi dam break 2.9 % at H/80).
#pragma once

#include "Dictionary.hpp"
#include "Model.hpp"
#include "Parallel.hpp"
#include "Scene.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace spindrift {

struct IterativeSolverControls {
    enum class Norm { Maximum, Average };
    Scalar maxDensityError = Scalar(0.01);
    Norm norm = Norm::Maximum;
    int minIterations = 3;
    int maxIterations = 100;
    Scalar peakDensityError = Scalar(0.01); // the largest error allowed whatever the norm
    double maxDisplacement = 0.4;           // [Δx] in a step (above)

    // 'solution' is sphSolution's `pressure` sub-dictionary (may be nullptr); the current
    // members are the defaults.
    void read(const Dictionary* solution) {
        const std::string normDefault = norm == Norm::Maximum ? "maximum" : "average";
        if (solution) {
            const Dictionary& d = *solution;
            maxDensityError = d.getOrDefault<double>("maxDensityError", maxDensityError);
            norm = d.getWordOrDefault("densityErrorNorm", {"maximum", "average"}, normDefault) == "maximum"
                       ? Norm::Maximum
                       : Norm::Average;
            minIterations = d.getOrDefault<int>("minIterations", minIterations);
            maxIterations = d.getOrDefault<int>("maxIterations", maxIterations);
            peakDensityError = d.getOrDefault<double>("peakDensityError", peakDensityError);
            maxDisplacement = d.getOrDefault<double>("maxDisplacement", maxDisplacement);
            if (!(maxDensityError >= 0))
                throw InputError(d.locationOf("maxDensityError"), "maxDensityError must not be negative",
                                 "maxDensityError");
            if (!(peakDensityError > 0))
                throw InputError(d.locationOf("peakDensityError"), "peakDensityError must be positive", "peakDensityError");
            if (!(maxDisplacement > 0))
                throw InputError(d.locationOf("maxDisplacement"),
                                 "maxDisplacement (the furthest a particle moves in a step, in particle spacings) must be positive",
                                 "maxDisplacement");
            if (minIterations < 0)
                throw InputError(d.locationOf("minIterations"), "minIterations must not be negative", "minIterations");
            if (maxIterations < 1 || maxIterations < minIterations)
                throw InputError(d.locationOf("maxIterations"),
                                 "maxIterations must be at least 1 and at least minIterations", "maxIterations");
            d.checkAllKeywordsUsed();
        } else {
            std::ostringstream eta;
            eta << maxDensityError;
            logDefaultOnce("sphSolution.pressure.maxDensityError", eta.str());
            logDefaultOnce("sphSolution.pressure.densityErrorNorm", normDefault);
            std::ostringstream peak;
            peak << peakDensityError;
            logDefaultOnce("sphSolution.pressure.peakDensityError", peak.str());
            logDefaultOnce("sphSolution.pressure.minIterations", std::to_string(minIterations));
            logDefaultOnce("sphSolution.pressure.maxIterations", std::to_string(maxIterations));
        }
        std::ostringstream step;
        step << maxDisplacement;
        if (!solution || !solution->found("maxDisplacement")) logDefaultOnce("sphSolution.pressure.maxDisplacement", step.str());
    }

    // Δt ≤ maxDisplacement Δx / |v|max over the fluids (+∞ at rest): the solver's Model::maxTimeStep.
    double maxTimeStep(const Scene& s, const StateSpeeds& v) const {
        return v.fluid > 0 ? maxDisplacement * s.physics.particleSpacing / v.fluid : std::numeric_limits<double>::infinity();
    }

    Scalar error(Scalar maxError, Scalar avgError) const { return norm == Norm::Maximum ? maxError : avgError; }

    // After 'iterations' corrections with the given predicted errors: stop correcting?
    bool done(int iterations, Scalar maxError, Scalar avgError) const {
        if (iterations >= maxIterations) return true;
        return iterations >= minIterations && converged(maxError, avgError);
    }
    bool converged(Scalar maxError, Scalar avgError) const {
        return error(maxError, avgError) <= maxDensityError && maxError <= peakDensityError;
    }
};

// Compression error max(0, ρ_i − ρ0)/ρ0 of a density array: maximum and average over the
// particles (deterministic for any thread count).
struct CompressionError {
    Scalar max = 0, avg = 0;
};

// One parallel pass (it runs every solver iteration).
inline CompressionError compressionError(const std::vector<Scalar>& rho, Scalar rho0) {
    const std::size_t n = rho.size();
    if (n == 0) return {};
    const SumAndMax e = deterministicSumAndMax(n, [&](std::size_t i) { return std::max(Scalar(0), (rho[i] - rho0) / rho0); });
    return {Scalar(e.max), Scalar(e.sum / double(n))};
}

} // namespace spindrift
