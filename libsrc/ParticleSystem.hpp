// Spindrift — a particle system: the unit the scene, the neighbour search, the pair loop, the
// writer and the restart work on.
//
// Every system is a named particle set with a role:
//   fluid    integrated by the integrator, with the models' forces (rest density ρ0 and a
//            particle mass of its own: two fluids of different ρ0 are two systems);
//   wall     a boundary: fixed, or moving with a prescribed Motion (x_b(t) = c + R(t)(x_b(0) − c) + d(t));
//   body     a boundary moved by the fluid: a rigid body whose state (RigidBody.hpp) the core
//            advances with the fluid's force and moment on it and gravity;
//   passive  particles carried by the flow, never acting on it (tracers, the diffuse particles
//            of foam and spray to come): a model that owns the system moves them after the step.
// A boundary (wall or body) acts on the fluid through the case's boundary model, which declares
// the masses M_b of its particles in the pair sums, whether they mirror the fluid's pressure or
// have their own, and the velocity viscous terms see (BoundaryModel.hpp).
//
// Ghosts: a system may carry ghost particles after its own, copies of particles beyond a
// boundary (a periodic image, an MPI neighbour's halo). They are neighbours only: the search
// finds them as sources, but the pair loop, the integrator, the writer and the restart visit
// the system's own particles [0, ownedSize()) alone.
#pragma once

#include "Motion.hpp"
#include "NeighbourSearch.hpp"
#include "ParticleSet.hpp"

#include <memory>
#include <string>
#include <vector>

namespace spindrift {

class RigidBody;

enum class SystemRole { fluid, wall, body, passive };

// "fluid", "wall", "body", "passive" (as logs and messages name them).
const char* roleName(SystemRole role);

// ∇_i W_ij of every pair of a system's own neighbour list, in list order, kept by a model that
// computes them anyway (dfsph, pcisph, iisph, with the density) so that the pair loops evaluated
// after it in the step stream them instead of the kernel table. Valid for the system's own
// positions while its lists are those they were computed on (QueryLists::stamp); the core drops
// them when the particles move and re-sorts them with lists it keeps.
struct PairGradients {
    std::vector<Vec3> values;
    long stamp = -1; // QueryLists::stamp() of the lists they were computed on; -1: none

    bool validFor(const QueryLists& q) const {
        return stamp == q.stamp() && q.hasOwn() && values.size() == q.own().totalPairs();
    }
    void invalidate() { stamp = -1; }
};

class ParticleSystem {
public:
    ParticleSystem(std::string name, SystemRole role, std::size_t index);
    ~ParticleSystem();
    ParticleSystem(const ParticleSystem&) = delete;
    ParticleSystem& operator=(const ParticleSystem&) = delete;

    ParticleSet particles;
    const SystemRole role;
    const std::size_t index; // its place in Scene::systems: the number the search and the pair loop use

    // fluid: the rest density [kg/m^d] (the particle mass is particles.particleMass())
    Scalar rho0 = 0;

    // wall: a prescribed motion (null: fixed), its particles' positions at displacement zero
    std::unique_ptr<Motion> motion;
    std::vector<Vec3> initialPosition;
    // wall or body sampled as one layer on a surface (a Poisson-disk mesh wall): the surface's unit
    // normal at each particle, either orientation (its set's field "surfaceNormal"; null for
    // lattice walls), turned with the particles; its values at displacement zero (motion) or in
    // the body frame (body)
    std::vector<Vec3>* surfaceNormal = nullptr;
    std::vector<Vec3> initialSurfaceNormal;
    Scalar surfaceSpacing = 0; // the least distance of its particles (the Poisson-disk radius) [m]
    // body: its rigid-body state, mass properties and constraints; its particles' positions
    // in the body frame are the body's own (RigidBody::place)
    std::unique_ptr<RigidBody> body;

    // Declared by the boundary model in its initialise() (walls and bodies): the mass M_b each
    // particle has in the pair sums; whether a particle takes the pressure and density of the
    // fluid particle it faces (mirrored, Akinci et al. 2012) or has its own (the set's pressure
    // and density, Adami et al. 2012); and the velocity viscous terms see (null: the system's own).
    const std::vector<Scalar>* mass = nullptr;
    bool pressureMirrored = true;
    const std::vector<Vec3>* viscousVelocity = nullptr;

    // The last ghostCount particles are ghosts (neighbours only).
    std::size_t ghostCount = 0;

    // The pair gradients of its own neighbour list, when a model keeps them (PairGradients).
    PairGradients gradients;

    const std::string& name() const { return particles.name(); }
    std::size_t size() const { return particles.size(); }
    std::size_t ownedSize() const { return particles.size() - ghostCount; }
    bool isFluid() const { return role == SystemRole::fluid; }
    bool isBoundary() const { return role == SystemRole::wall || role == SystemRole::body; }
    bool isPassive() const { return role == SystemRole::passive; }
    // Its particles move during the run (a fluid, a passive system, a wall with a motion, a body).
    bool moves() const { return !(role == SystemRole::wall && !motion); }
    // A boundary that moves (a wall with a motion, a body): its particles have a velocity.
    bool movingBoundary() const { return isBoundary() && moves(); }
    const std::vector<Vec3>& velocitySeenByViscosity() const {
        return viscousVelocity ? *viscousVelocity : particles.velocity();
    }
};

} // namespace spindrift
