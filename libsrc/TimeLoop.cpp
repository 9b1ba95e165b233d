// Spindrift — the time loop of a run (Simulation::run): each step's lists, the evaluation, the
// integrator, the bodies and passive systems; the blow-up check with its roll-back (StateHistory);
// writing, function objects, signals and run-time edits of controlDict. The set-up is in
// Simulation.cpp, the run's log lines in RunLog.cpp.
#include "Simulation.hpp"

#include "Log.hpp"
#include "PairLoop.hpp"
#include "RigidBody.hpp"
#include "RunLog.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>

namespace spindrift {

void Simulation::advanceBodies(double dt) {
    const auto bodies = scene_.ofRole(SystemRole::body);
    if (bodies.empty()) return;
    const RigidBody::V3 g = scene_.physics.gravity.cast<double>();
    for (ParticleSystem* b : bodies) {
        RigidBody& body = *b->body;
        const Wrench w = scene_.reactions.total(b->index);
        body.advance(dt, w.force, w.momentAbout(body.state().position), g);
        body.place(*b);
        resolveContacts(*b);
    }
}

void Simulation::resolveContacts(ParticleSystem& b) {
    using V3 = RigidBody::V3;
    RigidBody& body = *b.body;
    const double d0 = scene_.physics.particleSpacing; // particles of two solids at rest sit Δx apart
    const QueryLists& q = scene_.listsOf(b);
    const auto& xb = b.particles.position();
    // the contact with every wall and other body at once: the deepest penetration, the normal
    // (penetration-weighted), the contact point and the other side's velocity there
    double deepest = 0, weight = 0;
    V3 normal = V3::Zero(), point = V3::Zero(), otherVelocity = V3::Zero();
    for (std::size_t k = 0; k < q.sourceCount(); ++k) {
        const ParticleSystem& o = scene_.system(q.source(k));
        const auto& xo = o.particles.position();
        const auto& vo = o.particles.velocity();
        for (std::size_t i = 0; i < q.size(); ++i)
            forEachNeighbour(q.list(k), xb, xo, i, [&](Index j, const Vec3& r, Scalar r2) {
                const double d = std::sqrt(double(r2));
                if (!(d < d0) || !(d > 0)) return;
                const double depth = d0 - d;
                deepest = std::max(deepest, depth);
                weight += depth;
                normal += depth * (r.cast<double>() / d);
                point += depth * xb[i].cast<double>();
                otherVelocity += depth * vo[j].cast<double>();
            });
    }
    if (!(weight > 0) || !(normal.norm() > 0)) return;
    normal.normalize();
    point /= weight;
    otherVelocity /= weight;
    body.resolveContact(normal, deepest, point, otherVelocity);
    body.place(b);
}

void Simulation::placeMovingWalls(double time) {
    for (ParticleSystem* w : scene_.ofRole(SystemRole::wall)) {
        if (!w->motion) continue;
        // x = c + R (x0 − c) + d, v = d' + ω × r, a = d'' + α × r + ω × (ω × r), r = x − c − d
        // (Motion.hpp), in double for every particle: a function of time alone
        const Motion& m = *w->motion;
        const RigidState st = m.state(time);
        auto& x = w->particles.position();
        auto& v = w->particles.velocity();
        auto& a = w->particles.acceleration();
        const auto& x0 = w->initialPosition;
        forEachIndex(x.size(), [&](std::size_t b) {
            const Eigen::Vector3d xb = m.position(st, x0[b].cast<double>());
            x[b] = xb.cast<Scalar>();
            v[b] = m.velocityAt(st, xb).cast<Scalar>();
            a[b] = m.accelerationAt(st, xb).cast<Scalar>();
        });
        if (w->surfaceNormal) {
            const auto& n0 = w->initialSurfaceNormal;
            forEachIndex(x.size(), [&](std::size_t b) { (*w->surfaceNormal)[b] = (st.rotation * n0[b].cast<double>()).cast<Scalar>(); });
        }
    }
}

double Simulation::wallSpeed(const ParticleSystem& w, double time) const {
    // the fastest particle of a moving wall at 'time': |d'| + |ω| max|x0 − c| bounds it
    const Motion& m = *w.motion;
    const RigidState st = m.state(time);
    double speed = st.velocity.norm();
    if (st.omega.squaredNorm() > 0) {
        const Eigen::Vector3d c = m.centre();
        const auto& x0 = w.initialPosition;
        const double r2 = parallelMax(x0.size(), [&](std::size_t b) { return (x0[b].cast<double>() - c).squaredNorm(); });
        speed += st.omega.norm() * std::sqrt(r2);
    }
    return speed;
}

void Simulation::updateLists(double time) {
    auto& s = scene_;
    placeMovingWalls(time);
    // lists at exactly the systems' positions (the last build, a re-sort of it, or a search a model
    // made ahead: dfsph's check) are kept, unless a boundary has moved since they were made
    bool stale = s.anyMovingBoundary() && !(listsBoundaryTime_ == time);
    for (const auto& q : s.systems) stale = stale || !s.search.listsAt(q->index, q->particles.position());
    if (stale) s.search.build();
    listsBoundaryTime_ = time;
}

void Simulation::evaluate(double time, Scalar dt) {
    auto& s = scene_;
    const Step step{time, dt, *services_};
    updateLists(time);
    Reactions& reactions = s.reactions;
    const bool wantReactions = reactions.anyWanted();
    if (wantReactions) reactions.clear();
    const auto fluids = s.ofRole(SystemRole::fluid);
    for (ParticleSystem* f : fluids) pressure_->computeDensity(s, *f, step);
    if (boundaryModel_) boundaryModel_->update(s, step);
    const Vec3 g = s.physics.gravity;
    for (ParticleSystem* f : fluids) {
        auto& a = f->particles.acceleration();
        forEachIndex(a.size(), [&](std::size_t i) { a[i] = g; });
        if (viscosity_) viscosity_->addAcceleration(s, *f, step);
        if (viscosity_ && wantReactions) viscosity_->addReactions(s, *f, step, reactions);
        for (auto& force : forces_) {
            force->addAcceleration(s, *f, step);
            if (wantReactions) force->addReactions(s, *f, step, reactions);
        }
        if (surfaceTension_) surfaceTension_->addAcceleration(s, *f, step);
        if (surfaceTension_ && wantReactions) surfaceTension_->addReactions(s, *f, step, reactions);
        pressure_->addPressureAcceleration(s, *f, step);
        if (wantReactions) pressure_->addReactions(s, *f, step, reactions);
        if (shifting_) shifting_->computeShift(s, *f, step);
        if (shifting_ && wantReactions) shifting_->addReactions(s, *f, step, reactions);
        // last: the collision with the boundaries has the final word on where the step takes a
        // particle (a shift or a particle collision would otherwise push it into a wall)
        if (boundaryModel_) boundaryModel_->correctAcceleration(s, *f, step);
        if (boundaryModel_ && wantReactions) boundaryModel_->addReactions(s, *f, step, reactions);
    }
}

double Simulation::stableDeltaT() const {
    const auto& s = scene_;
    const double h = s.constants.supportRadius;
    double vMax = 0, aMax = 0;
    for (const ParticleSystem* f : s.ofRole(SystemRole::fluid)) {
        const auto& v = f->particles.velocity();
        const auto& a = f->particles.acceleration();
        vMax = std::max(vMax, std::sqrt(parallelMax(f->ownedSize(), [&](std::size_t i) { return v[i].squaredNorm(); })));
        aMax = std::max(aMax, std::sqrt(parallelMax(f->ownedSize(), [&](std::size_t i) { return a[i].squaredNorm(); })));
    }
    const StateSpeeds speeds{vMax};
    for (const ParticleSystem* w : s.boundaries()) // a moving wall's fastest particle
        if (w->motion) vMax = std::max(vMax, wallSpeed(*w, s.time));
    for (const ParticleSystem* b : s.ofRole(SystemRole::body)) { // a body's fastest particle
        const auto& v = b->particles.velocity();
        vMax = std::max(vMax, std::sqrt(parallelMax(v.size(), [&](std::size_t i) { return v[i].squaredNorm(); })));
    }
    const double c0 = s.constants.soundSpeed;
    double dt = std::numeric_limits<double>::infinity();
    if (c0 + vMax > 0) dt = time_->maxCo() * h / (c0 + vMax);
    if (aMax > 0) dt = std::min(dt, 0.25 * std::sqrt(h / aMax));
    // the limits the models declare (viscosity's, the iterative solvers' displacement, ...)
    for (const Model* m : models()) dt = std::min(dt, m->maxTimeStep(s, speeds));
    return dt;
}

namespace {
// A moving wall or a body whose positions are not finite or beyond the box [lo, hi] at the scene's
// time (a wall's motion, checked at set-up, should never put it there): "" when none.
std::string movingBoundaryBlowUp(const Scene& s, const Vec3& lo, const Vec3& hi) {
    for (const ParticleSystem* w : s.boundaries()) {
        if (!w->moves()) continue;
        const auto& x = w->particles.position();
        const bool bad = parallelAny(x.size(), [&](std::size_t b) {
            for (int d = 0; d < s.physics.dimension; ++d)
                if (!(x[b][d] >= lo[d] && x[b][d] <= hi[d])) return true;
            return false;
        });
        if (!bad) continue;
        std::ostringstream m;
        m << std::setprecision(6) << "blow-up at step " << s.step << ", time " << s.time << ": ";
        if (w->motion) {
            const Vec3 d = w->motion->displacement(s.time);
            m << "wall '" << w->name() << "' is displaced by (" << d[0] << " " << d[1] << " " << d[2]
              << ") by its motion (" << w->motion->describe() << "), beyond the domain or not finite";
        } else
            m << "body '" << w->name() << "' is beyond the domain or not finite (centre of mass "
              << w->body->state().position.transpose() << ")";
        return m.str();
    }
    return {};
}
} // namespace

std::vector<const Model*> Simulation::models() const {
    std::vector<const Model*> out{pressure_.get(), integrator_.get()};
    for (const Model* m : {static_cast<const Model*>(viscosity_.get()), static_cast<const Model*>(boundaryModel_.get()),
                           static_cast<const Model*>(densityDiffusion_.get()), static_cast<const Model*>(shifting_.get())})
        if (m) out.push_back(m);
    for (const auto& f : forces_) out.push_back(f.get());
    if (surfaceTension_) out.push_back(surfaceTension_.get());
    for (const auto& p : passive_) out.push_back(p.get());
    return out;
}

std::string Simulation::findBlowUp(bool& densityOnly) const {
    densityOnly = false;
    if (std::string boundary = movingBoundaryBlowUp(scene_, blowUpMin_, blowUpMax_); !boundary.empty()) return boundary;
    std::string worst;
    for (const ParticleSystem* f : scene_.ofRole(SystemRole::fluid)) {
        bool density = false;
        const std::string found = findBlowUp(*f, density);
        if (!found.empty() && (worst.empty() || (densityOnly && !density))) {
            worst = found;
            densityOnly = density;
        }
    }
    return worst;
}

std::size_t Simulation::removeParticlesOutside() {
    const int dim = scene_.physics.dimension;
    std::size_t removedNow = 0;
    for (ParticleSystem* f : scene_.ofRole(SystemRole::fluid)) {
        ParticleSet& set = f->particles;
        const auto& x = set.position();
        const std::size_t n = f->ownedSize();
        // (a position that is not finite is not outside: the blow-up check reports it)
        const auto outside = [&](std::size_t i) {
            bool out = false;
            for (int d = 0; d < dim; ++d)
                out |= !periodic_.axis[d] && (x[i][d] < blowUpMin_[d] || x[i][d] > blowUpMax_[d]);
            return out;
        };
        if (!parallelAny(n, outside)) continue;
        // the rest in their order, its ghosts after them, the removed last
        std::vector<Index> order, gone;
        order.reserve(set.size());
        for (std::size_t i = 0; i < n; ++i) (outside(i) ? gone : order).push_back(Index(i));
        const double allowed = maxRemovedFraction_ * double(fluidAtStart_);
        if (double(removedParticles_ + removedNow + gone.size()) > allowed) continue; // a blow-up
        const std::size_t kept = order.size() + f->ghostCount;
        for (std::size_t i = n; i < set.size(); ++i) order.push_back(Index(i));
        std::ostringstream m;
        const std::size_t first = gone.front();
        m << std::setprecision(6) << "time " << scene_.time << ": removed " << gone.size() << " particle"
          << (gone.size() > 1 ? "s" : "") << " of " << f->name() << " that left the domain (" << blowUpMin_.transpose()
          << ") to (" << blowUpMax_.transpose() << ")" << (gone.size() > 1 ? ", the first " : ": ")
          << "particle " << set.id()[first] << " at (" << x[first].transpose() << ") with velocity ("
          << set.velocity()[first].transpose() << ")";
        order.insert(order.end(), gone.begin(), gone.end());
        set.permute(order);
        set.resize(kept);
        scene_.search.positionsChanged(f->index);
        f->gradients.invalidate();
        removedNow += gone.size();
        m << "; " << removedParticles_ + removedNow << " removed in this run, "
          << 100.0 * double(removedParticles_ + removedNow) / double(std::max<std::size_t>(fluidAtStart_, 1))
          << " % of the fluid (maxRemovedFraction " << maxRemovedFraction_ << ")";
        log::warning(m.str());
    }
    if (removedNow > 0) ++scene_.stateVersion;
    removedParticles_ += removedNow;
    return removedNow;
}

std::string Simulation::findBlowUp(const ParticleSystem& system, bool& densityOnly) const {
    const auto& f = system.particles;
    const auto& x = f.position();
    const auto& v = f.velocity();
    const auto& rho = f.density();
    const auto& p = f.pressure();
    const auto& a = f.acceleration();
    const int dim = scene_.physics.dimension;
    const double rho0 = system.rho0;
    const std::size_t n = system.ownedSize();
    // worst particle: not finite > far outside > largest density error
    long worst = -1;
    int worstKind = 0; // 3 not finite, 2 outside, 1 density
    double worstDensity = blowUpDensityError_;
    // a parallel look first (every step); the serial search for the worst particle only after
    // a blow-up
    // (without branches: a value not finite makes the sum's s − s NaN, which fails == 0)
    const double speed2 = blowUpSpeed_ * blowUpSpeed_;
    bool bounded[3];
    for (int d = 0; d < 3; ++d) bounded[d] = d < dim && !periodic_.axis[d];
    const bool any = parallelAny(n, [&](std::size_t i) {
        const Scalar sum = x[i].sum() + v[i].sum() + a[i].sum() + rho[i] + p[i];
        int bad = int(!(sum - sum == 0)) | int(v[i].squaredNorm() > speed2) | int((rho[i] - rho0) / rho0 > worstDensity);
        for (int d = 0; d < 3; ++d) bad |= int(bounded[d]) & (int(x[i][d] < blowUpMin_[d]) | int(x[i][d] > blowUpMax_[d]));
        return bad != 0;
    });
    densityOnly = false;
    if (!any) return {};
    for (std::size_t i = 0; i < n; ++i) {
        if (!x[i].allFinite() || !v[i].allFinite() || !a[i].allFinite() || !std::isfinite(rho[i]) ||
            !std::isfinite(p[i])) {
            worst = long(i);
            worstKind = 3;
            break;
        }
        if (worstKind < 2 && v[i].squaredNorm() > blowUpSpeed_ * blowUpSpeed_) {
            worst = long(i);
            worstKind = 2;
        }
        if (worstKind < 2)
            for (int d = 0; d < dim; ++d)
                if (!periodic_.axis[d] && (x[i][d] < blowUpMin_[d] || x[i][d] > blowUpMax_[d])) {
                    worst = long(i);
                    worstKind = 2;
                }
        if (worstKind < 2 && (rho[i] - rho0) / rho0 > worstDensity) {
            worst = long(i);
            worstKind = 1;
            worstDensity = (rho[i] - rho0) / rho0;
        }
    }
    densityOnly = worstKind == 1;
    if (worst < 0) return {};
    const std::size_t i = std::size_t(worst);
    std::ostringstream s;
    s << std::setprecision(6) << "blow-up at step " << scene_.step << ", time " << scene_.time << ": particle "
      << f.id()[i] << " of " << system.name() << " at (" << x[i].transpose() << ") with velocity ("
      << v[i].transpose() << ") ";
    if (worstKind == 3) s << "has a value that is not finite (density " << rho[i] << ", pressure " << p[i] << ")";
    else if (worstKind == 2 && v[i].norm() > blowUpSpeed_) s << "moves faster than " << blowUpSpeed_ << " m/s";
    else if (worstKind == 2 && removeOutside_)
        s << "is far outside the domain, and removing the particles there would take this run's removals ("
          << removedParticles_ << " so far) past maxRemovedFraction " << maxRemovedFraction_ << " of the fluid";
    else if (worstKind == 2) s << "is far outside the domain (onParticleOutside stop)";
    else s << "has a density error of " << 100 * worstDensity << "% (blowUpDensityError " << 100 * blowUpDensityError_ << "%)";
    return s.str();
}

void Simulation::write() {
    // every system at every written time: a wall's own pressure and density change (adami), and
    // each time directory is whole by itself (a fixed wall's positions are written again: VTK
    // XML PolyData cannot take another file's points). A wall whose boundary model mirrors the
    // fluid's pressure has no pressure nor density of its own (the arrays hold nothing
    // meaningful): they are left out rather than written as 0
    for (ParticleSystem* w : scene_.boundaries())
        if (w->pressureMirrored) {
            w->particles.setUndefined("pressure");
            w->particles.setUndefined("density");
        }
    // the other systems: walls and bodies (sampled anew on a restart; a body's state is in
    // uniform/bodies) and passive systems (their particles continue: restart fields)
    std::vector<CaseWriter::SystemFile> others;
    for (const auto& p : scene_.systems)
        if (p.get() != fluid_) others.push_back({&p->particles, p->role == SystemRole::passive});
    std::vector<std::pair<std::string, std::string>> extra{{"uniform/time", timeFile()},
                                                           {"uniform/particles", particlesFile()}};
    if (const std::string bodies = bodiesFile(); !bodies.empty()) extra.emplace_back("uniform/bodies", bodies);
    if (const std::string passive = passiveStateFile(); !passive.empty()) extra.emplace_back("uniform/passive", passive);
    // the function objects' blocks (freeSurface's surface mesh), of the state written
    std::vector<CaseWriter::Block> blocks;
    for (auto& f : functions_)
        if (std::string name = f->blockName(); !name.empty())
            blocks.push_back({std::move(name), [this, &f](const std::filesystem::path& file) { f->writeBlock(scene_, file); }});
    writer_->write(scene_.time, fluid_->particles, others, writeFields_, extra, blocks);
}

void Simulation::takeCaseTimes() {
    const CaseWriter::RunStart start = writer_->beginRun(scene_.time, restartedFrom_);
    const auto names = [](const std::vector<std::string>& list) {
        std::string text;
        for (const auto& n : list) text += " " + n;
        return text;
    };
    if (!start.movedAside.empty())
        log::warning((restarted_ ? "the times after the restart time " + restartedFrom_ + " are not continued: moved them"
                                 : "a run from startTime owns the case's times: moved those of an earlier run") +
                     " to " + (case_.dir / "previousRun").string() + ":" + names(start.movedAside) +
                     (start.replacedPreviousRun ? " (removing the previousRun/ of an earlier start)" : ""));
    if (!start.notListed.empty())
        log::info("The times before startTime" + names(start.notListed) +
                  " are an earlier run's: kept, but not listed in " + writer_->collectionFile().filename().string());
}

void Simulation::writeInitialState() {
    evaluate(scene_.time, Scalar(time_->initialDeltaT()));
    startFunctionObjects();
    takeCaseTimes();
    write();
}

void Simulation::startFunctionObjects() {
    // After the start time's evaluation and before its write: their first rows describe what the
    // time directory holds (-postProcess reproduces them), and an entry they refuse (a probed
    // field the case does not have) stops the run before anything is written.
    for (auto& f : functions_) f->start(scene_, scene_.time);
}

namespace {
constexpr int stopSignals[] = {SIGINT, SIGTERM, SIGHUP};
std::atomic<int> pendingSignal{0};
extern "C" void onStopSignal(int signal) { pendingSignal.store(signal); }

extern "C" void onStopSignalDuringSetUp(int signal) {
    char text[128] = "spindrift: ";
    std::size_t n = std::strlen(text);
    for (const char* part : {log::signalName(signal), " received during set-up (before the time loop): stopped\n"})
        for (; *part && n + 1 < sizeof text; ++part) text[n++] = *part;
    log::writeLastWords(text, n);
    CaseLock::releaseInSignalHandler(); // a run that never started leaves no lock behind
    ::signal(signal, SIG_DFL); // die of the signal: the status a shell shows is 128 + signal
    ::raise(signal);
}

void installStopHandler(void (*handler)(int), int flags, struct sigaction* previous = nullptr) {
    struct sigaction action {};
    action.sa_handler = handler;
    sigemptyset(&action.sa_mask);
    action.sa_flags = flags;
    for (std::size_t k = 0; k < std::size(stopSignals); ++k)
        ::sigaction(stopSignals[k], &action, previous ? &previous[k] : nullptr);
}

// Installs the time loop's SIGINT/SIGTERM/SIGHUP handlers (finish the step, write it, stop) for
// the life of a run, restoring the previous ones after.
struct StopSignals {
    struct sigaction previous[std::size(stopSignals)];
    StopSignals() {
        pendingSignal.store(0);
        installStopHandler(onStopSignal, SA_RESTART, previous);
    }
    ~StopSignals() {
        for (std::size_t k = 0; k < std::size(stopSignals); ++k) ::sigaction(stopSignals[k], &previous[k], nullptr);
    }
};

} // namespace

void stopAtOnceOnSignalsDuringSetUp() { installStopHandler(onStopSignalDuringSetUp, SA_RESETHAND | SA_NODEFER); }

namespace {
// The states before the last two steps, to go back to when a step blows up: every system whose
// state is not a function of time (fluids, passive systems) and the bodies, with the time
// controls of the step that followed. A density error shows in the evaluation of the step after
// the one that caused it, so such a blow-up goes back two steps.
class StateHistory {
public:
    struct State {
        std::vector<ParticleSet> systems; // of the kept systems, in order
        std::vector<RigidBody::State> bodies;
        double time = 0, lastDeltaT = 0, dtTaken = 0, deltaTCap = 0;
        long step = 0;
        int holdSteps = 0;
        std::size_t removedParticles = 0; // the run's removals so far
        bool valid = false;
    };

