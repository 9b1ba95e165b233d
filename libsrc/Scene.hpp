// Spindrift — the scene every model works on: its particle systems (the fluid and any number of
// walls, fixed or moving), the step's neighbour lists, the tabulated kernel, and the constants
// fixed at set-up.
//
// Systems. The fluid is one particle set; each entry of constant/geometry's `walls { }` is a wall
// system of its own (its name is the entry's), fixed or moving with a prescribed Motion. The
// neighbour search serves the fluid against itself and against every wall (never wall against
// wall during the run). The writer puts each system in its own file of a time directory
// (fluid.vtp, <wall>.vtp): one block each in ParaView. Rigid bodies (a wall whose motion comes
// from the fluid's forces), diffuse particles (advected through the fluid after its step) and
// further fluids are the next roles; SystemRole names them so the writer and the search already
// speak of roles, not of "the" fluid and "the" boundary.
//
// Contracts. `constants` is computed by the core before any model's initialise() and never
// changes afterwards: the sound speed of the pressure model's equation of state (declared by the
// pressure model, used by artificial viscosity and the time-step limit), the fluid height, the
// particle mass and the one support radius h the kernel, its table and the neighbour search are
// built from. Models read it; no model writes into the scene for another to read, except the
// declared wall state a boundary model keeps (WallSystem: mass, pressure, density, velocity
// seen by viscous terms) and the pair-gradient cache (PairGradients).
#pragma once

#include "KernelTable.hpp"
#include "Motion.hpp"
#include "NeighbourSearch.hpp"
#include "ParticleSet.hpp"

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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

// Fixed at set-up, before any model initialises (Simulation computes them); read-only to models.
struct SceneConstants {
    Scalar supportRadius = 0; // h [m]: the kernel, its table and the neighbour search use this one
    Scalar particleMass = 0;  // m of a fluid particle [kg] (latticeParticleMass)
    Scalar fluidHeight = 0;   // H [m]: the initial fluid's extent along gravity, plus Δx (0 without gravity)
    Scalar soundSpeed = 0;    // c0 [m/s] of the pressure model's equation of state; 0 for the
                              // incompressible solvers (PressureModel::soundSpeed declares it)
    Scalar eosExponent = 0;   // γ of its Tait equation of state (PressureModel::eosExponent)
    Scalar rho0 = 0;          // rest density [kg/m^d]

    // The density at pressure p by the pressure model's equation of state, inverted:
    // ρ0 (p/B + 1)^(1/γ), B = c0² ρ0/γ (Tait); ρ0 for an incompressible solver (c0 = 0). Walls
    // with a pressure of their own (adami) take their density from it.
    Scalar densityAt(Scalar p) const {
        if (!(soundSpeed > 0) || !(eosExponent > 0)) return rho0;
        const Scalar B = soundSpeed * soundSpeed * rho0 / eosExponent;
        return rho0 * std::pow(std::max(p / B + 1, Scalar(1e-3)), 1 / eosExponent);
    }
};

class BoundaryModel;
class DensityDiffusion;
struct Scene;

// A per-particle quantity a model integrates in time beside position and velocity (continuity
// density). The integrator advances it as the particles move, value += Δt rate
// (advanceIntegratedFields, Integrator.hpp), with the rate computeRate gives from the velocities
// the particles move with over the step, at the positions the step starts from (on the step's
// lists): a symplectic pairing, as the velocity's. (A rate taken with the old velocities makes
// the density–velocity acoustic waves grow every step: a tank at rest erupted in 0.1 s.)
struct IntegratedField {
    std::vector<Scalar>* value;
    std::vector<Scalar>* rate;
    std::function<void(const Scene&, std::vector<Scalar>& rate)> computeRate;
};

// Convergence of an iterative pressure solver in the last step (zero for explicit models).
struct SolverStats {
    int iterations = 0;
    bool converged = true;
    Scalar maxDensityError = 0; // max |ρ − ρ0| / ρ0 reached
    Scalar avgDensityError = 0; // average
};

