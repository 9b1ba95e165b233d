// Spindrift — the set-up of a run (Simulation): the dictionaries read, the models created, the
// particle systems built, the constants resolved, the run controls read, and a restart's state read
// back and checked. The time loop is in TimeLoop.cpp, the run's log lines in RunLog.cpp.
#include "Simulation.hpp"

#include "Geometry.hpp"
#include "Log.hpp"
#include "PairLoop.hpp"
#include "RigidBody.hpp"

#include <algorithm>
#include <fstream>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <sys/resource.h>

namespace fs = std::filesystem;

namespace spindrift {

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

const StepServices& Simulation::services() const { return *services_; }

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
    // the one support radius: the kernel, its table and the neighbour search are built from it
    scene_.constants.supportRadius = physics.supportRadiusFactor * physics.particleSpacing;
    scene_.constants.rho0 = physics.rho0;
    const SceneConstants& constants = scene_.constants;

    const Dictionary& schemes = case_.sphSchemes;
    auto solutionFor = [&](const std::string& kind) { return case_.sphSolution.findDict(kind); };
    kernel_ = registry.create<Kernel>(schemes.subDict("kernel"), physics, constants);
    scene_.kernel.build(*kernel_);
    pressure_ = registry.create<PressureModel>(schemes.subDict("pressure"), physics, constants, solutionFor("pressure"));
    if (const Dictionary* v = schemes.findDict("viscosity"))
        viscosity_ = registry.create<ViscosityModel>(*v, physics, constants, solutionFor("viscosity"));
    integrator_ = registry.create<Integrator>(schemes.subDict("integrator"), physics, constants);
    if (const Dictionary* forces = schemes.findDict("forces")) {
        for (const auto& name : forces->keywords())
            forces_.push_back(registry.create<ExtraForce>(forces->subDict(name), physics, constants, solutionFor(name),
                                                          case_.dir, name));
    }
    if (const Dictionary* d = schemes.findDict("surfaceTension"))
        surfaceTension_ = registry.create<SurfaceTensionModel>(*d, physics, constants, solutionFor("surfaceTension"));
    if (const Dictionary* d = schemes.findDict("densityDiffusion"))
        densityDiffusion_ = registry.create<DensityDiffusion>(*d, physics, constants, solutionFor("densityDiffusion"));
    if (const Dictionary* d = schemes.findDict("shifting"))
        shifting_ = registry.create<ShiftingModel>(*d, physics, constants, solutionFor("shifting"));
    if (const Dictionary* passive = schemes.findDict("passive"))
        for (const auto& name : passive->keywords())
            passive_.push_back(registry.create<PassiveModel>(passive->subDict(name), physics, constants,
                                                             solutionFor(name), case_.dir, name));
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

    if (!scene_.boundaries().empty()) {
        if (!schemes.findDict("boundary"))
            throw InputError(schemes.where(), "constant/geometry has walls, so sphSchemes needs a "
                                              "'boundary { type ...; }' entry (e.g. akinci)", "boundary");
        boundaryModel_ = registry.create<BoundaryModel>(schemes.subDict("boundary"), physics, constants);
    }
    schemes.markUsed("boundary");
    checkIntegratorApplies(schemes);
    schemes.markUsed("pressureSolvers"); // the tutorials' menu of solvers, chosen with $pressureSolvers.<name>
    schemes.checkAllKeywordsUsed();
    case_.sphSolution.markUsed("pressure");
    case_.sphSolution.markUsed("viscosity");
    case_.sphSolution.checkAllKeywordsUsed();

    services_ = std::make_unique<CoreServices>(
        CoreServices::Models{boundaryModel_.get(), nullptr, pressure_.get(), shifting_ != nullptr}, periodic_);
    if (boundaryModel_) boundaryModel_->initialise(scene_);
    pressure_->initialise(scene_);
    if (pressure_->integratesDensity())
        for (ParticleSystem* f : scene_.ofRole(SystemRole::fluid)) f->particles.addScalar("densityRate", {false, false, true});
    if (densityDiffusion_) {
        // it acts on a density the integrator advances (continuity), never on a summed one
        if (pressure_->integratesDensity()) {
            densityDiffusion_->initialise(scene_);
            services_->setModels({boundaryModel_.get(), densityDiffusion_.get(), pressure_.get(), shifting_ != nullptr});
        } else {
            // a tutorial's one-word swap of the pressure solver keeps its densityDiffusion entry
            log::warning("densityDiffusion " + schemes.subDict("densityDiffusion").get<std::string>("type") +
                         " is not used: the pressure model sums its density from the positions; the term acts "
                         "on a density integrated in time (wcsph or isobaric with 'density continuity;')");
            densityDiffusion_.reset();
        }
    }
    if (shifting_) {
        for (ParticleSystem* f : scene_.ofRole(SystemRole::fluid)) f->particles.addVector("shiftingVelocity", {false, true});
        shifting_->initialise(scene_);
    }
    if (viscosity_) viscosity_->initialise(scene_);
    for (auto& f : forces_) f->initialise(scene_);
    if (surfaceTension_) surfaceTension_->initialise(scene_);
    integrator_->initialise(scene_);
    for (auto& p : passive_) p->initialise(scene_); // (adds its systems: after every fluid field exists)
    if (functions) {
        std::vector<std::string> blocks; // the names a time directory's files have: fluid, the systems, the blocks
        blocks.push_back("fluid");
        for (const auto& p : scene_.systems)
            if (p.get() != fluid_) blocks.push_back(p->name());
        for (const auto& name : functions->keywords()) {
            functions_.push_back(registry.create<FunctionObject>(functions->subDict(name), physics, constants, nullptr,
                                                                 case_.dir, name));
            const std::string block = functions_.back()->blockName();
            if (block.empty()) continue;
            if (std::find(blocks.begin(), blocks.end(), block) != blocks.end())
                throw InputError(functions->subDict(name).where(),
                                 "function object '" + name + "' writes the block " + block + ".vtp, the name of a " +
                                     (block == "fluid" || scene_.find(block) ? "particle system" : "block of another function object") +
                                     ": rename the entry");
            blocks.push_back(block);
        }
    }

