// Spindrift — prescribed motion of a wall system (constant/geometry `walls { name { motion { } } }`).
//
// A motion is a rigid transform of the wall as constant/geometry draws it (x_b(0)):
//     x_b(t) = c + R(t) (x_b(0) − c) + d(t)
//     v_b(t) = d'(t) + ω(t) × r,      a_b(t) = d''(t) + α(t) × r + ω × (ω × r),   r = x_b(t) − c − d(t)
// with c a fixed centre (the rotation's axis passes through it), R(t) a rotation (the identity for
// a translation), d(t) the translation, ω and α the angular velocity and acceleration. In two
// dimensions a rotation is about z. The core places the wall at the time of each force evaluation
// (an integrator's stage may evaluate at t + Δt), so positions are a function of time alone and a
// restart reproduces them bit for bit. Every motion is at rest in its drawn pose before its
// startTime (R = I, d = 0). Types (README "Geometry", docs/MODELS.md §motions):
//
//   linear        velocity (0.5 0 0); startTime 0; endTime 1;
//                 d(t) = velocity · (clamp(t, startTime, endTime) − startTime)
//   oscillating   direction (1 0 0); amplitude 0.05; period 1; phase 0; startTime 0;
//                 d(t) = amplitude · direction · (sin(2π (t − startTime)/period + phase) − sin(phase))
//   rotating      axis (0 0 1); centre (0.5 0.2 0); rate 1.5 [rad/s]; startTime 0; rampTime 0;
//                 θ(t) = rate · (t − startTime) (spun up over rampTime)
//   rolling       axis; centre; amplitude [deg]; period; phase 0; startTime 0; rampTime 0;
//   flap          axis; hinge; amplitude [deg]; period; phase 0; startTime 0; rampTime 0;
//                 θ(t) = amplitude · (sin(2π (t − startTime)/period + phase) − sin(phase))
//   table         file "constant/motion.dat"; interpolation linear|spline; axis; centre;
//                 rows "t dx dy dz angle[deg]": d(t) and θ(t) interpolated (held beyond the table)
//   pistonWaveMaker  waveHeight H; period T; depth d; direction (1 0 0); rampTime 2T; startTime 0;
//                 secondOrder no;  d(t) = ramp · S/2 sin ωt (+ Madsen's second harmonic)
//   flapWaveMaker    waveHeight; period; depth; hinge (point on the bed); direction; rampTime;
//                 startTime;  θ(t) = ramp · atan(S/(2 depth)) sin ωt
// A ramp is the quintic smoothstep s³(10 − 15 s + 6 s²), s = (t − startTime)/rampTime, multiplying
// the signal (position, velocity and acceleration continuous). Stroke S from the first-order
// transfer functions (Biesel 1951; Dean & Dalrymple 1991 §6.2):
//   piston H/S = 2 (cosh 2kd − 1)/(sinh 2kd + 2kd)
//   flap   H/S = 4 (sinh kd / kd) (kd sinh kd − cosh kd + 1)/(sinh 2kd + 2kd)
// with k from ω² = g k tanh kd; piston second order: Madsen (1971), J. Geophys. Res. 76(36),
// 8672–8683, doi:10.1029/JC076i036p08672 (flap: refused).
#pragma once

#include "Dictionary.hpp"
#include "Types.hpp"

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>

namespace spindrift {

// The rigid transform of a motion at one time, in double precision.
struct RigidState {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); // R(t)
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // d(t)
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();     // d'(t)
    Eigen::Vector3d acceleration = Eigen::Vector3d::Zero(); // d''(t)
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();        // ω(t)
    Eigen::Vector3d alpha = Eigen::Vector3d::Zero();        // α(t) = ω'(t)
};

// What a motion needs from the case to be read.
struct MotionContext {
    int dimension = 3;
    double runStart = 0, runEnd = 1;
    std::filesystem::path caseDir;                 // a table's file is relative to it
    Eigen::Vector3d gravity{0, -9.81, 0};          // wave makers: g and "up"
};

class Motion {
public:
    virtual ~Motion() = default;
    virtual RigidState state(double t) const = 0;
    // A short description for the log, e.g. "linear, velocity (0.5 0 0)".
    virtual std::string describe() const = 0;
    // The fixed centre c of the rotation (zero for a translation).
    const Eigen::Vector3d& centre() const { return centre_; }

    // The translation d(t) and its derivatives (the whole motion for a translation).
    Vec3 displacement(double t) const { return state(t).translation.cast<Scalar>(); }
    Vec3 velocity(double t) const { return state(t).velocity.cast<Scalar>(); }
    Vec3 acceleration(double t) const { return state(t).acceleration.cast<Scalar>(); }

    // A point drawn at x0 (the wall's pose at rest), at the state s: its position, and the
    // velocity and acceleration of the wall at its position x.
    Eigen::Vector3d position(const RigidState& s, const Eigen::Vector3d& x0) const {
        return centre_ + s.rotation * (x0 - centre_) + s.translation;
    }
    Eigen::Vector3d velocityAt(const RigidState& s, const Eigen::Vector3d& x) const {
        return s.velocity + s.omega.cross(x - centre_ - s.translation);
    }
    Eigen::Vector3d accelerationAt(const RigidState& s, const Eigen::Vector3d& x) const {
        const Eigen::Vector3d r = x - centre_ - s.translation;
        return s.acceleration + s.alpha.cross(r) + s.omega.cross(s.omega.cross(r));
    }
    // Where the point x at the state s was drawn (the inverse transform).
    Eigen::Vector3d drawnPosition(const RigidState& s, const Eigen::Vector3d& x) const {
        return centre_ + s.rotation.transpose() * (x - centre_ - s.translation);
    }

    // The box swept over [t0, t1] by a wall drawn inside the box [wallLo, wallHi] (for the
    // neighbour grid's domain): its corners sampled, padded by half the most a corner moves between samples.
    void sweptRange(double t0, double t1, const Vec3& wallLo, const Vec3& wallHi, Vec3& lo, Vec3& hi) const;

    // Reads `motion { type ...; }` for a run from runStart to runEnd; errors name the
    // dictionary's file, line and keyword. Every number must be finite, a period a normal number,
    // an oscillation at most 1e9 periods from its startTime to runEnd (beyond that its phase is
    // noise) with a finite peak acceleration, and the motion finite over the run.
    static std::unique_ptr<Motion> read(const Dictionary& motion, const MotionContext& context);
    static std::unique_ptr<Motion> read(const Dictionary& motion, int dimension, double runStart, double runEnd) {
        MotionContext c;
        c.dimension = dimension;
        c.runStart = runStart;
        c.runEnd = runEnd;
        return read(motion, c);
    }

protected:
    Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
};

// First-order wave-maker theory (Biesel 1951; Dean & Dalrymple 1991 eqs. 6.22, 6.23).
namespace waveMaker {
// k from the linear dispersion relation ω² = g k tanh(k d).
double waveNumber(double omega, double depth, double g);
// wave height over stroke, H/S
double pistonRatio(double kd);
double flapRatio(double kd);
// Madsen (1971): the amplitude of the piston's second harmonic, sin(2ωt), for a wave of height H
// in depth d with wave number k.
double madsenSecondHarmonic(double H, double k, double depth);
} // namespace waveMaker

} // namespace spindrift