    explicit StateHistory(Scene& s) : scene_(s), bodies_(s.ofRole(SystemRole::body)) {
        for (const auto& p : s.systems)
            if (p->isFluid() || p->isPassive()) kept_.push_back(p.get());
    }

    // Before a step: the state it starts from becomes the last one (the one before it the
    // previous, unless the last step was taken back); the caller fills in its time controls.
    State& keep() {
        if (!keepPrevious_) std::swap(previous_, last_);
        keepPrevious_ = false;
        last_.systems.resize(kept_.size());
        for (std::size_t k = 0; k < kept_.size(); ++k) last_.systems[k].copyDataFrom(kept_[k]->particles);
        last_.bodies.clear();
        for (const ParticleSystem* b : bodies_) last_.bodies.push_back(b->body->state());
        last_.valid = true;
        return last_;
    }

    // After a blow-up: puts the scene's systems and bodies back to the state before the last step,
    // or before the last two for a density error (when that state is kept), and returns it.
    const State& goBack(bool densityError) {
        const bool twoBack = densityError && previous_.valid;
        const State& good = twoBack ? previous_ : last_;
        for (std::size_t k = 0; k < kept_.size(); ++k) {
            kept_[k]->particles.copyDataFrom(good.systems[k]);
            scene_.search.positionsChanged(kept_[k]->index);
        }
        for (std::size_t k = 0; k < bodies_.size(); ++k) {
            bodies_[k]->body->setState(good.bodies[k]);
            bodies_[k]->body->place(*bodies_[k]);
        }
        ++scene_.stateVersion;
        scene_.time = good.time;
        scene_.step = good.step;
        if (twoBack) {
            previous_.valid = last_.valid = false;
            return previous_; // its data stays as it was: only marked used up
        }
        keepPrevious_ = true; // 'previous' is still the state before the one gone back to
        return last_;
    }

private:
    Scene& scene_;
    std::vector<ParticleSystem*> kept_;
    std::vector<ParticleSystem*> bodies_;
    State previous_, last_;
    bool keepPrevious_ = false;
};
} // namespace

RunSummary Simulation::run() {
    StopSignals signals;
    auto& s = scene_;
    RunSummary summary;
    summary.fluidParticles = fluidAtStart_ = s.particlesOf(SystemRole::fluid);
    removedParticles_ = 0;
    summary.wallParticles = s.particlesOf(SystemRole::wall) + s.particlesOf(SystemRole::body);

    const long startStep = s.step;
    RunLog runLog(*time_, s.time, startStep);
    double lastWritten = restarted_ ? s.time : std::numeric_limits<double>::quiet_NaN();
    const auto writeAndLog = [&] {
        write();
        lastWritten = s.time;
        runLog.wrote(s.time, s.step);
    };
    // the fatal-signal message names the last completed step
    const auto setFatalSignalContext = [&] {
        char text[160];
        std::snprintf(text, sizeof text, "at step %ld, time %.6g (last completed step)", s.step, s.time);
        log::setFatalSignalContext(text);
    };

    if (!restarted_) evaluate(s.time, Scalar(time_->initialDeltaT()));
    startFunctionObjects(); // before anything is written, on the state the start time's directory holds
    takeCaseTimes();
    if (!restarted_) writeAndLog();
    setFatalSignalContext();
    {
        double vMax0 = 0;
        for (const ParticleSystem* f : s.ofRole(SystemRole::fluid))
            for (const auto& v : f->particles.velocity()) vMax0 = std::max(vMax0, double(v.norm()));
        for (const ParticleSystem* w : s.boundaries())
            if (w->motion) vMax0 = std::max(vMax0, wallSpeed(*w, s.time));
        blowUpSpeedAuto_ = std::max({blowUpSpeedFloor_, 100 * double(s.constants.soundSpeed), 100 * vMax0, 1.0});
        blowUpSpeed_ = blowUpSpeedSetting_ > 0 ? blowUpSpeedSetting_ : blowUpSpeedAuto_;
    }

    long iterations = 0, iterativeSteps = 0;
    StateHistory history(s);
    int retries = 0, stepsSinceRetry = 0;
    log::info("\nStarting time loop\n");
    while (!time_->finished(s.time)) {
        if (sortEvery_ > 0 && s.step % sortEvery_ == 0)
            for (ParticleSystem* f : s.ofRole(SystemRole::fluid)) resortSystem(s, *f);
        bool capped = false;
        const double dt = time_->nextDeltaT(s.time, stableDeltaT(), deltaTCap_, &capped);
        StateHistory::State& before = history.keep();
        before.time = s.time;
        before.step = s.step;
        before.lastDeltaT = lastDeltaT_;
        before.dtTaken = dt;
        before.deltaTCap = deltaTCap_;
        before.holdSteps = deltaTHoldSteps_;
        before.removedParticles = removedParticles_;

        // the step starts on the lists of its state: an integrator that carries a_n over from the
        // last step advances the integrated fields (continuity density) on them before it evaluates;
        // after a restart, a re-sort or a blow-up's roll-back they are made here
        updateLists(s.time);
        integrator_->step(s, *services_, Scalar(dt), [&](double t, Scalar stepDt) { evaluate(t, stepDt); });
        advanceBodies(dt);
        for (auto& p : passive_) p->afterStep(s, Step{before.time, Scalar(dt), *services_});
        s.time = before.time + dt;
        ++s.step;
        ++s.stateVersion;
        if (removeOutside_) removeParticlesOutside();
        bool densityBlowUp = false;
        const std::string blowUp = findBlowUp(densityBlowUp);
        if (!blowUp.empty()) {
            const StateHistory::State& good = history.goBack(densityBlowUp);
            lastDeltaT_ = good.lastDeltaT;
            removedParticles_ = good.removedParticles;
            // the times written after the good state hold the abandoned run: removed, so that
            // neither ParaView nor 'startFrom latestTime' takes them for results
            const auto removeAbandonedTimes = [&] {
                const auto removed = writer_->removeTimesWrittenAfter(good.time);
                std::string names;
                for (const auto& n : removed) names += " " + n;
                if (!removed.empty()) log::warning("removed the times written after " + CaseWriter::timeName(good.time) + ":" + names);
            };
            deltaTCap_ = good.deltaTCap;
            deltaTHoldSteps_ = good.holdSteps;
            time_->scheduleNextWrite(good.time); // the steps taken again write the times they pass
            if (reduceDeltaTOnBlowUp_ && retries < blowUpRetries_) {
                removeAbandonedTimes();
                ++retries;
                stepsSinceRetry = 0;
                deltaTCap_ = 0.5 * good.dtTaken;
                deltaTHoldSteps_ = blowUpHoldSteps;
                time_->setPreviousDeltaT(deltaTCap_);
                std::ostringstream m;
                m << std::setprecision(6) << "; going back to time " << CaseWriter::timeName(good.time)
                  << " and retrying with deltaT " << deltaTCap_ << ", held for " << blowUpHoldSteps
                  << " steps, then growing by at most " << blowUpCapGrowth << "x a step";
                log::warning(blowUp + m.str());
                runLog.logNextStep();
                setFatalSignalContext();
                continue;
            }
            write(); // the last good state, to look at in ParaView (and to restart from)
            removeAbandonedTimes();
            throw BlowUpError(blowUp + ". The last good state (time " + CaseWriter::timeName(good.time) +
                                     ") is written to " + (case_.dir / CaseWriter::timeName(good.time)).string() +
                                     "; try a smaller deltaT or maxCo, or onBlowUp reduceDeltaT;");
        }
        lastDeltaT_ = dt;
        if (++stepsSinceRetry >= 2) retries = 0; // the retried steps are known good
        // a blow-up's cap: held, then grown gradually, dropped once Δt stays below it
        if (std::isfinite(deltaTCap_) && (deltaTHoldSteps_ == 0 || --deltaTHoldSteps_ == 0)) {
            if (capped) {
                // from the step taken (a step evened out to land on a write time may be below the cap)
                deltaTCap_ = blowUpCapGrowth * std::min(deltaTCap_, dt);
            } else {
                std::ostringstream m;
                m << std::setprecision(6) << "deltaT " << dt << " at time " << s.time
                  << " is below the cap of the last blow-up retry (" << deltaTCap_ << "): no longer capped";
                log::info(m.str());
                deltaTCap_ = std::numeric_limits<double>::infinity();
            }
        }
        setFatalSignalContext();

        const DensityError err = densityError(s);
        summary.maxDensityError = std::max(summary.maxDensityError, err.max);
        std::optional<SolverStats> solver;
        if (pressure_->isIterative()) {
            solver = pressure_->lastSolve();
            iterations += solver->iterations;
            ++iterativeSteps;
            solverPerformance_->writeRow(s.time, {double(solver->iterations), solver->converged ? 1.0 : 0.0,
                                                  100 * solver->maxDensityError, 100 * solver->avgDensityError});
        }
        const int signal = pendingSignal.load();
        const bool notConverged = solver && !solver->converged;
        if (runLog.stepLineDue(s.time, s.step, dt, logInterval_, notConverged || signal != 0)) {
            double vMax = 0;
            for (const ParticleSystem* f : s.ofRole(SystemRole::fluid)) {
                const auto& v = f->particles.velocity();
                vMax = std::max(vMax, std::sqrt(parallelMax(f->ownedSize(), [&](std::size_t i) { return v[i].squaredNorm(); })));
            }
            runLog.stepLine(s.time, s.step, dt, vMax, err, solver ? &*solver : nullptr);
        }

        const bool writeTime = time_->writeDue(s.time, s.step) || signal != 0;
        if (writeTime) writeAndLog();
        for (auto& f : functions_) f->execute(s, writeTime);
        if (signal != 0) {
            log::clearProgress();
            log::info(std::string("\n") + log::signalName(signal) + " received: wrote time " +
                      CaseWriter::timeName(s.time) +
                      " and stopped. Continue with 'startFrom latestTime;' in system/controlDict.");
            summary.interrupted = true;
            break;
        }
        rereadControlDictIfChanged();
        runLog.progress(s.time, s.step);
    }
    log::clearProgress();
    // the end state, also off the write schedule (else the run's last steps are lost and a
    // restart goes back to the last write time)
    if (!summary.interrupted && s.time != lastWritten) writeAndLog();
    for (auto& f : functions_) f->end(s);
    summary.steps = s.step - startStep;
    summary.endTime = s.time;
    summary.writes = int(writer_->timesWritten());
    summary.wallSeconds = runLog.wallSeconds();
    summary.averageIterations = iterativeSteps ? double(iterations) / iterativeSteps : 0.0;
    summary.removedParticles = removedParticles_;
    return summary;
}

} // namespace spindrift
