#include "Simulation.hpp"

#include "Geometry.hpp"
#include "Log.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;

namespace spindrift {
namespace {

std::string formatDuration(double s) {
    std::ostringstream o;
    if (s < 60) o << std::fixed << std::setprecision(1) << s << " s";
    else if (s < 3600) o << int(s / 60) << " min " << int(s) % 60 << " s";
    else o << int(s / 3600) << " h " << int(s / 60) % 60 << " min";
    return o.str();
}

struct DensityError {
    double max = 0, avg = 0;
};

// Compression error (ρ − ρ0)/ρ0 where positive; the density deficit at a free surface is not
// an error of the pressure solver.
DensityError densityError(const SphSystem& s) {
    const auto& rho = s.fluid.density();
    const double rho0 = s.physics.rho0;
    const std::size_t n = rho.size();
    if (n == 0) return {};
    DensityError e;
    e.max = parallelMax(n, [&](std::size_t i) { return std::max(0.0, (rho[i] - rho0) / rho0); });
    e.avg = deterministicSum(n, [&](std::size_t i) { return std::max(0.0, (rho[i] - rho0) / rho0); }) / n;
    return e;
}

} // namespace

Scalar latticeParticleMass(const KernelTable& kernel, const PhysicalParameters& physics) {
    const double dx = physics.particleSpacing, h = kernel.supportRadius();
    const int reach = int(std::ceil(h / dx)), dim = physics.dimension;
    double sum = 0;
    for (int k = (dim == 3 ? -reach : 0); k <= (dim == 3 ? reach : 0); ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i)
                sum += kernel.W(Scalar(dx * std::sqrt(double(i * i + j * j + k * k))));
    return Scalar(physics.rho0 / sum);
}

Simulation::Simulation(const fs::path& caseDir) : case_(Case::read(caseDir)) {
    auto& registry = ModelRegistry::instance();
    const Dictionary& control = case_.controlDict;
    time_ = std::make_unique<TimeControl>(control);
    // user plugin libraries
    if (const Entry* libs = control.findEntry("libs")) {
        for (const auto& lib : control.get<std::vector<std::string>>("libs"))
            registry.loadUserLibrary(lib, case_.dir, libs->where);
    }
    writeFields_ = control.getOrDefault<std::vector<std::string>>("writeFields", {});
    const Dictionary* functions = control.findDict("functions");
    control.getOrDefault<std::string>("application", "spindrift");
    control.getOrDefault<std::string>("stopAt", "endTime");
    control.getOrDefault<int>("timePrecision", 6);
    control.checkAllKeywordsUsed();

    system_.physics = readPhysicalParameters(case_.fluidProperties);
    const auto& physics = system_.physics;

    const Dictionary& schemes = case_.sphSchemes;
    auto solutionFor = [&](const std::string& kind) { return case_.sphSolution.findDict(kind); };
    kernel_ = registry.create<Kernel>(schemes.subDict("kernel"), physics);
    system_.kernel.build(*kernel_);
    pressure_ = registry.create<PressureModel>(schemes.subDict("pressure"), physics, solutionFor("pressure"));
    if (const Dictionary* v = schemes.findDict("viscosity"))
        viscosity_ = registry.create<ViscosityModel>(*v, physics, solutionFor("viscosity"));
    integrator_ = registry.create<Integrator>(schemes.subDict("integrator"), physics);
    if (const Dictionary* forces = schemes.findDict("forces")) {
        for (const auto& name : forces->keywords())
            forces_.push_back(registry.create<ExtraForce>(forces->subDict(name), physics, solutionFor(name),
                                                          case_.dir, name));
    }
    if (const Dictionary* ns = schemes.findDict("neighbourSearch")) {
        sortEvery_ = ns->getOrDefault<int>("sortEvery", 10);
        ns->checkAllKeywordsUsed();
    }

    buildParticles();

    if (system_.hasBoundary()) {
        if (!schemes.findDict("boundary"))
            throw InputError(schemes.where(), "constant/geometry has walls, so sphSchemes needs a "
                                              "'boundary { type ...; }' entry (e.g. akinci)", "boundary");
        boundaryModel_ = registry.create<BoundaryModel>(schemes.subDict("boundary"), physics);
    }
    schemes.markUsed("boundary");
    schemes.checkAllKeywordsUsed();
    case_.sphSolution.markUsed("pressure");
    case_.sphSolution.markUsed("viscosity");
    case_.sphSolution.checkAllKeywordsUsed();

    if (boundaryModel_) boundaryModel_->initialise(system_);
    pressure_->initialise(system_);
    if (viscosity_) viscosity_->initialise(system_);
    for (auto& f : forces_) f->initialise(system_);
    integrator_->initialise(system_);
    if (functions) {
        for (const auto& name : functions->keywords())
            functions_.push_back(registry.create<FunctionObject>(functions->subDict(name), physics, nullptr,
                                                                 case_.dir, name));
    }

    writer_ = std::make_unique<CaseWriter>(case_.dir, control.getOrDefault<int>("timePrecision", 6));
    restarted_ = time_->startFromLatest() && restartFromLatest();
    if (!restarted_) system_.time = time_->startTime();
    time_->begin(system_.time);
    for (auto& f : functions_) f->start(system_, system_.time);
    if (pressure_->isIterative())
        solverPerformance_ = std::make_unique<PostProcessingFile>(
            case_.dir, "solverPerformance", system_.time,
            std::vector<std::string>{"iterations", "converged", "maxDensityError", "avgDensityError"});
}

Simulation::~Simulation() = default;

void Simulation::buildParticles() {
    const auto& physics = system_.physics;
    const SampledGeometry g = sampleGeometry(case_.geometry, physics.particleSpacing, physics.dimension);
    auto& fluid = system_.fluid;
    fluid.resize(g.fluidPositions.size());
    fluid.setParticleMass(latticeParticleMass(system_.kernel, physics));
    for (std::size_t i = 0; i < g.fluidPositions.size(); ++i) {
        fluid.position()[i] = g.fluidPositions[i];
        fluid.velocity()[i] = g.fluidVelocities[i];
        fluid.density()[i] = physics.rho0;
        fluid.id()[i] = Index(i);
    }
    auto& wall = system_.boundary;
    wall.resize(g.wallPositions.size());
    for (std::size_t i = 0; i < g.wallPositions.size(); ++i) {
        wall.position()[i] = g.wallPositions[i];
        wall.density()[i] = physics.rho0;
        wall.id()[i] = Index(i);
    }
    // Neighbour grid over the sampled bounds with a generous margin (particles beyond it are
    // clamped into border cells: correct, only slower).
    const Vec3 extent = g.boundsMax - g.boundsMin;
    const Scalar margin = 2 * physics.supportRadius;
    domainMin_ = g.boundsMin - Vec3::Constant(margin) - Scalar(0.25) * extent;
    domainMax_ = g.boundsMax + Vec3::Constant(margin) + Scalar(0.25) * extent;
    periodic_ = g.periodic;
    if (physics.dimension == 2) domainMin_[2] = domainMax_[2] = 0;
    // A particle beyond one more extent (and 10 h) from everything sampled has blown up.
    const Vec3 reach = extent.cwiseMax(Vec3::Constant(10 * physics.supportRadius));
    blowUpMin_ = g.boundsMin - reach;
    blowUpMax_ = g.boundsMax + reach;
    system_.search.setup(physics.supportRadius, physics.dimension, domainMin_, domainMax_, periodic_);
    if (wall.size() > 0) {
        const auto order = system_.search.sortOrder(wall.position());
        wall.permute(order);
        system_.search.setBoundary(wall.position());
    }
}

bool Simulation::restartFromLatest() {
    const auto times = writer_->existingTimes();
    if (times.empty()) {
        log::warning("startFrom latestTime: no time directory in " + case_.dir.string() +
                     "; starting from startTime");
        return false;
    }
    const auto& [time, name] = times.back();
    const ParticleSet saved = readVtp(case_.dir / name / "fluid.vtp");
    auto& fluid = system_.fluid;
    if (saved.size() == 0) throw InputError({(case_.dir / name / "fluid.vtp").string(), 0, 0}, "no particles to restart from");
    fluid.resize(saved.size());
    fluid.id() = saved.id();
    for (const auto& f : saved.scalarFields())
        if (auto* mine = fluid.findScalar(f->name)) *mine = f->data;
    for (const auto& f : saved.vectorFields())
        if (auto* mine = fluid.findVector(f->name)) *mine = f->data;
    fluid.position() = saved.position();
    system_.time = time;
    boundaryWritten_ = true; // static walls were written at the first time
    log::info("Restarting from time " + name + " (" + std::to_string(saved.size()) + " particles)");
    return true;
}

std::string Simulation::schemesSummary() const {
    std::ostringstream s;
    auto type = [&](const char* kind) {
        const Dictionary* d = case_.sphSchemes.findDict(kind);
        return d && d->found("type") ? d->get<std::string>("type") : std::string("none");
    };
    s << "kernel " << type("kernel") << ", pressure " << type("pressure") << ", viscosity "
      << (viscosity_ ? type("viscosity") : "none") << ", integrator " << type("integrator")
      << ", boundary " << (boundaryModel_ ? type("boundary") : "none");
    if (const Dictionary* forces = case_.sphSchemes.findDict("forces"))
        for (const auto& name : forces->keywords()) s << ", force " << forces->subDict(name).get<std::string>("type");
    return s.str();
}

void Simulation::evaluate(Scalar dt) {
    auto& s = system_;
    s.search.build(s.fluid.position());
    pressure_->computeDensity(s);
    if (boundaryModel_) boundaryModel_->update(s);
    auto& a = s.fluid.acceleration();
    const Vec3 g = s.physics.gravity;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = g;
    if (viscosity_) viscosity_->addAcceleration(s, dt);
    for (auto& f : forces_) f->addAcceleration(s, dt);
    pressure_->addPressureAcceleration(s, dt);
}

double Simulation::stableDeltaT() const {
    const auto& s = system_;
    const double h = s.physics.supportRadius;
    const auto& v = s.fluid.velocity();
    const auto& a = s.fluid.acceleration();
    const double vMax = std::sqrt(parallelMax(v.size(), [&](std::size_t i) { return v[i].squaredNorm(); }));
    const double aMax = std::sqrt(parallelMax(a.size(), [&](std::size_t i) { return a[i].squaredNorm(); }));
    const double c0 = pressure_->soundSpeed();
    double dt = std::numeric_limits<double>::infinity();
    if (c0 + vMax > 0) dt = time_->maxCo() * h / (c0 + vMax);
    if (aMax > 0) dt = std::min(dt, 0.25 * std::sqrt(h / aMax));
    double nu = viscosity_ ? viscosity_->timeStepViscosity() : 0.0;
    for (const auto& f : forces_) nu = std::max(nu, double(f->timeStepViscosity()));
    if (nu > 0) dt = std::min(dt, 0.125 * h * h / nu);
    return dt;
}

void Simulation::checkState() const {
    const auto& x = system_.fluid.position();
    const auto& v = system_.fluid.velocity();
    const Vec3 lo = blowUpMin_, hi = blowUpMax_;
    const int dim = system_.physics.dimension;
    for (std::size_t i = 0; i < x.size(); ++i) {
        bool bad = !x[i].allFinite() || !v[i].allFinite();
        for (int a = 0; a < dim && !bad; ++a)
            bad = !periodic_.axis[a] && (x[i][a] < lo[a] || x[i][a] > hi[a]);
        if (bad) {
            std::ostringstream s;
            s << "blow-up at step " << system_.step << ", time " << system_.time << ": particle "
              << system_.fluid.id()[i] << " at (" << x[i].transpose() << ") with velocity ("
              << v[i].transpose() << ") is " << (x[i].allFinite() ? "far outside the domain" : "not finite")
              << "; try a smaller deltaT or maxCo";
            throw std::runtime_error(s.str());
        }
    }
}

void Simulation::write() {
    const ParticleSet* wall = nullptr;
    if (system_.hasBoundary() && !boundaryWritten_) {
        wall = &system_.boundary;
        boundaryWritten_ = true;
    }
    writer_->write(system_.time, system_.fluid, wall, writeFields_);
    ++writes_;
}

void Simulation::writeInitialState() {
    writer_->rebuildCollection();
    evaluate(Scalar(time_->initialDeltaT()));
    write();
}

RunSummary Simulation::run() {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto& s = system_;
    RunSummary summary;
    summary.fluidParticles = s.fluid.size();
    summary.boundaryParticles = s.boundary.size();

    writer_->rebuildCollection();
    evaluate(Scalar(time_->initialDeltaT()));
    if (!restarted_) write();

    const double startTime = s.time;
    long iterations = 0, iterativeSteps = 0;
    log::info("\nStarting time loop\n");
    while (!time_->finished(s.time)) {
        if (sortEvery_ > 0 && s.step % sortEvery_ == 0) s.fluid.permute(s.search.sortOrder(s.fluid.position()));
        const double dt = time_->nextDeltaT(s.time, stableDeltaT());
        integrator_->step(s, Scalar(dt), [&] { evaluate(Scalar(dt)); });
        s.time += dt;
        ++s.step;
        if (periodic_.any()) {
            auto& x = s.fluid.position();
#pragma omp parallel for schedule(static)
            for (std::size_t i = 0; i < x.size(); ++i) periodic_.wrap(x[i]);
        }
        checkState();

        const DensityError err = densityError(s);
        summary.maxDensityError = std::max(summary.maxDensityError, err.max);
        const auto& v = s.fluid.velocity();
        const double vMax = std::sqrt(parallelMax(v.size(), [&](std::size_t i) { return v[i].squaredNorm(); }));
        std::ostringstream line;
        line << "Time = " << std::setprecision(6) << s.time << "  step " << s.step << "  deltaT "
             << std::setprecision(3) << dt << "  maxU " << vMax << "  rhoErr max " << 100 * err.max
             << "% avg " << 100 * err.avg << "%";
        if (pressure_->isIterative()) {
            const SolverStats st = pressure_->lastSolve();
            iterations += st.iterations;
            ++iterativeSteps;
            line << "  iterations " << st.iterations << (st.converged ? "" : " (not converged: maxIterations reached)");
            solverPerformance_->writeRow(s.time, {double(st.iterations), st.converged ? 1.0 : 0.0,
                                                  st.maxDensityError, st.avgDensityError});
        }
        log::info(line.str());

        const bool writeTime = time_->writeDue(s.time, s.step);
        if (writeTime) write();
        for (auto& f : functions_) f->execute(s, writeTime);
        if (log::stdoutIsTerminal()) {
            const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
            const double done = (s.time - startTime) / (time_->endTime() - startTime);
            std::ostringstream p;
            p << "[" << std::fixed << std::setprecision(1) << 100 * done << "%] t = " << std::setprecision(4)
              << s.time << " / " << time_->endTime() << "  ETA " << formatDuration(elapsed * (1 - done) / std::max(done, 1e-9));
            log::progress(p.str());
        }
    }
    log::clearProgress();
    for (auto& f : functions_) f->end(s);
    summary.steps = s.step;
    summary.endTime = s.time;
    summary.writes = writes_;
    summary.wallSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    summary.averageIterations = iterativeSteps ? double(iterations) / iterativeSteps : 0.0;
    return summary;
}

} // namespace spindrift
