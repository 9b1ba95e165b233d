// Spindrift — the state every model works on: fluid and boundary particles, the step's
// neighbour lists, the tabulated kernel and the case's physical parameters.
#pragma once

#include "KernelTable.hpp"
#include "NeighbourSearch.hpp"
#include "ParticleSet.hpp"

#include <cmath>

namespace spindrift {

// From constant/fluidProperties.
struct PhysicalParameters {
    int dimension = 2;
    Scalar rho0 = 1000;            // rest density [kg/m^d]
    Scalar nu = 0;                 // kinematic viscosity [m^2/s]
    Vec3 gravity = Vec3::Zero();   // [m/s^2]
    Scalar particleSpacing = 0;    // Δx [m]
    Scalar supportRadius = 0;      // h [m] (= supportRadius factor · Δx)
    Scalar particleMass() const { return rho0 * std::pow(particleSpacing, dimension); }
};

// Convergence of an iterative pressure solver in the last step (zero for explicit models).
struct SolverStats {
    int iterations = 0;
    bool converged = true;
    Scalar maxDensityError = 0; // max |ρ − ρ0| / ρ0 reached
    Scalar avgDensityError = 0; // average
};

struct SphSystem {
    PhysicalParameters physics;
    ParticleSet fluid{"fluid"};
    ParticleSet boundary{"boundary"}; // static wall particles (may be empty)
    NeighbourSearch search;
    KernelTable kernel;

    // Set by the boundary model: in pair terms a wall particle b has mass boundaryMass[b] and,
    // when mirrored, the pressure and density of the fluid particle it interacts with.
    std::vector<Scalar>* boundaryMass = nullptr;
    bool boundaryPressureMirrored = true;
    // Set by the pressure model: numerical sound speed c0 (0 for incompressible solvers),
    // used by artificial viscosity and the time-step limit.
    Scalar soundSpeed = 0;
    // Set by a pressure model that keeps ∇_i W_ij of every fluid pair of the step's lists, in
    // list order (dfsph): valid from its computeDensity until the next neighbour search, so the
    // models evaluated after it in the step (viscosity) stream it instead of the kernel table.
    const std::vector<Vec3>* fluidPairGradients = nullptr;

    double time = 0;
    long step = 0;

    bool hasBoundary() const { return boundary.size() > 0; }
};

// Sum over i in [0, n) of f(i), independent of the thread count: partial sums over fixed
// blocks, combined in order.
template <class F> double deterministicSum(std::size_t n, F&& f) {
    constexpr std::size_t block = 4096;
    const std::size_t blocks = (n + block - 1) / block;
    std::vector<double> partial(blocks, 0.0);
#pragma omp parallel for schedule(static)
    for (std::size_t b = 0; b < blocks; ++b) {
        double s = 0;
        const std::size_t end = std::min(n, (b + 1) * block);
        for (std::size_t i = b * block; i < end; ++i) s += f(i);
        partial[b] = s;
    }
    double total = 0;
    for (double s : partial) total += s;
    return total;
}

// Max over i of f(i) (deterministic by nature); 0 for n = 0.
template <class F> double parallelMax(std::size_t n, F&& f) {
    double m = 0;
#pragma omp parallel for schedule(static) reduction(max : m)
    for (std::size_t i = 0; i < n; ++i) m = std::max(m, double(f(i)));
    return m;
}

} // namespace spindrift
