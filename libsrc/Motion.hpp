// Spindrift — prescribed motion of a wall system (constant/geometry `walls { name { motion { } } }`).
//
// Every particle of a moving wall follows the same translation d(t): x_b(t) = x_b(0) + d(t),
// v_b(t) = d'(t), a_b(t) = d''(t). The core places the wall at the time of each force
// evaluation (an integrator's stage may evaluate at t + Δt), so positions are a function of
// time alone and a restart reproduces them bit for bit.
//
//   motion { type linear; velocity (0.5 0 0); startTime 0; endTime 1; }
//       d(t) = velocity · (clamp(t, startTime, endTime) − startTime)   (at rest before and after)
//   motion { type oscillating; direction (1 0 0); amplitude 0.05; period 1; phase 0; startTime 0; }
//       d(t) = amplitude · direction · (sin(2π (t − startTime)/period + phase) − sin(phase)),
//       for t ≥ startTime (a piston wave maker; at rest before startTime)
#pragma once

#include "Dictionary.hpp"
#include "Types.hpp"

#include <memory>
#include <string>

namespace spindrift {

class Motion {
public:
    virtual ~Motion() = default;
    virtual Vec3 displacement(double t) const = 0;
    virtual Vec3 velocity(double t) const = 0;
    virtual Vec3 acceleration(double t) const = 0;
    // A short description for the log, e.g. "linear, velocity (0.5 0 0)".
    virtual std::string describe() const = 0;
    // The box swept by the displacement over [t0, t1] (for the neighbour grid's domain).
    void sweptRange(double t0, double t1, Vec3& lo, Vec3& hi) const;

    // Reads `motion { type ...; }` for a run from runStart to runEnd; errors name the
    // dictionary's file, line and keyword. Every number must be finite, a period a normal number,
    // an oscillation at most 1e9 periods from its startTime to runEnd (beyond that its phase is
    // noise) with a finite peak acceleration, and the motion finite over the run.
    static std::unique_ptr<Motion> read(const Dictionary& motion, int dimension, double runStart, double runEnd);
};

} // namespace spindrift