    checkWriteFields();
    for (const ParticleSystem* b : scene_.ofRole(SystemRole::body)) scene_.reactions.want(b->index); // what moves it
    writer_ = std::make_unique<CaseWriter>(case_.dir, time_->timePrecision(), std::min(0.0, time_->startTime()));
    restarted_ = time_->startFromLatest() && restartFromLatest();
    if (!restarted_) scene_.time = time_->startTime();
    time_->begin(scene_.time, lastDeltaT_);
    if (restarted_) integrator_->restarted(scene_);
    for (auto& f : functions_) f->require(scene_);
    if (pressure_->isIterative())
        solverPerformance_ = std::make_unique<PostProcessingFile>(
            case_.dir, "solverPerformance", scene_.time,
            std::vector<PostProcessingColumn>{
                {"iterations", "-"}, {"converged", "-"}, {"maxDensityError", "%"}, {"avgDensityError", "%"}});
}

Simulation::~Simulation() = default;

namespace {
// A number read from the start of a file (nullopt when absent or not a number: "max").
std::optional<double> numberIn(const fs::path& file) {
    std::ifstream in(file);
    double value = 0;
    if (in >> value) return value;
    return std::nullopt;
}

// A /proc/meminfo entry in bytes (0 when unknown).
double meminfoBytes(const fs::path& procRoot, const std::string& key) {
    std::ifstream in(procRoot / "meminfo");
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

MemoryLimit availableMemory(const fs::path& procRoot, const fs::path& cgroupRoot, double addressSpaceLimit) {
    MemoryLimit best;
    const auto consider = [&](double bytes, const std::string& source) {
        if (bytes >= 0 && (best.source.empty() || bytes < best.bytes)) best = {bytes, source};
    };
    if (const double available = meminfoBytes(procRoot, "MemAvailable"); available > 0)
        consider(available, gib(available) + " available of " + gib(meminfoBytes(procRoot, "MemTotal")) +
                                " (/proc/meminfo)");
    // ulimit -v: the address space left (glibc's arenas and the threads' stacks count in it too)
    if (std::isfinite(addressSpaceLimit)) {
        double used = 0;
        std::ifstream status(procRoot / "self/status");
        for (std::string line; std::getline(status, line);)
            if (line.rfind("VmSize:", 0) == 0) used = std::atof(line.c_str() + 7) * 1024;
        consider(std::max(0.0, addressSpaceLimit - used),
                 gib(std::max(0.0, addressSpaceLimit - used)) + " of address space left under ulimit -v " +
                     std::to_string(long(addressSpaceLimit / 1024)) + " (kB)");
    }
    // the cgroup's memory limit, and those of the cgroups above it: v2 (memory.max, memory.current)
    // and v1 (memory/…/memory.limit_in_bytes, memory.usage_in_bytes)
    std::ifstream groups(procRoot / "self/cgroup");
    for (std::string line; std::getline(groups, line);) {
        const auto first = line.find(':'), second = line.find(':', first + 1);
        if (first == std::string::npos || second == std::string::npos) continue;
        const std::string controllers = line.substr(first + 1, second - first - 1);
        const fs::path path = fs::path(line.substr(second + 1)).relative_path();
        const bool v2 = controllers.empty();
        if (!v2 && ("," + controllers + ",").find(",memory,") == std::string::npos) continue;
        const fs::path base = v2 ? cgroupRoot : cgroupRoot / "memory";
        const char* limitFile = v2 ? "memory.max" : "memory.limit_in_bytes";
        const char* usageFile = v2 ? "memory.current" : "memory.usage_in_bytes";
        std::error_code ec;
        // (in a container the hierarchy's root is often the container's own cgroup)
        fs::path dir = fs::is_directory(base / path, ec) ? base / path : base;
        for (;;) {
            const auto limit = numberIn(dir / limitFile);
            if (limit && *limit < 0x1p60) { // v1 writes "no limit" as about 2^63
                const double room = std::max(0.0, *limit - numberIn(dir / usageFile).value_or(0.0));
                consider(room, gib(room) + " left of the cgroup's " + gib(*limit) + " (" + (dir / limitFile).string() + ")");
            }
            if (dir == base || !dir.has_relative_path() || dir.parent_path() == dir) break;
            dir = dir.parent_path();
        }
    }
    return best;
}

double latticeNeighbours(Scalar h, Scalar dx, int dim) {
    const int reach = int(std::ceil(h / dx));
    double n = 0;
    for (int k = (dim == 3 ? -reach : 0); k <= (dim == 3 ? reach : 0); ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i)
                n += (i || j || k) && double(dx) * std::sqrt(double(i * i + j * j + k * k)) < double(h);
    return n;
}

// Peak resident memory of runs (GNU time's maximum RSS, 2 threads, a few steps; the solver itself
// and its libraries take 30 MB), per particle, from two runs with the walls fixed and more fluid:
//   damBreak2D at dx 0.5 mm (26,106 / 240,000 fluid), damBreak3D at dx 1 cm (64,000 / 288,000
//   fluid, 121,788 wall), with the tutorials' continuity density, density diffusion, artificial
//   viscosity and adami walls. B a fluid particle (pairs within h = 2.6 dx: 20 in 2D, 80 in 3D):
//     wcsph 703 (2D), 1484 (3D), float 547 (2D); pbf 812 (2D); pcisph 1224, 3065, float 745 (2D);
//     dfsph 1294, 3141; iisph 1317 (2D)
//   and a wall particle: 83 B (wcsph), 195-209 B (pcisph, dfsph).
// Fitted as fields (the fluid's and its two copies kept for a blow-up's rollback: in part
// Scalars) plus the pairs (neighbour lists and their build's buffers, 13 B a pair; the iterative
// solvers' ∇W cache adds 3 Scalars a pair), each fit at or above every measurement. PBF's are
// taken as the iterative solvers' (it keeps no cache: about 60 % over). damBreak3D at dx 1 cm:
// 140 MB estimated, 133 MB measured with wcsph; 263 MB and 245 MB with pcisph.
ParticleBytes bytesPerParticle(const PhysicalParameters& physics, bool iterativePressure) {
    const double S = sizeof(Scalar);
    const double pairs = latticeNeighbours(physics.supportRadiusFactor * physics.particleSpacing, physics.particleSpacing, physics.dimension);
    ParticleBytes b;
    b.fluid = iterativePressure ? 80 + 78 * S + pairs * (7 + 3 * S) : 140 + 39 * S + pairs * 13;
    b.wall = iterativePressure ? 10 + 25 * S : 8 + 10 * S;
    return b;
}

MemoryLimit availableMemory() {
    rlimit limit{};
    const double addressSpace = ::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY
                                    ? double(limit.rlim_cur)
                                    : std::numeric_limits<double>::infinity();
    return availableMemory("/proc", "/sys/fs/cgroup", addressSpace);
}

void Simulation::checkParticleEstimate() const {
    const auto& physics = scene_.physics;
    const ParticleEstimate e = estimateParticleCount(case_.geometry, physics.particleSpacing, physics.dimension);
    const double count = e.count;
    const ParticleBytes per = bytesPerParticle(physics, pressure_->isIterative());
    const double bytes = 32.0 * 1024 * 1024 + e.fluid * per.fluid + (count - e.fluid) * per.wall; // + the solver's own
    std::ostringstream estimate;
    estimate << std::setprecision(3) << "about " << count << " particles at particleSpacing " << physics.particleSpacing
             << " in " << physics.dimension << "D (" << e.largest << " in " << e.largestName << ")";
    // the entry that makes the most particles (a huge box, `layers 1e9`), or the spacing itself
    const std::string keyword = e.largestName.substr(e.largestName.find('.') + 1);
    const SourceLocation where = e.largestAt;
    const MemoryLimit available = availableMemory();
    if (available.bytes >= 0 && bytes > available.bytes) {
        std::ostringstream need;
        need << std::setprecision(3) << "the geometry makes " << estimate.str() << ", needing about " << gib(bytes)
             << " (" << per.fluid << " B a fluid particle with these models, " << per.wall << " B a wall particle); "
             << "there is " << available.source;
        if (!forceLargeCase_)
            throw InputError(where, need.str() + ": use a larger particleSpacing or a smaller geometry (or -force)",
                             keyword);
        log::warning(need.str() + "; running anyway (-force)");
    }
    if (count > double(std::numeric_limits<Index>::max()))
        throw InputError(where, "the geometry makes " + estimate.str() + ", more than the " +
                                    std::to_string(std::numeric_limits<Index>::max()) +
                                    " a particle index can number; use a larger particleSpacing or a smaller geometry",
                         keyword);
}

namespace {
// The entry of constant/geometry that stretches the neighbour grid's domain the most along 'axis':
// the block or wall (a moving one over its sweep) farthest from the fluid's centre.
struct DomainEntry {
    std::string what; // "wall 'tank'", "fluid block 'water'"
    SourceLocation where;
    std::string keyword;
    Vec3 lo, hi;
};

// Refuses a domain whose neighbour grid lattice is beyond the grid's bounds (UniformGrid: cells of
// h along an axis and in all), naming the entry that stretches it the most along the axis of the
// most cells: the block or wall (over its motion's sweep) reaching farthest from the fluid's centre.
void checkDomainSize(const std::vector<DomainEntry>& entries, const Vec3& domainMin, const Vec3& domainMax,
                     const Periodicity& periodic, Scalar h, int dim, const Vec3& fluidCentre) {
    double cells[3] = {1, 1, 1}, all = 1;
    int axis = 0;
    for (int a = 0; a < dim; ++a) {
        cells[a] = periodic.axis[a] ? std::floor(double(periodic.length[a]) / h)
                                    : UniformGrid::cellsAlong(double(domainMax[a] - domainMin[a]), h);
        if (!(cells[a] <= cells[axis])) axis = a;
        all *= cells[a];
    }
    if (cells[axis] <= UniformGrid::maxCellsAlong && all <= UniformGrid::maxCells) return;
    const DomainEntry* farthest = nullptr;
    double reach = -1;
    for (const DomainEntry& e : entries) {
        const double r = std::max(std::abs(double(e.lo[axis]) - fluidCentre[axis]), std::abs(double(e.hi[axis]) - fluidCentre[axis]));
        if (!(r <= reach)) {
            reach = r;
            farthest = &e;
        }
    }
    std::ostringstream s;
    s << std::setprecision(3);
    const char name = "xyz"[axis];
    if (farthest) {
        const double far = std::abs(double(farthest->lo[axis]) - fluidCentre[axis]) >
                                   std::abs(double(farthest->hi[axis]) - fluidCentre[axis])
                               ? farthest->lo[axis]
                               : farthest->hi[axis];
        s << farthest->what << " reaches " << name << " = " << far << " m: ";
    }
    s << "the neighbour grid over the case (" << name << " from " << domainMin[axis] << " to " << domainMax[axis]
      << " m) would need " << cells[axis] << " cells of the support radius " << h << " m along " << name << " ("
      << all << " in all); it can number at most " << UniformGrid::maxCellsAlong << " along an axis and "
      << UniformGrid::maxCells << " in all: is a wall, a block or a motion's sweep far from the rest?";
    if (!farthest) throw InputError({}, s.str());
    throw InputError(farthest->where, s.str(), farthest->keyword);
}
} // namespace

void Simulation::buildParticles() {
    const auto& physics = scene_.physics;
    const int dim = physics.dimension;
    const SampledGeometry g = sampleGeometry(case_.geometry, physics.particleSpacing, dim, physics.gravity);
    // the fluid blocks make one fluid system; each wall entry a wall system of its own
    scene_.systems.clear();
    ParticleSystem& fluidSystem = scene_.addSystem("fluid", SystemRole::fluid);
    fluid_ = &fluidSystem;
    fluidSystem.rho0 = physics.rho0;
    auto& fluid = fluidSystem.particles;
    fluid.resize(g.fluidPositions.size());
    fluid.setParticleMass(latticeParticleMass(scene_.kernel, physics));
    for (std::size_t i = 0; i < g.fluidPositions.size(); ++i) {
        fluid.position()[i] = g.fluidPositions[i];
        fluid.velocity()[i] = g.fluidVelocities[i];
        fluid.density()[i] = physics.rho0;
        fluid.id()[i] = Index(i);
    }
    initialDepths_ = g.fluidDepths;
    initialPressures_ = g.fluidPressures;
    std::vector<DomainEntry> entries;
    for (const SampledBlock& b : g.fluidBlocks) {
        Vec3 lo = b.min, hi = b.max;
        if (dim == 2) lo[2] = hi[2] = 0;
        entries.push_back({"fluid block '" + b.name + "'", b.where, b.name, lo, hi});
    }
    Vec3 sweptLo = g.boundsMin, sweptHi = g.boundsMax; // moving walls: where they go during the run
    const double startTime = time_->startTime(), endTime = time_->endTime();
    for (const SampledWall& sampled : g.walls) {
        ParticleSystem& w = scene_.addSystem(sampled.name, sampled.body ? SystemRole::body : SystemRole::wall);
        auto& set = w.particles;
        set.resize(sampled.positions.size());
        Vec3 wallLo = Vec3::Constant(std::numeric_limits<Scalar>::max()), wallHi = -wallLo;
        for (std::size_t i = 0; i < sampled.positions.size(); ++i) {
            set.position()[i] = sampled.positions[i];
            set.density()[i] = physics.rho0;
            set.id()[i] = Index(i);
            wallLo = wallLo.cwiseMin(sampled.positions[i]);
            wallHi = wallHi.cwiseMax(sampled.positions[i]);
        }
        if (!sampled.normals.empty()) {
            w.surfaceNormal = &set.addVector("surfaceNormal", {.output = false, .scratch = true});
            *w.surfaceNormal = sampled.normals;
            w.surfaceSpacing = sampled.surfaceSpacing;
        }
        if (sampled.body) {
            w.body = std::make_unique<RigidBody>(
                RigidBody::read(*sampled.body, sampled.mass.volume, sampled.mass.centroid, sampled.mass.inertia,
                                physics.dimension));
            sampled.body->checkAllKeywordsUsed();
            // where it may go: anywhere in the sampled domain (a body moves with the fluid)
            std::ostringstream m;
            m << std::setprecision(4) << "Body '" << sampled.name << "': mass " << w.body->mass()
              << (physics.dimension == 2 ? " kg/m" : " kg") << ", centre of mass (" << w.body->state().position.transpose()
              << "), " << w.size() << " particles";
            log::info(m.str());
        }
        if (!sampled.motion) {
            entries.push_back({std::string(sampled.body ? "body '" : "wall '") + sampled.name + "'", sampled.where, sampled.name,
                               wallLo, wallHi});
            continue;
        }
        MotionContext context;
        context.dimension = dim;
        context.runStart = startTime;
        context.runEnd = endTime;
        context.caseDir = case_.dir;
        context.gravity = physics.gravity.cast<double>();
        w.motion = Motion::read(*sampled.motion, context);
        Vec3 lo, hi; // the wall's bounds over its motion (a rotating wall's corners)
        w.motion->sweptRange(startTime, endTime, wallLo, wallHi, lo, hi);
        if (dim == 2) lo[2] = hi[2] = 0;
        sweptLo = sweptLo.cwiseMin(lo);
        sweptHi = sweptHi.cwiseMax(hi);
        entries.push_back({"wall '" + sampled.name + "' (over its motion)", sampled.motion->where(), "motion", lo, hi});
        log::info("Wall '" + sampled.name + "' moves: " + w.motion->describe());
        // The fluid is drawn against the walls where constant/geometry puts them (a motion's
        // displacement is zero at its startTime). A wall its motion has already moved by the
        // run's start (the run starting after the motion's startTime) must not start inside
        // the fluid: what the wall would have pushed is unknown, so the overlap is an error.
        const RigidState s0 = w.motion->state(startTime);
        const Vec3 d0 = s0.translation.cast<Scalar>();
        if (d0 != Vec3::Zero() || s0.rotation != Eigen::Matrix3d::Identity()) {
            std::size_t overlapping = 0, first = g.fluidPositions.size();
            for (std::size_t i = 0; i < g.fluidPositions.size(); ++i)
                if (sampled.occupies(w.motion->drawnPosition(s0, g.fluidPositions[i].cast<double>()).cast<Scalar>(), dim,
                                     Scalar(0.01) * physics.particleSpacing)) {
                    ++overlapping;
                    first = std::min(first, i);
                }
            std::ostringstream where;
            where << std::setprecision(6) << "wall '" << sampled.name << "' starts at time " << startTime
                  << " displaced by (" << d0[0] << " " << d0[1] << " " << d0[2] << ")";
            if (s0.rotation != Eigen::Matrix3d::Identity())
                where << " and rotated by " << Eigen::AngleAxisd(s0.rotation).angle() * 180 / std::numbers::pi << " deg";
            where << " by its motion";
            if (overlapping > 0) {
                std::string block;
                for (const SampledBlock& b : g.fluidBlocks)
                    if (first >= b.first && first < b.first + b.count) block = b.name;
                throw InputError(sampled.motion->where(),
                                 where.str() + ", where it overlaps " + std::to_string(overlapping) +
                                     " particles of the fluid (block '" + block +
                                     "' first): the fluid is drawn against the wall where constant/geometry "
                                     "places it, its position at the motion's startTime; start the run at the "
                                     "motion's startTime, or draw the wall and the fluid as they are at time " +
                                     CaseWriter::timeName(startTime),
                                 "motion");
            }
            log::info(where.str() + " (clear of the fluid)");
        }
    }
    if (dim == 2) sweptLo[2] = sweptHi[2] = 0;
    // Neighbour grid over the sampled bounds (and the moving walls' sweep) with a generous
    // margin (particles beyond it are clamped into border cells: correct, only slower).
    const Vec3 extent = sweptHi - sweptLo;
    const Scalar h = scene_.constants.supportRadius;
    const Scalar margin = 2 * h;
    domainMin_ = sweptLo - Vec3::Constant(margin) - Scalar(0.25) * extent;
    domainMax_ = sweptHi + Vec3::Constant(margin) + Scalar(0.25) * extent;
    periodic_ = g.periodic;
    if (dim == 2) domainMin_[2] = domainMax_[2] = 0;
    Vec3 fluidCentre = Vec3::Zero();
    for (const Vec3& x : g.fluidPositions) fluidCentre += x / Scalar(g.fluidPositions.size());
    checkDomainSize(entries, domainMin_, domainMax_, periodic_, h, dim, fluidCentre);
    // A particle beyond one more extent (and 10 h) from everything sampled has blown up.
    const Vec3 reach = extent.cwiseMax(Vec3::Constant(10 * h));
    blowUpMin_ = sweptLo - reach;
    blowUpMax_ = sweptHi + reach;
    // ... or moves 100 times faster than a free fall across the domain could make it
    blowUpSpeedFloor_ = 100 * std::sqrt(2 * physics.gravity.norm() * extent.norm());
    scene_.search.setup(h, physics.dimension, domainMin_, domainMax_, periodic_);
    for (ParticleSystem* w : scene_.boundaries()) {
        w->particles.permute(scene_.search.sortOrder(w->particles.position())); // cache order
        if (w->motion) {
            w->initialPosition = w->particles.position();
            if (w->surfaceNormal) w->initialSurfaceNormal = *w->surfaceNormal;
        }
        if (w->body) {
            w->body->attach(*w); // its particles' positions in the body frame
            w->body->place(*w);
        }
    }
    declareInteractions();
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

void Simulation::declareInteractions() {
    for (const auto& p : scene_.systems) scene_.registerWithSearch(*p);
}

void Simulation::resolveConstants() {
    SceneConstants& c = scene_.constants;
    c.particleMass = fluid_->particles.particleMass();
    c.rho0 = scene_.physics.rho0;
    c.soundSpeed = pressure_->soundSpeed(c, scene_.physics);
    c.eosExponent = pressure_->eosExponent();
    if (!(c.soundSpeed >= 0) || !std::isfinite(c.soundSpeed))
        throw std::logic_error("the pressure model declared a sound speed that is not a finite non-negative number");
}

void Simulation::applyInitialPressure() {
    auto& fluid = fluid_->particles;
    const Scalar rhoG = scene_.physics.rho0 * scene_.physics.gravity.norm();
    for (std::size_t i = 0; i < fluid.size(); ++i) {
        const Scalar p = rhoG * initialDepths_[i] + initialPressures_[i];
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
    if (surfaceTension_)
        check("surfaceTension", schemes.subDict("surfaceTension").get<std::string>("type"), surfaceTension_->result());
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
    removeOutside_ = control.getWordOrDefault("onParticleOutside", {"remove", "stop"}, "remove") == "remove";
    maxRemovedFraction_ = control.getOrDefault<double>("maxRemovedFraction", 0.01);
    if (!(maxRemovedFraction_ >= 0 && maxRemovedFraction_ <= 1))
        throw InputError(control.locationOf("maxRemovedFraction"), "maxRemovedFraction must be between 0 and 1",
                         "maxRemovedFraction");
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
    for (const auto& p : scene_.systems) add(p->particles);
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
// The shortest text that reads back as x in the build's precision (0.01, not 0.0099999997764825821
// for a float).
std::string shortest(Scalar x) {
    for (int digits = 6;; ++digits) {
        std::ostringstream s;
        s << std::setprecision(digits) << double(x);
        if (digits >= 17 || Scalar(std::strtod(s.str().c_str(), nullptr)) == x) return s.str();
    }
}
} // namespace

std::string Simulation::particlesFile() const {
    const auto& physics = scene_.physics;
    std::ostringstream s;
    s << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
      << "    class       dictionary;\n    object      particles;\n}\n\n"
      << "// what 'startFrom latestTime' from this time must match (the particles continue)\n"
      << "dimension       " << physics.dimension << ";\n"
      << "particleSpacing " << shortest(physics.particleSpacing) << ";\n"
      << "supportRadius   " << shortest(physics.supportRadiusFactor) << ";\n"
      << "rho0            " << shortest(physics.rho0) << ";\n"
      << "kernel          " << case_.sphSchemes.subDict("kernel").get<std::string>("type") << ";\n"
      << "particleMass    " << shortest(fluid_->particles.particleMass()) << ";\n"
      << "fluid           (" << fluid_->name() << ");\n";
    const auto list = [&](const char* keyword, const std::vector<const ParticleSystem*>& systems) {
        s << keyword << "(";
        for (std::size_t k = 0; k < systems.size(); ++k) s << (k ? " " : "") << systems[k]->name();
        s << ");\n";
    };
    list("walls           ", scene_.ofRole(SystemRole::wall));
    list("bodies          ", scene_.ofRole(SystemRole::body));
    list("passive         ", scene_.ofRole(SystemRole::passive));
    return s.str();
}

namespace {
// The two values of a setting a restart refuses, in words that tell them apart.
std::string twoValues(double now, double then) {
    for (int digits = 6;; ++digits) {
        std::ostringstream a, b;
        a << std::setprecision(digits) << now;
        b << std::setprecision(digits) << then;
        if (a.str() != b.str() || digits == 17) return a.str() + " is not the " + b.str();
    }
}

bool sameValue(double a, double b, double tolerance) {
    return std::abs(a - b) <= tolerance * std::max(std::abs(a), std::abs(b));
}
} // namespace

void Simulation::checkRestartMatches(const fs::path& dir, const ParticleSet& saved) const {
    // (relative tolerance: a restart by a build of the other precision reads the same values)
    constexpr double tolerance = 1e-6;
    const std::string time = dir.filename().string();
    const auto& physics = scene_.physics;
    const Dictionary& fp = case_.fluidProperties;
    const fs::path file = dir / "uniform/particles";
    const std::string anew = ", or 'startFrom startTime;' to start anew";
    // "<what> of time T (<file>): a restart continues its particles; use <fix>, or ..."
    const auto refuse = [&](const SourceLocation& where, const std::string& keyword, const std::string& what,
                            const std::string& fix, const fs::path& source) {
        throw InputError(where, what + " of time " + time + " (" + source.string() +
                                    "): a restart continues its particles; use " + fix + anew, keyword);
    };
    const Scalar mass = fluid_->particles.particleMass();
    if (!fs::exists(file)) {
        // a time written before uniform/particles was: the mass its fluid.vtp holds (it changes
        // with the spacing, the dimension, rho0, the kernel and its support)
        if (!sameValue(saved.particleMass(), mass, tolerance))
            refuse(fp.where(), "", "the particle mass " + twoValues(mass, saved.particleMass()),
                   "the particleSpacing, dimension, rho0 and kernel it was run with", dir / "fluid.vtp");
        return;
    }
    const Dictionary then = Dictionary::fromFile(file);
    const auto at = [](const Dictionary& d, const std::string& keyword) {
        return d.found(keyword) ? d.locationOf(keyword) : d.where();
    };
    if (const int was = then.get<int>("dimension"); was != physics.dimension)
        refuse(at(fp, "dimension"), "dimension",
               "dimension " + std::to_string(physics.dimension) + " is not the " + std::to_string(was),
               "dimension " + std::to_string(was), file);
    const auto check = [&](const std::string& keyword, double now) {
        const double was = then.get<double>(keyword);
        if (!sameValue(now, was, tolerance))
            refuse(at(fp, keyword), keyword, keyword + " " + twoValues(now, was), keyword + " " + shortest(Scalar(was)),
                   file);
    };
    check("particleSpacing", physics.particleSpacing);
    check("supportRadius", physics.supportRadiusFactor);
    check("rho0", physics.rho0);
    const Dictionary& kernel = case_.sphSchemes.subDict("kernel");
    const std::string kernelNow = kernel.get<std::string>("type"), kernelThen = then.get<std::string>("kernel");
    if (kernelNow != kernelThen)
        refuse(at(kernel, "type"), "type",
               "kernel " + kernelNow + " is not the " + kernelThen,
               "kernel { type " + kernelThen + "; } (the particle mass is the kernel's lattice sum)", file);
    const double massThen = then.get<double>("particleMass");
    if (!sameValue(mass, massThen, tolerance))
        refuse(fp.where(), "", "the particle mass " + twoValues(mass, massThen),
               "the fluidProperties and kernel it was run with", file);
    const auto fluids = then.get<std::vector<std::string>>("fluid");
    if (fluids != std::vector<std::string>{fluid_->name()}) {
        std::string list;
        for (const auto& f : fluids) list += (list.empty() ? "" : " ") + f;
        refuse(case_.geometry.where(), "", "the fluid systems (" + fluid_->name() + ") are not the (" + list + ")",
               "the fluids it was run with", file);
    }
    // walls are sampled anew from constant/geometry: a change is the user's (a gate taken out)
    std::vector<std::string> wallsNow, wallsThen = then.get<std::vector<std::string>>("walls");
    for (const ParticleSystem* w : scene_.ofRole(SystemRole::wall)) wallsNow.push_back(w->name());
    for (const auto& w : wallsThen)
        if (std::find(wallsNow.begin(), wallsNow.end(), w) == wallsNow.end())
            log::info("Wall '" + w + "' of time " + time + " is not in constant/geometry: the restart runs without it");
    for (const auto& w : wallsNow)
        if (std::find(wallsThen.begin(), wallsThen.end(), w) == wallsThen.end())
            log::info("Wall '" + w + "' is new since time " + time + " (it is not in " + file.string() + ")");
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
    checkRestartMatches(case_.dir / name, *saved);
    restartedFrom_ = name;
    auto& fluid = fluid_->particles;
    fluid.resize(saved->size());
    fluid.id() = saved->id();
    for (const auto& f : saved->scalarFields())
        if (auto* mine = fluid.findScalar(f->name)) *mine = f->data;
    for (const auto& f : saved->vectorFields())
        if (auto* mine = fluid.findVector(f->name)) *mine = f->data;
    fluid.position() = saved->position();
    restorePassiveSystems(case_.dir / name);
    ++scene_.stateVersion;
    // exact time, step index and last Δt
    scene_.time = timeDict->get<double>("value");
    scene_.step = timeDict->get<long>("index");
    lastDeltaT_ = timeDict->get<double>("deltaT");
    // a blow-up retry's cap still in force at that time (absent: none)
    deltaTCap_ = timeDict->getOrDefault<double>("blowUpDeltaTCap", std::numeric_limits<double>::infinity());
    deltaTHoldSteps_ = timeDict->getOrDefault<int>("blowUpHoldSteps", 0);
    if (!(deltaTCap_ > 0)) deltaTCap_ = std::numeric_limits<double>::infinity();
    readBodies(case_.dir / name);
    readPassiveStates(case_.dir / name);
    log::info("Restarting from time " + name + " (step " + std::to_string(scene_.step) + ", " +
              std::to_string(saved->size()) + " particles)");
    return true;
}

void Simulation::restorePassiveSystems(const fs::path& timeDir) {
    for (ParticleSystem* p : scene_.ofRole(SystemRole::passive)) {
        const fs::path file = timeDir / (p->name() + ".vtp");
        if (!fs::exists(file)) {
            log::info("Passive system '" + p->name() + "' is new since time " + timeDir.filename().string() +
                      " (no " + file.filename().string() + "): it starts as its model seeds it");
            continue;
        }
        const ParticleSet saved = readVtp(file, p->name());
        auto& set = p->particles;
        set.resize(saved.size());
        set.id() = saved.id();
        for (const auto& f : saved.scalarFields())
            if (auto* mine = set.findScalar(f->name)) *mine = f->data;
        for (const auto& f : saved.vectorFields())
            if (auto* mine = set.findVector(f->name)) *mine = f->data;
        set.position() = saved.position();
        scene_.search.positionsChanged(p->index);
    }
}

namespace {
// The FoamFile header of a uniform/ dictionary of states (bodies, passive).
std::string uniformFileHeader(const std::string& object) {
    return "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n    object      " +
           object + ";\n}\n\n";
}
} // namespace

std::string Simulation::passiveStateFile() const {
    const Dictionary* passive = case_.sphSchemes.findDict("passive");
    if (!passive) return {};
    const auto names = passive->keywords();
    std::ostringstream entries;
    for (std::size_t k = 0; k < passive_.size(); ++k)
        if (const std::string state = passive_[k]->stateText(); !state.empty())
            entries << names[k] << "\n{\n" << state << "}\n";
    if (entries.str().empty()) return {};
    return uniformFileHeader("passive") + entries.str();
}

void Simulation::readPassiveStates(const fs::path& timeDir) {
    const fs::path file = timeDir / "uniform/passive";
    const Dictionary* passive = case_.sphSchemes.findDict("passive");
    if (!passive || !fs::exists(file)) return; // (a model then rebuilds its state from its particles)
    const Dictionary d = Dictionary::fromFile(file);
    const auto names = passive->keywords();
    for (std::size_t k = 0; k < passive_.size(); ++k)
        if (const Dictionary* state = d.findDict(names[k])) passive_[k]->readState(*state);
}

std::string Simulation::bodiesFile() const {
    const auto bodies = scene_.ofRole(SystemRole::body);
    if (bodies.empty()) return {};
    std::ostringstream s;
    s << uniformFileHeader("bodies");
    for (const ParticleSystem* b : bodies) s << b->name() << "\n{\n" << b->body->stateText() << "}\n";
    return s.str();
}

void Simulation::readBodies(const fs::path& timeDir) {
    const auto bodies = scene_.ofRole(SystemRole::body);
    if (bodies.empty()) return;
    const fs::path file = timeDir / "uniform/bodies";
    if (!fs::exists(file))
        throw InputError({file.string(), 0, 0}, "the case has bodies but time " + timeDir.filename().string() +
                                                    " holds no uniform/bodies (their state): it was written by "
                                                    "another case; use 'startFrom startTime;'");
    const Dictionary d = Dictionary::fromFile(file);
    for (ParticleSystem* b : bodies) {
        if (!d.findDict(b->name()))
            throw InputError(d.where(), "uniform/bodies has no state of body '" + b->name() + "'", b->name());
        b->body->readState(d.subDict(b->name()));
        b->body->place(*b);
    }
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
    if (surfaceTension_) s << ", surfaceTension " << type("surfaceTension");
    if (const Dictionary* passive = case_.sphSchemes.findDict("passive"))
        for (const auto& name : passive->keywords())
            s << ", passive " << name << " (" << passive->subDict(name).get<std::string>("type") << ")";
    return s.str();
}

} // namespace spindrift
