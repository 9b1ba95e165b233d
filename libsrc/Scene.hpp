// Spindrift — the scene every model works on: its particle systems (ParticleSystem.hpp: fluids,
// walls, bodies, passive systems), the step's neighbour lists, the tabulated kernel, and the
// constants fixed at set-up.
//
// Systems. The scene is a list of named systems, numbered in the order they were added (the
// number is the one the neighbour search and the pair loop use). The neighbour search builds
// lists for the pairs of systems declared to interact: every fluid against itself, the other
// fluids and every boundary (wall or body); a passive system against the systems a model
// declares for it. The writer puts each system in its own file of a time directory
// (<system>.vtp: one block each in ParaView); the restart and the blow-up roll-back cover every
// system.
//
// Contracts. `constants` is computed by the core before any model's initialise() and never
// changes afterwards: the one support radius h the kernel, its table and the neighbour search
// are built from, the sound speed of the pressure model's equation of state (declared by the
// pressure model, used by artificial viscosity and the time-step limit), the fluid height, the
// particle mass. Models read it; no model writes into the scene for another to read, except the
// boundary model's declared state of the boundary systems (ParticleSystem: mass, pressure,
// density, velocity seen by viscous terms) and the pair-gradient cache (PairGradients).
// Models do not hold one another: what one needs of another is a service of the core's
// (StepServices, Step.hpp), passed with each call.
#pragma once

#include "KernelTable.hpp"
#include "Parallel.hpp"
#include "NeighbourSearch.hpp"
#include "ParticleSystem.hpp"
#include "Reactions.hpp"

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
    Scalar supportRadiusFactor = 2; // h/Δx (the entry supportRadius; h itself is SceneConstants')
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

// Convergence of an iterative pressure solver in the last step (zero for explicit models).
struct SolverStats {
    int iterations = 0;
    bool converged = true;
    Scalar maxDensityError = 0; // max |ρ − ρ0| / ρ0 reached
    Scalar avgDensityError = 0; // average
};

struct Scene {
    PhysicalParameters physics;
    SceneConstants constants;
    // every system, in the order they were added (ParticleSystem::index); held by pointer, so a
    // system keeps its address when others are added (the search reads positions through it)
    std::vector<std::unique_ptr<ParticleSystem>> systems;
    NeighbourSearch search;
    KernelTable kernel;
    // the forces of the last evaluation on the boundary systems something asked for (Reactions.hpp)
    Reactions reactions;

    double time = 0;
    long step = 0;
    // changes whenever the particles move (a step, a roll-back): point queries on the current
    // positions rebuild their grid when it differs (NeighbourSearch::forEachWithin)
    long stateVersion = 0;

    // Adds a system (not yet known to the neighbour search: registerWithSearch).
    ParticleSystem& addSystem(const std::string& name, SystemRole role);
    // Registers a system with the neighbour search (systems are registered in the scene's order;
    // a wall's motion must be set first, so the search knows it moves) and declares the
    // interactions of its role with the systems registered before it: a fluid with itself, the
    // other fluids and every boundary; a boundary with every fluid; a body (its contacts) with
    // every other boundary. A passive system's interactions are declared by the model that owns it.
    void registerWithSearch(const ParticleSystem& system);
    ParticleSystem& system(std::size_t index) { return *systems[index]; }
    const ParticleSystem& system(std::size_t index) const { return *systems[index]; }
    // The system of that name (null if none).
    ParticleSystem* find(const std::string& name);
    const ParticleSystem* find(const std::string& name) const;
    // The systems of a role, in order.
    std::vector<ParticleSystem*> ofRole(SystemRole role);
    std::vector<const ParticleSystem*> ofRole(SystemRole role) const;
    // The boundaries (walls and bodies), in order.
    std::vector<ParticleSystem*> boundaries();
    std::vector<const ParticleSystem*> boundaries() const;
    bool anyMovingBoundary() const;
    std::size_t particlesOf(SystemRole role) const;
    // The lists of a query system.
    const QueryLists& listsOf(const ParticleSystem& query) const { return search.of(query.index); }
};

// Re-sorts a system's particles along the search grid's space-filling curve (cache locality),
// every field with them. A search at exactly these positions (the last build, or one made
// ahead: NeighbourSearch::listsAt) is kept: its lists are relabelled and the cached pair gradients
// moved with their rows (models' scratch fields move with the particles); otherwise the lists
// are stale until the next build.
void resortSystem(Scene& s, ParticleSystem& system);

} // namespace spindrift
