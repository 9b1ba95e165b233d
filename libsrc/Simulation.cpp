#include "Simulation.hpp"

#include "Geometry.hpp"
#include "Log.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <limits>
#include <optional>
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
    double min = 0, max = 0, avg = 0;
};

// The density error e_i = (ρ_i − ρ0)/ρ0, signed (> 0 compressed; a free surface with a summed
// density shows as a negative minimum): its min, max and average over the fluid. One definition
// for the step line's "rhoErr min/max/avg" (in %), fieldStats' rhoErrMin/Max/Avg columns (in %)
// and the End line's "max density error" (the largest max of the run).
DensityError densityError(const Scene& s) {
    const auto& rho = s.fluid.density();
    const double rho0 = s.physics.rho0;
    const std::size_t n = rho.size();
    if (n == 0) return {};
    DensityError e;
    double lo = (rho[0] - rho0) / rho0, hi = lo;
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
    for (std::size_t i = 1; i < n; ++i) {
        const double ei = (rho[i] - rho0) / rho0;
        lo = std::min(lo, ei);
        hi = std::max(hi, ei);
    }
    e.min = lo;
    e.max = hi;
    e.avg = deterministicSum(n, [&](std::size_t i) { return (rho[i] - rho0) / rho0; }) / n;
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

Simulation::Simulation(const fs::path& caseDir, bool forceLargeCase)
    : case_(Case::read(caseDir)), forceLargeCase_(forceLargeCase) {
    auto& registry = ModelRegistry::instance();
    const Dictionary& control = case_.controlDict;
    time_ = std::make_unique<TimeControl>(control);
    // user plugin libraries
    if (const Entry* libs = control.findEntry("libs")) {
        for (const auto& lib : control.get<std::vector<std::string>>("libs"))
            registry.loadUserLibrary(lib, case_.dir, libs->where);
    }
    const Dictionary* functions = control.findDict("functions");
    readRunControls(control);
    checkWritable();
    // one solver per case: a second one would write into (or remove) the first one's times
    lock_ = std::make_unique<CaseLock>(case_.dir);

    scene_.physics = readPhysicalParameters(case_.fluidProperties);
    const auto& physics = scene_.physics;
    scene_.constants.supportRadius = physics.supportRadius;

    const Dictionary& schemes = case_.sphSchemes;
    auto solutionFor = [&](const std::string& kind) { return case_.sphSolution.findDict(kind); };
    kernel_ = registry.create<Kernel>(schemes.subDict("kernel"), physics);
    scene_.kernel.build(*kernel_);
    pressure_ = registry.create<PressureModel>(schemes.subDict("pressure"), physics, solutionFor("pressure"));
    if (const Dictionary* v = schemes.findDict("viscosity"))
        viscosity_ = registry.create<ViscosityModel>(*v, physics, solutionFor("viscosity"));
    integrator_ = registry.create<Integrator>(schemes.subDict("integrator"), physics);
    if (const Dictionary* forces = schemes.findDict("forces")) {
        for (const auto& name : forces->keywords())
            forces_.push_back(registry.create<ExtraForce>(forces->subDict(name), physics, solutionFor(name),
                                                          case_.dir, name));
    }
    if (const Dictionary* d = schemes.findDict("densityDiffusion"))
        densityDiffusion_ = registry.create<DensityDiffusion>(*d, physics, solutionFor("densityDiffusion"));
    if (const Dictionary* d = schemes.findDict("shifting"))
        shifting_ = registry.create<ShiftingModel>(*d, physics, solutionFor("shifting"));
    if (const Dictionary* ns = schemes.findDict("neighbourSearch")) {
        sortEvery_ = ns->getOrDefault<int>("sortEvery", 10);
        if (sortEvery_ < 0)
            throw InputError(ns->locationOf("sortEvery"), "sortEvery must be 0 (never) or a number of steps", "sortEvery");
        ns->checkAllKeywordsUsed();
    }

    checkParticleEstimate();
    buildParticles();
    resolveConstants();
    applyInitialPressure();

    if (scene_.hasWalls()) {
        if (!schemes.findDict("boundary"))
            throw InputError(schemes.where(), "constant/geometry has walls, so sphSchemes needs a "
                                              "'boundary { type ...; }' entry (e.g. akinci)", "boundary");
        boundaryModel_ = registry.create<BoundaryModel>(schemes.subDict("boundary"), physics);
    }
    schemes.markUsed("boundary");
    checkIntegratorApplies(schemes);
    schemes.markUsed("pressureSolvers"); // the tutorials' menu of solvers, chosen with $pressureSolvers.<name>
    schemes.checkAllKeywordsUsed();
    case_.sphSolution.markUsed("pressure");
    case_.sphSolution.markUsed("viscosity");
    case_.sphSolution.checkAllKeywordsUsed();

    scene_.boundaryModel = boundaryModel_.get();
    if (boundaryModel_) boundaryModel_->initialise(scene_);
    pressure_->initialise(scene_);
    if (densityDiffusion_) {
        // it acts on a density the integrator advances (continuity), never on a summed one
        const bool integrated = std::any_of(scene_.integratedFields.begin(), scene_.integratedFields.end(),
                                            [&](const IntegratedField& f) { return f.value == &scene_.fluid.density(); });
        if (integrated) {
            densityDiffusion_->initialise(scene_);
            scene_.densityDiffusion = densityDiffusion_.get();
        } else {
            // a tutorial's one-word swap of the pressure solver keeps its densityDiffusion entry
            log::warning("densityDiffusion " + schemes.subDict("densityDiffusion").get<std::string>("type") +
                         " is not used: the pressure model sums its density from the positions; the term acts "
                         "on a density integrated in time (wcsph or isobaric with 'density continuity;')");
            densityDiffusion_.reset();
        }
    }
    if (shifting_) {
        scene_.shiftingVelocity = &scene_.fluid.addVector("shiftingVelocity", {false, true});
        shifting_->initialise(scene_);
    }
    if (viscosity_) viscosity_->initialise(scene_);
    for (auto& f : forces_) f->initialise(scene_);
    integrator_->initialise(scene_);
    if (functions) {
        for (const auto& name : functions->keywords())
            functions_.push_back(registry.create<FunctionObject>(functions->subDict(name), physics, nullptr,
                                                                 case_.dir, name));
    }

    checkWriteFields();
    writer_ = std::make_unique<CaseWriter>(case_.dir, time_->timePrecision());
    restarted_ = time_->startFromLatest() && restartFromLatest();
    if (!restarted_) scene_.time = time_->startTime();
    time_->begin(scene_.time, lastDeltaT_);
    if (restarted_) integrator_->restarted(scene_);
    if (pressure_->isIterative())
        solverPerformance_ = std::make_unique<PostProcessingFile>(
            case_.dir, "solverPerformance", scene_.time,
            std::vector<PostProcessingColumn>{
                {"iterations", "-"}, {"converged", "-"}, {"maxDensityError", "%"}, {"avgDensityError", "%"}});
}

Simulation::~Simulation() = default;

namespace {
// A /proc/meminfo entry in bytes (0 when unknown).
double meminfoBytes(const std::string& key) {
    std::ifstream in("/proc/meminfo");
    for (std::string name; in >> name;) {
        double kib = 0;
        in >> kib;
        if (name == key + ":") return kib * 1024;
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return 0;
}

std::string gib(double bytes) {
    std::ostringstream s;
    s << std::setprecision(3) << bytes / (1024.0 * 1024 * 1024) << " GiB";
    return s.str();
}
} // namespace

void Simulation::checkParticleEstimate() const {
    const auto& physics = scene_.physics;
    const ParticleEstimate e = estimateParticleCount(case_.geometry, physics.particleSpacing, physics.dimension);
    const double count = e.count;
    // bytes per particle: its fields, the sampling's copies and the neighbour lists; measured
    // (peak memory less that of a small run): 0.6 kB running damBreak2D at 81,000 particles,
    // 0.45 kB setting up damBreak3D (mostly wall particles). 400 B is below both, so a case that
    // fits is not refused.
    const double perParticle = 400;
    const double bytes = count * perParticle;
    std::ostringstream estimate;
    estimate << std::setprecision(3) << "about " << count << " particles at particleSpacing " << physics.particleSpacing
             << " in " << physics.dimension << "D (" << e.largest << " in " << e.largestName << ")";
    // the entry that makes the most particles (a huge box, `layers 1e9`), or the spacing itself
    const std::string keyword = e.largestName.substr(e.largestName.find('.') + 1);
    const SourceLocation where = e.largestAt;
    const double available = meminfoBytes("MemAvailable");
    if (available > 0 && bytes > available) {
        const std::string message = "the geometry makes " + estimate.str() + ", needing about " + gib(bytes) +
                                    "; this machine has " + gib(available) + " available (" +
                                    gib(meminfoBytes("MemTotal")) + " in all)";
        if (!forceLargeCase_)
            throw InputError(where, message + ": use a larger particleSpacing or a smaller geometry (or -force)",
                             keyword);
        log::warning(message + "; running anyway (-force)");
    }
    if (count > double(std::numeric_limits<Index>::max()))
        throw InputError(where, "the geometry makes " + estimate.str() + ", more than the " +
                                    std::to_string(std::numeric_limits<Index>::max()) +
                                    " a particle index can number; use a larger particleSpacing or a smaller geometry",
                         keyword);
}

void Simulation::buildParticles() {
    const auto& physics = scene_.physics;
    const SampledGeometry g = sampleGeometry(case_.geometry, physics.particleSpacing, physics.dimension, physics.gravity);
    auto& fluid = scene_.fluid;
    fluid.resize(g.fluidPositions.size());
    fluid.setParticleMass(latticeParticleMass(scene_.kernel, physics));
    for (std::size_t i = 0; i < g.fluidPositions.size(); ++i) {
        fluid.position()[i] = g.fluidPositions[i];
        fluid.velocity()[i] = g.fluidVelocities[i];
        fluid.density()[i] = physics.rho0;
        fluid.id()[i] = Index(i);
    }
    initialDepths_ = g.fluidDepths;
    // Each wall entry is a wall system; the vector is not resized after this (the search keeps
    // pointers to the walls' positions).
    scene_.walls.clear();
    scene_.walls.reserve(g.walls.size());
    Vec3 sweptLo = g.boundsMin, sweptHi = g.boundsMax; // moving walls: where they go during the run
    for (const SampledWall& sampled : g.walls) {
        WallSystem& w = scene_.walls.emplace_back(sampled.name);
        auto& set = w.particles;
        set.resize(sampled.positions.size());
        for (std::size_t i = 0; i < sampled.positions.size(); ++i) {
            set.position()[i] = sampled.positions[i];
            set.density()[i] = physics.rho0;
            set.id()[i] = Index(i);
        }
        if (sampled.motion) {
            w.motion = Motion::read(*sampled.motion, physics.dimension);
            Vec3 lo, hi;
            w.motion->sweptRange(time_->startTime(), time_->endTime(), lo, hi);
            Vec3 wallLo = Vec3::Constant(std::numeric_limits<Scalar>::max()), wallHi = -wallLo;
            for (const Vec3& p : sampled.positions) {
                wallLo = wallLo.cwiseMin(p);
                wallHi = wallHi.cwiseMax(p);
            }
            sweptLo = sweptLo.cwiseMin(wallLo + lo);
            sweptHi = sweptHi.cwiseMax(wallHi + hi);
            log::info("Wall '" + sampled.name + "' moves: " + w.motion->describe());
        }
    }
    if (physics.dimension == 2) sweptLo[2] = sweptHi[2] = 0;
    // Neighbour grid over the sampled bounds (and the moving walls' sweep) with a generous
    // margin (particles beyond it are clamped into border cells: correct, only slower).
    const Vec3 extent = sweptHi - sweptLo;
    const Scalar margin = 2 * physics.supportRadius;
    domainMin_ = sweptLo - Vec3::Constant(margin) - Scalar(0.25) * extent;
    domainMax_ = sweptHi + Vec3::Constant(margin) + Scalar(0.25) * extent;
    periodic_ = g.periodic;
    if (physics.dimension == 2) domainMin_[2] = domainMax_[2] = 0;
    // A particle beyond one more extent (and 10 h) from everything sampled has blown up.
    const Vec3 reach = extent.cwiseMax(Vec3::Constant(10 * physics.supportRadius));
    blowUpMin_ = sweptLo - reach;
    blowUpMax_ = sweptHi + reach;
    // ... or moves 100 times faster than a free fall across the domain could make it
    blowUpSpeedFloor_ = 100 * std::sqrt(2 * physics.gravity.norm() * extent.norm());
    scene_.search.setup(scene_.constants.supportRadius, physics.dimension, domainMin_, domainMax_, periodic_);
    std::vector<NeighbourSearch::WallSource> sources;
    for (WallSystem& w : scene_.walls) {
        w.particles.permute(scene_.search.sortOrder(w.particles.position())); // cache order
        if (w.moving()) w.initialPosition = w.particles.position();
        sources.push_back({&w.particles.position(), w.moving()});
    }
    scene_.search.setWalls(sources);
    // the fluid's initial extent along gravity, for the equation of state's default sound speed
    const Scalar gNorm = physics.gravity.norm();
    if (gNorm > 0 && fluid.size() > 0) {
        const Vec3 up = -physics.gravity / gNorm;
        Scalar lo = std::numeric_limits<Scalar>::max(), hi = -lo;
        for (const auto& x : fluid.position()) {
            lo = std::min(lo, x.dot(up));
            hi = std::max(hi, x.dot(up));
        }
        scene_.constants.fluidHeight = hi - lo + physics.particleSpacing;
    }
}

void Simulation::resolveConstants() {
    SceneConstants& c = scene_.constants;
    c.particleMass = scene_.fluid.particleMass();
    c.rho0 = scene_.physics.rho0;
    c.soundSpeed = pressure_->soundSpeed(c, scene_.physics);
    c.eosExponent = pressure_->eosExponent();
    if (!(c.soundSpeed >= 0) || !std::isfinite(c.soundSpeed))
        throw std::logic_error("the pressure model declared a sound speed that is not a finite non-negative number");
}

void Simulation::applyInitialPressure() {
    auto& fluid = scene_.fluid;
    const Scalar rhoG = scene_.physics.rho0 * scene_.physics.gravity.norm();
    for (std::size_t i = 0; i < fluid.size(); ++i) {
        const Scalar p = rhoG * initialDepths_[i];
        fluid.pressure()[i] = p;
        fluid.density()[i] = scene_.constants.densityAt(p);
    }
}

void Simulation::checkIntegratorApplies(const Dictionary& schemes) const {
    const auto describe = [](ResultKind k) {
        return k == ResultKind::velocityChange ? "a change of velocity (dv, added as dv/dt)"
                                               : "a change of position (dx, added as dx/dt^2)";
    };
    const std::string integrator = schemes.subDict("integrator").get<std::string>("type");
    const auto check = [&](const char* slot, const std::string& type, ResultKind kind) {
        if (integrator_->applies(kind)) return;
        throw InputError(schemes.subDict("integrator").locationOf("type"),
                         std::string(slot) + " '" + type + "' returns " + describe(kind) + ", which integrator '" +
                             integrator + "' cannot apply exactly; use 'integrator { type symplecticEuler; }' " +
                             "(the scheme " + type + " is formulated with)",
                         "type");
    };
    check("pressure", schemes.subDict("pressure").get<std::string>("type"), pressure_->result());
    if (viscosity_) check("viscosity", schemes.subDict("viscosity").get<std::string>("type"), viscosity_->result());
    if (const Dictionary* forces = schemes.findDict("forces"))
        for (std::size_t k = 0; k < forces_.size(); ++k)
            check("force", forces->subDict(forces->keywords()[k]).get<std::string>("type"), forces_[k]->result());
}

void Simulation::placeMovingWalls(double time) {
    for (WallSystem& w : scene_.walls) {
        if (!w.moving()) continue;
        const Vec3 d = w.motion->displacement(time), v = w.motion->velocity(time), a = w.motion->acceleration(time);
        auto& x = w.particles.position();
        const std::size_t n = x.size();
#pragma omp parallel for schedule(static)
        for (std::size_t b = 0; b < n; ++b) x[b] = w.initialPosition[b] + d;
        std::fill(w.particles.velocity().begin(), w.particles.velocity().end(), v);
        std::fill(w.particles.acceleration().begin(), w.particles.acceleration().end(), a);
    }
}

void Simulation::readRunControls(const Dictionary& control) {
    writeFields_ = control.getOrDefault<std::vector<std::string>>("writeFields", {});
    reduceDeltaTOnBlowUp_ = control.getWordOrDefault("onBlowUp", {"stop", "reduceDeltaT"}, "stop") == "reduceDeltaT";
    blowUpRetries_ = control.getOrDefault<int>("blowUpRetries", 5);
    if (blowUpRetries_ < 0)
        throw InputError(control.locationOf("blowUpRetries"), "blowUpRetries must be 0 or more", "blowUpRetries");
    blowUpDensityError_ = control.getOrDefault<double>("blowUpDensityError", 0.2);
    blowUpSpeedSetting_ = control.found("blowUpSpeed") ? control.get<double>("blowUpSpeed") : 0.0; // 0: automatic
    blowUpSpeed_ = blowUpSpeedSetting_ > 0 ? blowUpSpeedSetting_ : blowUpSpeedAuto_;
    if (!(blowUpDensityError_ > 0))
        throw InputError(control.locationOf("blowUpDensityError"), "blowUpDensityError must be positive",
                         "blowUpDensityError");
    logInterval_ = control.found("logInterval") ? control.get<int>("logInterval") : 0; // 0: automatic (run())
    if (control.found("logInterval") && logInterval_ < 1)
        throw InputError(control.locationOf("logInterval"),
                         "logInterval must be a whole number of steps, at least 1 (leave it out for the "
                         "automatic interval)",
                         "logInterval");
    runTimeModifiable_ = control.getOrDefault<bool>("runTimeModifiable", true);
    // a case written for another solver, or a stop this solver does not implement, is not run
    // as if it were right
    control.getWordOrDefault("application", {"spindrift"}, "spindrift");
    control.getWordOrDefault("stopAt", {"endTime"}, "endTime");
    control.markUsed("libs");
    control.markUsed("functions");
    control.checkAllKeywordsUsed();
    std::error_code ec;
    controlDictTime_ = fs::last_write_time(case_.dir / "system/controlDict", ec);
}

void Simulation::rereadControlDictIfChanged() {
    if (!runTimeModifiable_) return;
    std::error_code ec;
    const fs::path file = case_.dir / "system/controlDict";
    const auto stamp = fs::last_write_time(file, ec);
    if (ec || stamp == controlDictTime_) return;
    controlDictTime_ = stamp;
    try {
        Dictionary control = Dictionary::fromFile(file);
        TimeControl updated(control);
        const std::vector<std::string> fields = writeFields_;
        try {
            readRunControls(control);
            checkWriteFields();
        } catch (const InputError&) {
            writeFields_ = fields;
            throw;
        }
        const double previous = time_->previousDeltaT();
        *time_ = updated;
        time_->setPreviousDeltaT(previous);
        time_->scheduleNextWrite(scene_.time);
        case_.controlDict = std::move(control);
        log::info("Re-read system/controlDict (endTime " + std::to_string(time_->endTime()) + ")");
    } catch (const InputError& e) {
        log::warning(std::string("system/controlDict changed but cannot be used, keeping the previous settings: ") +
                     e.what());
    }
}

void Simulation::checkWritable() const {
    const fs::path probe = case_.dir / ".spindrift-write-test";
    std::ofstream out(probe);
    if (!out || !(out << "x").flush())
        throw InputError({case_.dir.string(), 0, 0}, "case directory '" + case_.dir.string() +
                                                         "' is not writable (results go there)");
    out.close();
    std::error_code ec;
    fs::remove(probe, ec);
}

void Simulation::checkWriteFields() const {
    std::vector<std::string> known{"id"};
    const auto add = [&](const ParticleSet& set) {
        for (const auto& f : set.scalarFields()) known.push_back(f->name);
        for (const auto& f : set.vectorFields()) known.push_back(f->name);
    };
    add(scene_.fluid);
    for (const auto& w : scene_.walls) add(w.particles);
    for (const auto& name : writeFields_)
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            std::sort(known.begin(), known.end());
            known.erase(std::unique(known.begin(), known.end()), known.end());
            std::string list, closest = closestMatch(name, known);
            for (const auto& k : known) list += (list.empty() ? "" : " ") + k;
            throw InputError(case_.controlDict.locationOf("writeFields"),
                             "unknown field '" + name + "' in writeFields; fields: (" + list + ")" +
                                 (closest.empty() ? "" : "; did you mean '" + closest + "'?"),
                             "writeFields");
        }
}

std::string Simulation::timeFile() const {
    std::ostringstream s;
    s << std::setprecision(17) << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
      << "    class       dictionary;\n    object      time;\n}\n\n"
      << "value       " << scene_.time << ";\n"
      << "index       " << scene_.step << ";\n"
      << "deltaT      " << lastDeltaT_ << ";\n";
    if (std::isfinite(deltaTCap_))
        s << "blowUpDeltaTCap " << deltaTCap_ << ";\n"
          << "blowUpHoldSteps " << deltaTHoldSteps_ << ";\n";
    return s.str();
}

namespace {
// Why a saved time cannot be restarted from (empty: it can): its fluid.vtp unreadable, empty or
// holding a value that is not finite (a blow-up saved as if it were a state), its uniform/time
// (exact time, step index, last Δt) missing, unreadable or of another time than its name.
std::string unusableForRestart(const fs::path& dir, std::optional<ParticleSet>& saved,
                               std::optional<Dictionary>& time) {
    try {
        saved.emplace(readVtp(dir / "fluid.vtp"));
    } catch (const std::exception& e) {
        return e.what();
    }
    if (saved->size() == 0) return "fluid.vtp holds no particles";
    const auto notFinite = [&](const std::string& field, std::size_t i) {
        return "fluid.vtp: " + field + " of particle " + std::to_string(saved->id()[i]) + " is not finite";
    };
    for (std::size_t i = 0; i < saved->size(); ++i)
        if (!saved->position()[i].allFinite()) return notFinite("position", i);
    for (const auto& f : saved->scalarFields())
        for (std::size_t i = 0; i < f->data.size(); ++i)
            if (!std::isfinite(f->data[i])) return notFinite(f->name, i);
    for (const auto& f : saved->vectorFields())
        for (std::size_t i = 0; i < f->data.size(); ++i)
            if (!f->data[i].allFinite()) return notFinite(f->name, i);
    const fs::path file = dir / "uniform/time";
    if (!fs::exists(file)) return "uniform/time (its step index) is missing";
    try {
        time.emplace(Dictionary::fromFile(file));
        const double value = time->get<double>("value");
        time->get<long>("index");
        time->get<double>("deltaT");
        // the name at some precision (timePrecision may have changed since it was written)
        bool named = false;
        for (int digits = 1; digits <= 17 && std::isfinite(value); ++digits)
            named = named || CaseWriter::timeName(value, digits) == dir.filename().string();
        if (!named)
            return "uniform/time holds the time " + std::to_string(value) + ", not " + dir.filename().string();
    } catch (const std::exception& e) {
        return e.what();
    }
    return {};
}
} // namespace

bool Simulation::restartFromLatest() {
    const auto times = writer_->existingTimes();
    if (times.empty()) {
        log::warning("startFrom latestTime: no time directory in " + case_.dir.string() +
                     "; starting from startTime");
        return false;
    }
    // the newest usable time; a newer one that is not is skipped with a warning (never restarted
    // from as if it were good, never with its step index reset)
    std::optional<ParticleSet> saved;
    std::optional<Dictionary> timeDict;
    std::string name, firstProblem;
    for (auto it = times.rbegin(); it != times.rend(); ++it) {
        saved.reset();
        timeDict.reset();
        const std::string problem = unusableForRestart(case_.dir / it->second, saved, timeDict);
        if (problem.empty()) {
            name = it->second;
            break;
        }
        if (firstProblem.empty()) firstProblem = "time " + it->second + ": " + problem;
        log::warning("startFrom latestTime: cannot restart from time " + it->second + " (" + problem +
                     "); trying the time before");
    }
    if (name.empty())
        throw InputError(case_.controlDict.locationOf("startFrom"),
                         "no time directory to restart from (" + firstProblem +
                             "); use 'startFrom startTime;' or repair the time",
                         "startFrom");
    auto& fluid = scene_.fluid;
    fluid.resize(saved->size());
    fluid.id() = saved->id();
    for (const auto& f : saved->scalarFields())
        if (auto* mine = fluid.findScalar(f->name)) *mine = f->data;
    for (const auto& f : saved->vectorFields())
        if (auto* mine = fluid.findVector(f->name)) *mine = f->data;
    fluid.position() = saved->position();
    // exact time, step index and last Δt
    scene_.time = timeDict->get<double>("value");
    scene_.step = timeDict->get<long>("index");
    lastDeltaT_ = timeDict->get<double>("deltaT");
    // a blow-up retry's cap still in force at that time (absent: none)
    deltaTCap_ = timeDict->getOrDefault<double>("blowUpDeltaTCap", std::numeric_limits<double>::infinity());
    deltaTHoldSteps_ = timeDict->getOrDefault<int>("blowUpHoldSteps", 0);
    if (!(deltaTCap_ > 0)) deltaTCap_ = std::numeric_limits<double>::infinity();
    staticWallsWritten_ = true; // fixed walls were written at the first time
    log::info("Restarting from time " + name + " (step " + std::to_string(scene_.step) + ", " +
              std::to_string(saved->size()) + " particles)");
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
    if (densityDiffusion_) s << ", densityDiffusion " << type("densityDiffusion");
    if (shifting_) s << ", shifting " << type("shifting");
    if (const Dictionary* forces = case_.sphSchemes.findDict("forces"))
        for (const auto& name : forces->keywords()) s << ", force " << forces->subDict(name).get<std::string>("type");
    return s.str();
}

void Simulation::evaluate(double time, Scalar dt) {
    auto& s = scene_;
    placeMovingWalls(time);
    // a search a model made ahead at exactly these positions (dfsph's check) is kept, unless a
    // wall has moved since
    if (!s.search.builtAt(s.fluid.position()) || s.anyMovingWall()) s.search.build(s.fluid.position());
    pressure_->computeDensity(s);
    if (boundaryModel_) boundaryModel_->update(s);
    auto& a = s.fluid.acceleration();
    const Vec3 g = s.physics.gravity;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = g;
    if (viscosity_) viscosity_->addAcceleration(s, dt);
    for (auto& f : forces_) f->addAcceleration(s, dt);
    pressure_->addPressureAcceleration(s, dt);
    if (shifting_) shifting_->computeShift(s, dt);
}

double Simulation::stableDeltaT() const {
    const auto& s = scene_;
    const double h = s.physics.supportRadius;
    const auto& v = s.fluid.velocity();
    const auto& a = s.fluid.acceleration();
    double vMax = std::sqrt(parallelMax(v.size(), [&](std::size_t i) { return v[i].squaredNorm(); }));
    const double aMax = std::sqrt(parallelMax(a.size(), [&](std::size_t i) { return a[i].squaredNorm(); }));
    for (const auto& w : s.walls) // a moving wall's speed over the step (it is uniform over the wall)
        if (w.moving()) vMax = std::max(vMax, double(w.motion->velocity(s.time).norm()));
    const double c0 = s.constants.soundSpeed;
    double dt = std::numeric_limits<double>::infinity();
    if (c0 + vMax > 0) dt = time_->maxCo() * h / (c0 + vMax);
    if (aMax > 0) dt = std::min(dt, 0.25 * std::sqrt(h / aMax));
    double nu = viscosity_ ? viscosity_->timeStepViscosity() : 0.0;
    for (const auto& f : forces_) nu = std::max(nu, double(f->timeStepViscosity()));
    // Morris et al. (1997): 0.125 h_s²/ν on the smoothing length h_s = h/2 (on the support
    // radius itself the limit is 4 times too large: Poiseuille flow blows up)
    if (nu > 0) dt = std::min(dt, 0.125 * 0.25 * h * h / nu);
    return dt;
}

std::string Simulation::findBlowUp(bool& densityOnly) const {
    const auto& f = scene_.fluid;
    const auto& x = f.position();
    const auto& v = f.velocity();
    const auto& rho = f.density();
    const auto& p = f.pressure();
    const auto& a = f.acceleration();
    const int dim = scene_.physics.dimension;
    const double rho0 = scene_.physics.rho0;
    // worst particle: not finite > far outside > largest density error
    long worst = -1;
    int worstKind = 0; // 3 not finite, 2 outside, 1 density
    double worstDensity = blowUpDensityError_;
    // a parallel look first (every step); the serial search for the worst particle only after
    // a blow-up
    // (without branches: a value not finite makes the sum's s − s NaN, which fails == 0)
    int any = 0;
    const double speed2 = blowUpSpeed_ * blowUpSpeed_;
    bool bounded[3];
    for (int d = 0; d < 3; ++d) bounded[d] = d < dim && !periodic_.axis[d];
#pragma omp parallel for schedule(static) reduction(| : any)
    for (std::size_t i = 0; i < x.size(); ++i) {
        const Scalar sum = x[i].sum() + v[i].sum() + a[i].sum() + rho[i] + p[i];
        int bad = int(!(sum - sum == 0)) | int(v[i].squaredNorm() > speed2) | int((rho[i] - rho0) / rho0 > worstDensity);
        for (int d = 0; d < 3; ++d) bad |= int(bounded[d]) & (int(x[i][d] < blowUpMin_[d]) | int(x[i][d] > blowUpMax_[d]));
        any |= bad;
    }
    densityOnly = false;
    if (!any) return {};
    for (std::size_t i = 0; i < x.size(); ++i) {
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
      << f.id()[i] << " at (" << x[i].transpose() << ") with velocity (" << v[i].transpose() << ") ";
    if (worstKind == 3) s << "has a value that is not finite (density " << rho[i] << ", pressure " << p[i] << ")";
    else if (worstKind == 2 && v[i].norm() > blowUpSpeed_) s << "moves faster than " << blowUpSpeed_ << " m/s";
    else if (worstKind == 2) s << "is far outside the domain";
    else s << "has a density error of " << 100 * worstDensity << "% (blowUpDensityError " << 100 * blowUpDensityError_ << "%)";
    return s.str();
}

void Simulation::write() {
    // fixed walls once (later times refer to them), moving walls at every written time; a wall
    // whose boundary model mirrors the fluid's pressure has no pressure nor density of its own
    // (the arrays hold nothing meaningful): they are left out rather than written as 0
    std::vector<const ParticleSet*> walls;
    for (auto& w : scene_.walls) {
        if (w.pressureMirrored) {
            w.particles.setUndefined("pressure");
            w.particles.setUndefined("density");
        }
        if (w.moving() || !staticWallsWritten_) walls.push_back(&w.particles);
    }
    staticWallsWritten_ = true;
    writer_->write(scene_.time, scene_.fluid, walls, writeFields_, {{"uniform/time", timeFile()}});
    ++writes_;
}

void Simulation::writeInitialState() {
    evaluate(scene_.time, Scalar(time_->initialDeltaT()));
    startFunctionObjects();
    writer_->rebuildCollection();
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

// The automatic logInterval: every step for a run of up to 250 steps; a longer one gets the
// smallest of 1, 2, 5, 10, 20, 50, ... steps that keeps it to at most 250 step lines (a
// 10,000-step run logs every 50th step: 200 lines).
long automaticLogInterval(double estimatedSteps) {
    constexpr double lines = 250;
    estimatedSteps = std::min(estimatedSteps, 1e15); // also for a step size that is not finite
    for (long decade = 1;; decade *= 10)
        for (long mantissa : {1, 2, 5})
            if (double(mantissa * decade) * lines >= estimatedSteps) return mantissa * decade;
}

// The wall-clock time of day, hh:mm:ss.
std::string clockTime() {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char text[16];
    std::strftime(text, sizeof text, "%H:%M:%S", &local);
    return text;
}
} // namespace

void stopAtOnceOnSignalsDuringSetUp() { installStopHandler(onStopSignalDuringSetUp, SA_RESETHAND | SA_NODEFER); }

RunSummary Simulation::run() {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    StopSignals signals;
    auto& s = scene_;
    RunSummary summary;
    summary.fluidParticles = s.fluid.size();
    summary.wallParticles = s.wallParticles();

    const double startTime = s.time;
    const long startStep = s.step;
    const auto wallSeconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const auto fractionDone = [&] { return (s.time - startTime) / (time_->endTime() - startTime); };
    // the wall time still to go, from the simulated time still to go at the pace so far
    const auto eta = [&] {
        const double done = fractionDone();
        return formatDuration(wallSeconds() * (1 - done) / std::max(done, 1e-9));
    };
    double lastWritten = restarted_ ? s.time : std::numeric_limits<double>::quiet_NaN();
    const auto writeAndLog = [&] {
        write();
        lastWritten = s.time;
        std::ostringstream o;
        o << "Wrote time " << CaseWriter::timeName(s.time) << " (step " << s.step << ") at " << clockTime() << ", "
          << formatDuration(wallSeconds()) << " wall";
        if (s.time > startTime && !time_->finished(s.time)) o << ", ETA " << eta();
        log::info(o.str());
    };
    // the fatal-signal message names the last completed step
    const auto setFatalSignalContext = [&] {
        char text[160];
        std::snprintf(text, sizeof text, "at step %ld, time %.6g (last completed step)", s.step, s.time);
        log::setFatalSignalContext(text);
    };

    if (!restarted_) evaluate(s.time, Scalar(time_->initialDeltaT()));
    startFunctionObjects(); // before anything is written, on the state the start time's directory holds
    writer_->rebuildCollection();
    if (!restarted_) writeAndLog();
    setFatalSignalContext();
    {
        double vMax0 = 0;
        for (const auto& v : s.fluid.velocity()) vMax0 = std::max(vMax0, double(v.norm()));
        for (const auto& w : s.walls)
            if (w.moving()) vMax0 = std::max(vMax0, double(w.motion->velocity(s.time).norm()));
        blowUpSpeedAuto_ = std::max({blowUpSpeedFloor_, 100 * double(s.constants.soundSpeed), 100 * vMax0, 1.0});
        blowUpSpeed_ = blowUpSpeedSetting_ > 0 ? blowUpSpeedSetting_ : blowUpSpeedAuto_;
    }

    long iterations = 0, iterativeSteps = 0;
    // The states before the last two steps. A density error shows in the evaluation of the
    // step after the one that caused it, so such a blow-up rolls back two steps.
    struct Snapshot {
        ParticleSet fluid;
        double time = 0, lastDeltaT = 0, dtTaken = 0, deltaTCap = 0;
        long step = 0;
        int holdSteps = 0;
        bool valid = false;
    };
    Snapshot previous{ParticleSet(s.fluid.name())}, last{ParticleSet(s.fluid.name())};
    int retries = 0, stepsSinceRetry = 0;
    bool keepPrevious = false; // after going back one step, 'previous' is still the step before
    // Step lines: every logInterval-th step (automatic: from the number of steps the run is
    // estimated to take), and always the first and the last step of the run, the steps after a
    // retry, those whose pressure solver did not converge and the step a signal stops at.
    double typicalDeltaT = 0; // moving average: landing on a write time shortens a step or two
    bool logNextStep = true;
    log::info("\nStarting time loop\n");
    while (!time_->finished(s.time)) {
        if (sortEvery_ > 0 && s.step % sortEvery_ == 0) resortFluid(s);
        bool capped = false;
        const double dt = time_->nextDeltaT(s.time, stableDeltaT(), deltaTCap_, &capped);
        if (!keepPrevious) std::swap(previous, last);
        keepPrevious = false;
        last.fluid.copyDataFrom(s.fluid);
        last.time = s.time;
        last.step = s.step;
        last.lastDeltaT = lastDeltaT_;
        last.dtTaken = dt;
        last.deltaTCap = deltaTCap_;
        last.holdSteps = deltaTHoldSteps_;
        last.valid = true;

        integrator_->step(s, Scalar(dt), [&](double t) { evaluate(t, Scalar(dt)); });
        s.time = last.time + dt;
        ++s.step;
        if (periodic_.any()) {
            auto& x = s.fluid.position();
#pragma omp parallel for schedule(static)
            for (std::size_t i = 0; i < x.size(); ++i) periodic_.wrap(x[i]);
        }
        bool densityBlowUp = false;
        const std::string blowUp = findBlowUp(densityBlowUp);
        if (!blowUp.empty()) {
            const bool twoBack = densityBlowUp && previous.valid;
            Snapshot& good = twoBack ? previous : last;
            s.fluid.copyDataFrom(good.fluid);
            s.time = good.time;
            s.step = good.step;
            lastDeltaT_ = good.lastDeltaT;
            if (twoBack) previous.valid = last.valid = false;
            keepPrevious = !twoBack;
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
                logNextStep = true;
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
                deltaTCap_ *= blowUpCapGrowth;
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
        bool converged = true;
        SolverStats st;
        if (pressure_->isIterative()) {
            st = pressure_->lastSolve();
            converged = st.converged;
            iterations += st.iterations;
            ++iterativeSteps;
            solverPerformance_->writeRow(s.time, {double(st.iterations), st.converged ? 1.0 : 0.0,
                                                  100 * st.maxDensityError, 100 * st.avgDensityError});
        }
        const int signal = pendingSignal.load();
        typicalDeltaT = typicalDeltaT > 0 ? 0.9 * typicalDeltaT + 0.1 * dt : dt;
        const double estimatedSteps =
            double(s.step - startStep) + (time_->endTime() - s.time) / std::max(dt, typicalDeltaT);
        const long interval = logInterval_ > 0 ? logInterval_ : automaticLogInterval(estimatedSteps);
        if (logNextStep || s.step % interval == 0 || time_->finished(s.time) || !converged || signal != 0) {
            logNextStep = false;
            const auto& v = s.fluid.velocity();
            const double vMax = std::sqrt(parallelMax(v.size(), [&](std::size_t i) { return v[i].squaredNorm(); }));
            std::ostringstream line;
            line << "Time = " << std::setprecision(6) << s.time << "  step " << s.step << "  deltaT "
                 << std::setprecision(3) << dt << "  maxU " << vMax << "  rhoErr min " << 100 * err.min << "% max "
                 << 100 * err.max << "% avg " << 100 * err.avg << "%";
            if (pressure_->isIterative())
                line << "  iterations " << st.iterations
                     << (st.converged ? "" : " (not converged: maxIterations reached)");
            log::info(line.str());
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
        if (log::stdoutIsTerminal()) {
            std::ostringstream p;
            p << "[" << std::fixed << std::setprecision(1) << 100 * fractionDone() << "%] t = " << std::setprecision(4)
              << s.time << " / " << time_->endTime() << "  step " << s.step << "  ETA " << eta();
            log::progress(p.str());
        }
    }
    log::clearProgress();
    // the end state, also off the write schedule (else the run's last steps are lost and a
    // restart goes back to the last write time)
    if (!summary.interrupted && s.time != lastWritten) writeAndLog();
    for (auto& f : functions_) f->end(s);
    summary.steps = s.step - startStep;
    summary.endTime = s.time;
    summary.writes = writes_;
    summary.wallSeconds = wallSeconds();
    summary.averageIterations = iterativeSteps ? double(iterations) / iterativeSteps : 0.0;
    return summary;
}

} // namespace spindrift
