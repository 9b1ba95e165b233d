// Spindrift — a rigid body moved by the fluid: Newton–Euler in 6 degrees of freedom (3 in 2D:
// x, y and the rotation about z), with gravity, the fluid's force F and moment M about the
// centre of mass (the reactions of the pair terms, Reactions.hpp) and a contact force that keeps
// it out of walls and other bodies.
//
//   Translation:  A = F/m + g,   X_{n+1} = X_n + Δt V_n + ½Δt² A,   V_{n+1} = V_n + Δt A
//   Rotation:     L_{n+1} = L_n + Δt M   (L the angular momentum about X, world frame)
//                 ω = R I⁻¹ Rᵀ L,   q_{n+1} = exp(½ Δt ω) q_n   (R of the unit quaternion q)
// With A constant the positions are exact (a ballistic flight to round-off); with no moment L is
// kept exactly, whatever the inertia (a torque-free body's angular momentum to round-off).
// Constraints fix world axes: `fixedTranslation (0 1 0)` keeps the centre from moving along y,
// `fixedRotation (1 1 0)` allows rotation about z only; in 2D the body moves in the plane and
// turns about z. The body's particles keep their positions r_b in the body frame:
//   x_b = X + R r_b,   v_b = V + ω × (x_b − X),   a_b = A + α × r + ω × (ω × r)
// (a_b enters adami's wall pressure through (g − a_b)). The state is kept in double precision
// whatever the build's, and written in full (uniform/bodies), so a restart continues bit for bit.
#pragma once

#include "Types.hpp"

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace spindrift {

class Dictionary;
class ParticleSystem;

class RigidBody {
public:
    using V3 = Eigen::Vector3d;
    using M3 = Eigen::Matrix3d;
    using Q = Eigen::Quaterniond;

    struct State {
        V3 position = V3::Zero();        // X: the centre of mass [m]
        Q orientation = Q::Identity();   // q: body frame → world frame
        V3 velocity = V3::Zero();        // V [m/s]
        V3 angularMomentum = V3::Zero(); // L about X, world frame [kg m²/s] (per unit depth in 2D)
    };

    // mass [kg] (per unit depth in 2D), inertia about the centre of mass in the body frame
    // [kg m²], the initial state, the dimension.
    RigidBody(double mass, const M3& inertia, const State& start, int dimension);

    // A body from its constant/geometry `bodies` entry, sampled in the box [boxMin, boxMax]:
    //   density 500;                    // [kg/m³]: mass and inertia of the uniform box, or
    //   mass 12.5; centreOfMass (..);   // [kg] (2D: kg/m); default the box's centre
    //   inertia (Ixx Iyy Izz);          // [kg m²] about the centre of mass (2D: Izz alone)
    //   velocity (0 0 0); angularVelocity (0 0 0);   // initial [m/s], [rad/s]
    //   translation (1 1 1); rotation (1 1 1);       // free degrees of freedom (0: fixed)
    // Errors name the entry's keyword.
    static RigidBody read(const Dictionary& entry, const Vec3& boxMin, const Vec3& boxMax, int dimension);
    // The same for a body of any shape: 'volume' (2D: area), 'centroid' and 'unitInertia' (about
    // the centroid, per unit density) of the uniform solid; `density` scales them.
    static RigidBody read(const Dictionary& entry, double volume, const V3& centroid, const M3& unitInertia,
                          int dimension);

    // Translation and rotation locked along world axes (true: fixed).
    void setConstraints(const std::array<bool, 3>& fixedTranslation, const std::array<bool, 3>& fixedRotation);

    double mass() const { return mass_; }
    const M3& inertia() const { return inertia_; }
    const State& state() const { return state_; }
    void setState(const State& s) { state_ = s; }
    V3 angularVelocity() const;
    const V3& acceleration() const { return acceleration_; }
    const V3& angularAcceleration() const { return angularAcceleration_; }

    // The body frame positions of a system's particles from their world positions at the
    // initial state (set-up): r_b = Rᵀ (x_b − X).
    void attach(ParticleSystem& system) const;
    // Places the particles where the state puts them: positions, velocities, accelerations.
    void place(ParticleSystem& system) const;
    // Advances the state over dt with force F and moment M (about X) besides gravity g.
    void advance(double dt, const V3& force, const V3& moment, const V3& gravity);
    // A contact with a wall or another body: moves the body 'depth' along the unit normal n (out
    // of the other) and, where the contact point c approaches the other side (its velocity u
    // there), applies the impulse J n that stops the approach (a plastic contact, no friction):
    //   J = −(v_c − u)·n / (1/m + n·(I_w⁻¹ (r × n)) × r),   r = c − X,   v_c = V + ω × r.
    // The constraints hold: a fixed direction neither moves nor takes an impulse.
    void resolveContact(const V3& n, double depth, const V3& c, const V3& u);

    // The state (and the last step's accelerations) as dictionary entries in full precision, and
    // read back (a restart continues bit for bit).
    std::string stateText() const;
    void readState(const Dictionary& d);

private:
    V3 masked(const V3& v, const std::array<bool, 3>& fixed) const;

    double mass_;
    M3 inertia_, inverseInertia_;
    State state_;
    int dimension_;
    std::array<bool, 3> fixedTranslation_{false, false, false}, fixedRotation_{false, false, false};
    V3 acceleration_ = V3::Zero(), angularAcceleration_ = V3::Zero();
};

} // namespace spindrift
