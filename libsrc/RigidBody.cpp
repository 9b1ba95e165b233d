#include "RigidBody.hpp"

#include "Dictionary.hpp"
#include "ParticleSystem.hpp"
#include "Parallel.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace spindrift {

RigidBody::RigidBody(double mass, const M3& inertia, const State& start, int dimension)
    : mass_(mass), inertia_(inertia), state_(start), dimension_(dimension) {
    if (!(mass > 0)) throw std::invalid_argument("a rigid body needs a positive mass");
    if (dimension == 2) {
        // in the plane: x, y and the rotation about z
        fixedTranslation_ = {false, false, true};
        fixedRotation_ = {true, true, false};
        if (!(inertia(2, 2) > 0)) throw std::invalid_argument("a 2D rigid body needs a positive moment of inertia Izz");
        inverseInertia_ = M3::Zero();
        inverseInertia_(2, 2) = 1 / inertia(2, 2);
    } else {
        if (!(inertia.determinant() > 0)) throw std::invalid_argument("a rigid body needs a positive definite inertia");
        inverseInertia_ = inertia.inverse();
    }
}

RigidBody RigidBody::read(const Dictionary& d, const Vec3& boxMin, const Vec3& boxMax, int dim) {
    const V3 lo = boxMin.cast<double>(), hi = boxMax.cast<double>();
    const V3 size = hi - lo;
    const double volume = dim == 2 ? size[0] * size[1] : size[0] * size[1] * size[2];
    // the uniform box about its centre: I_xx = V (b² + c²)/12, ... (2D: the in-plane Izz)
    M3 unit = M3::Zero();
    unit(0, 0) = volume * (size[1] * size[1] + size[2] * size[2]) / 12;
    unit(1, 1) = volume * (size[0] * size[0] + size[2] * size[2]) / 12;
    unit(2, 2) = volume * (size[0] * size[0] + size[1] * size[1]) / 12;
    return read(d, volume, 0.5 * (lo + hi), unit, dim);
}

RigidBody RigidBody::read(const Dictionary& d, double volume, const V3& centroid, const M3& unitInertia, int dim) {
    const auto positive = [&](const char* key, double value) {
        if (!(value > 0) || !std::isfinite(value))
            throw InputError(d.locationOf(key), std::string(key) + " must be a positive number", key);
        return value;
    };
    const auto vector3 = [&](const char* key, const V3& fallback) {
        if (!d.found(key)) return fallback;
        const Vec3 v = d.get<Vec3>(key);
        if (!v.allFinite()) throw InputError(d.locationOf(key), std::string(key) + " must be finite", key);
        return V3(v.cast<double>());
    };
    if (d.found("density") == d.found("mass"))
        throw InputError(d.found("mass") ? d.locationOf("mass") : d.where(),
                         "a body needs either 'density' (of the uniform solid) or 'mass'", "density");
    double mass = 0;
    M3 inertia = M3::Zero();
    if (d.found("density")) {
        const double density = positive("density", d.get<double>("density"));
        mass = density * volume;
        inertia = density * unitInertia;
    } else {
        mass = positive("mass", d.get<double>("mass"));
        if (!d.found("inertia"))
            throw InputError(d.locationOf("mass"), "a body given by its 'mass' needs its 'inertia' too", "inertia");
    }
    if (d.found("inertia")) {
        const auto I = d.get<std::vector<double>>("inertia");
        if (dim == 2 && I.size() == 1) inertia(2, 2) = positive("inertia", I[0]);
        else if (I.size() == 3)
            for (int a = 0; a < 3; ++a) inertia(a, a) = (dim == 2 && a < 2) ? 0.0 : positive("inertia", I[a]);
        else
            throw InputError(d.locationOf("inertia"), dim == 2 ? "inertia needs (Izz) or (Ixx Iyy Izz)"
                                                               : "inertia needs (Ixx Iyy Izz), the principal moments",
                             "inertia");
    }
    State start;
    start.position = vector3("centreOfMass", centroid);
    if (dim == 2) start.position[2] = 0;
    start.velocity = vector3("velocity", V3::Zero());
    const V3 w = vector3("angularVelocity", V3::Zero());
    start.angularMomentum = inertia * w; // the body frame is the world's at the start
    std::array<bool, 3> fixedTranslation{}, fixedRotation{};
    const auto freedoms = [&](const char* key, std::array<bool, 3>& fixed) {
        if (!d.found(key)) return;
        const Vec3 f = d.get<Vec3>(key);
        for (int a = 0; a < 3; ++a) {
            if (f[a] != 0 && f[a] != 1)
                throw InputError(d.locationOf(key), std::string(key) + " lists the free axes: 1 free, 0 fixed", key);
            fixed[a] = f[a] == 0;
        }
    };
    freedoms("translation", fixedTranslation);
    freedoms("rotation", fixedRotation);
    try {
        RigidBody body(mass, inertia, start, dim);
        body.setConstraints(fixedTranslation, fixedRotation);
        return body;
    } catch (const std::invalid_argument& e) {
        throw InputError(d.where(), std::string("body: ") + e.what());
    }
}

void RigidBody::setConstraints(const std::array<bool, 3>& fixedTranslation, const std::array<bool, 3>& fixedRotation) {
    for (int a = 0; a < 3; ++a) {
        fixedTranslation_[a] = fixedTranslation_[a] || fixedTranslation[a];
        fixedRotation_[a] = fixedRotation_[a] || fixedRotation[a];
    }
    state_.velocity = masked(state_.velocity, fixedTranslation_);
    state_.angularMomentum = masked(state_.angularMomentum, fixedRotation_);
}

