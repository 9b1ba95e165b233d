// Spindrift — the forces the fluid exerts on the boundary systems (walls and bodies): the
// reactions of the pair terms by which a boundary acts on the fluid.
//
// A pair term gives fluid particle i the acceleration a_ib from boundary particle b; Newton's
// third law gives b the force f_bi = −m_i a_ib. Summed over the pairs of a boundary system:
//   F = Σ_i Σ_b f_bi,   M_O = Σ_i Σ_b x_b × f_bi   (about the origin; M_c = M_O − c × F)
// for each kind of force apart (pressure, viscous, other), as OpenFOAM's forces function object
// reports them. A model computes the reactions of its own terms from its final state (the
// iterative solvers' final pressure), on request only: the core asks for them (and clears them
// before each evaluation) when something wants them — a `forces` function object, a rigid body.
// The sums are deterministic at any thread count: per fluid particle in list order, then over
// fixed blocks of particles in order. They are kept in double precision.
#pragma once

#include "Types.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <vector>

namespace spindrift {

enum class ForceKind { pressure = 0, viscous = 1, other = 2 };
inline constexpr std::size_t forceKinds = 3;
const char* forceKindName(ForceKind kind);

// A force and its moment about the origin (double precision).
struct Wrench {
    using V3 = Eigen::Vector3d;
    V3 force = V3::Zero();
    V3 moment = V3::Zero(); // about the origin
    Wrench& operator+=(const Wrench& w) {
        force += w.force;
        moment += w.moment;
        return *this;
    }
    // The moment about point c.
    V3 momentAbout(const V3& c) const { return moment - c.cross(force); }
};

class Reactions {
public:
    // Asks for the reactions on system 'system' from the next evaluation on (idempotent).
    void want(std::size_t system);
    bool wanted(std::size_t system) const;
    bool anyWanted() const;
    const std::vector<std::size_t>& wantedSystems() const { return systems_; }

    // Before an evaluation: every sum to zero.
    void clear();
    void add(std::size_t system, ForceKind kind, const Wrench& w);

    // On a wanted system, of one kind and of every kind.
    const Wrench& of(std::size_t system, ForceKind kind) const;
    Wrench total(std::size_t system) const;

private:
    std::vector<std::size_t> systems_;
    std::vector<std::array<Wrench, forceKinds>> sums_; // parallel to systems_
    std::size_t slot(std::size_t system) const;
};

} // namespace spindrift