enum class SystemRole { fluid, wall };

// A wall: particles fixed in space, or all moving with one prescribed Motion. The particle set
// holds position, velocity (the wall's own: zero when fixed), density and pressure (the boundary
// model's: extrapolated, or unused when it mirrors the fluid's), and what the boundary model adds.
struct WallSystem {
    explicit WallSystem(std::string name) : particles(std::move(name)) {}
    ParticleSet particles;
    std::unique_ptr<Motion> motion;    // null: fixed
    std::vector<Vec3> initialPosition; // x_b(0) of a moving wall: x_b(t) = x_b(0) + d(t)

    // Set by the boundary model in its initialise(): the mass M_b each wall particle has in the
    // pair sums; whether a wall particle takes the pressure and density of the fluid particle it
    // faces (mirrored, Akinci et al. 2012) or has its own (the particle set's pressure and
    // density, Adami et al. 2012); and the velocity viscous terms see (null: the wall's own).
    const std::vector<Scalar>* mass = nullptr;
    bool pressureMirrored = true;
    const std::vector<Vec3>* viscousVelocity = nullptr;

    const std::string& name() const { return particles.name(); }
    std::size_t size() const { return particles.size(); }
    bool moving() const { return motion != nullptr; }
    const std::vector<Vec3>& velocitySeenByViscosity() const {
        return viscousVelocity ? *viscousVelocity : particles.velocity();
    }
};

// ∇_i W_ij of every fluid pair of the current neighbour lists, in list order, kept by a model
// that computes them anyway (dfsph, with its density) so that the pair loops evaluated after it
// in the step stream them instead of the kernel table. Valid for the fluid's own positions while
// the search has not been rebuilt; the core drops it when the particles move and re-sorts it
// with a search it keeps.
struct PairGradients {
    std::vector<Vec3> values;
    long build = -1; // NeighbourSearch::builds() they were computed for; -1: none

    bool validFor(const NeighbourSearch& search) const {
        return build == search.builds() && values.size() == search.fluidNeighbours().totalPairs();
    }
    void invalidate() { build = -1; }
};

struct Scene {
    PhysicalParameters physics;
    SceneConstants constants;
    ParticleSet fluid{"fluid"};
    std::vector<WallSystem> walls; // not resized after set-up (the search keeps their positions)
    NeighbourSearch search;
    KernelTable kernel;
    PairGradients gradients;
    // quantities models integrate in time (registered in their initialise())
    std::vector<IntegratedField> integratedFields;
    // the boundary model, for pressure solvers that change the fluid's pressure in their
    // iterations and must carry it to walls of their own pressure (BoundaryModel::updatePressure)
    BoundaryModel* boundaryModel = nullptr;
    // a density-diffusion model (δ-SPH), adding to the rate of the integrated density
    const DensityDiffusion* densityDiffusion = nullptr;
    // the transport velocity correction δv of a shifting model (fluid field "shiftingVelocity"):
    // particles move with v + δv (the integrators' drift), null without one
    const std::vector<Vec3>* shiftingVelocity = nullptr;

    double time = 0;
    long step = 0;

    bool hasWalls() const { return !walls.empty(); }
    bool anyMovingWall() const {
        for (const auto& w : walls)
            if (w.moving()) return true;
        return false;
    }
    std::size_t wallParticles() const {
        std::size_t n = 0;
        for (const auto& w : walls) n += w.size();
        return n;
    }
};

// Re-sorts the fluid particles along the search grid's space-filling curve (cache locality), every
// field with them. A search at exactly these positions (the last build, or one made ahead:
// NeighbourSearch::listsAt) is kept: its lists are relabelled and the cached pair gradients moved
// with their rows (models' scratch fields move with the particles); otherwise the lists are stale
// until the next build.
void resortFluid(Scene& s);

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