RigidBody::V3 RigidBody::masked(const V3& v, const std::array<bool, 3>& fixed) const {
    V3 out = v;
    for (int a = 0; a < 3; ++a)
        if (fixed[a]) out[a] = 0;
    return out;
}

RigidBody::V3 RigidBody::angularVelocity() const {
    const M3 R = state_.orientation.toRotationMatrix();
    return masked(R * inverseInertia_ * R.transpose() * state_.angularMomentum, fixedRotation_);
}

void RigidBody::attach(ParticleSystem& system) const {
    const M3 Rt = state_.orientation.toRotationMatrix().transpose();
    const auto& x = system.particles.position();
    system.initialPosition.resize(x.size());
    for (std::size_t b = 0; b < x.size(); ++b)
        system.initialPosition[b] = (Rt * (x[b].cast<double>() - state_.position)).cast<Scalar>();
    if (system.surfaceNormal) {
        system.initialSurfaceNormal.resize(x.size());
        for (std::size_t b = 0; b < x.size(); ++b)
            system.initialSurfaceNormal[b] = (Rt * (*system.surfaceNormal)[b].cast<double>()).cast<Scalar>();
    }
}

void RigidBody::place(ParticleSystem& system) const {
    const M3 R = state_.orientation.toRotationMatrix();
    const V3 X = state_.position, V = state_.velocity, w = angularVelocity();
    const V3 A = acceleration_, alpha = angularAcceleration_;
    auto& x = system.particles.position();
    auto& v = system.particles.velocity();
    auto& a = system.particles.acceleration();
    const auto& local = system.initialPosition;
    forEachIndex(x.size(), [&](std::size_t b) {
        const V3 r = R * local[b].cast<double>();
        x[b] = (X + r).cast<Scalar>();
        v[b] = (V + w.cross(r)).cast<Scalar>();
        a[b] = (A + alpha.cross(r) + w.cross(w.cross(r))).cast<Scalar>();
    });
    if (system.surfaceNormal) {
        const auto& n0 = system.initialSurfaceNormal;
        forEachIndex(x.size(), [&](std::size_t b) { (*system.surfaceNormal)[b] = (R * n0[b].cast<double>()).cast<Scalar>(); });
    }
}

void RigidBody::advance(double dt, const V3& force, const V3& moment, const V3& gravity) {
    const V3 A = masked(force / mass_ + gravity, fixedTranslation_);
    state_.position += dt * state_.velocity + (0.5 * dt * dt) * A;
    state_.velocity += dt * A;
    acceleration_ = A;
    const V3 w0 = angularVelocity();
    state_.angularMomentum = masked(state_.angularMomentum + dt * moment, fixedRotation_);
    const V3 w = angularVelocity();
    const double angle = w.norm() * dt;
    if (angle > 0) state_.orientation = (Q(Eigen::AngleAxisd(angle, w.normalized())) * state_.orientation).normalized();
    angularAcceleration_ = dt > 0 ? V3((angularVelocity() - w0) / dt) : V3::Zero();
}

void RigidBody::resolveContact(const V3& n, double depth, const V3& c, const V3& u) {
    state_.position += masked(depth * n, fixedTranslation_);
    const V3 r = c - state_.position;
    const V3 vc = state_.velocity + angularVelocity().cross(r);
    const double approach = (vc - u).dot(n);
    if (!(approach < 0)) return;
    const M3 R = state_.orientation.toRotationMatrix();
    const M3 inverseWorld = R * inverseInertia_ * R.transpose();
    const V3 nLinear = masked(n, fixedTranslation_);
    const V3 torque = masked(r.cross(n), fixedRotation_);
    const double denominator = nLinear.dot(n) / mass_ + (inverseWorld * torque).cross(r).dot(n);
    if (!(denominator > 0)) return;
    const double J = -approach / denominator;
    state_.velocity += masked(J * n, fixedTranslation_) / mass_;
    state_.angularMomentum += masked(r.cross(J * n), fixedRotation_);
}

std::string RigidBody::stateText() const {
    std::ostringstream s;
    s << std::setprecision(17);
    const auto vector = [&](const char* name, const V3& v) {
        s << "    " << name << " (" << v[0] << " " << v[1] << " " << v[2] << ");\n";
    };
    vector("position", state_.position);
    const Q& q = state_.orientation;
    s << "    orientation (" << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << ");\n";
    vector("velocity", state_.velocity);
    vector("angularMomentum", state_.angularMomentum);
    vector("acceleration", acceleration_);
    vector("angularAcceleration", angularAcceleration_);
    return s.str();
}

void RigidBody::readState(const Dictionary& d) {
    const auto vector = [&](const char* name) {
        const auto v = d.get<std::vector<double>>(name);
        if (v.size() != 3) throw InputError(d.locationOf(name), std::string(name) + " needs 3 components", name);
        return V3(v[0], v[1], v[2]);
    };
    State s;
    s.position = vector("position");
    const auto q = d.get<std::vector<double>>("orientation");
    if (q.size() != 4)
        throw InputError(d.locationOf("orientation"), "orientation needs 4 components (w x y z)", "orientation");
    s.orientation = Q(q[0], q[1], q[2], q[3]);
    s.velocity = vector("velocity");
    s.angularMomentum = vector("angularMomentum");
    state_ = s;
    acceleration_ = vector("acceleration");
    angularAcceleration_ = vector("angularAcceleration");
}

} // namespace spindrift
