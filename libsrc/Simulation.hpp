// Spindrift — one run of a case: set-up (Simulation.cpp: dictionaries → particle systems →
// constants → models) and the time loop (TimeLoop.cpp)
//   walls placed → neighbour search → density → boundary → non-pressure → pressure → integrator → write.
#pragma once

#include "Case.hpp"
#include "CaseWriter.hpp"
#include "PassiveModel.hpp"
#include "ModelRegistry.hpp"
#include "Step.hpp"
#include "TimeControl.hpp"

#include <limits>
#include <memory>
#include <optional>

namespace spindrift {

struct RunSummary {
    long steps = 0;                 // steps taken in this run (not counting those before a restart)
    bool interrupted = false;       // stopped by SIGINT/SIGTERM/SIGHUP (state written)
    double endTime = 0;
    double wallSeconds = 0;
    std::size_t fluidParticles = 0, wallParticles = 0;
    int writes = 0;
    double maxDensityError = 0;     // max over the run of max_i (ρ_i − ρ0)/ρ0 (the step line's rhoErr max)
    double averageIterations = 0;   // of an iterative pressure solver
    std::size_t removedParticles = 0; // fluid particles that left the domain (onParticleOutside remove)
};

// Mass of a fluid particle such that a particle with a full neighbourhood on the initial
// lattice has exactly the rest density: m = ρ0 / Σ_lattice W (instead of ρ0 Δx^d, which is off
// by the kernel's lattice-sum error, ~1 % for the Wendland C2 at h = 2.6Δx in 2D).
Scalar latticeParticleMass(const KernelTable& kernel, const PhysicalParameters& physics);

// The memory this process may still take, and what limits it: the least of MemAvailable
// (/proc/meminfo), the address space left under `ulimit -v` (addressSpaceLimit: RLIMIT_AS in
// bytes, infinity for none; less the process's VmSize) and the room left in its cgroup and every
// cgroup above it (v2: memory.max less memory.current; v1: memory.limit_in_bytes less
// memory.usage_in_bytes). bytes < 0 when nothing is known.
struct MemoryLimit {
    double bytes = -1;
    std::string source; // e.g. "1.2 GiB left of the cgroup's 2 GiB (/sys/fs/cgroup/memory.max)"
};
MemoryLimit availableMemory(const std::filesystem::path& procRoot, const std::filesystem::path& cgroupRoot,
                            double addressSpaceLimit);
MemoryLimit availableMemory(); // this process's: /proc, /sys/fs/cgroup, getrlimit(RLIMIT_AS)

// The neighbours a particle has within the support radius h on the lattice of spacing dx.
double latticeNeighbours(Scalar h, Scalar dx, int dimension);
// Bytes a fluid and a wall particle take at the peak of a run, for this spacing, support radius
// and dimension and an iterative pressure solver or not (see Simulation.cpp for what is counted
// and the measurements it rests on).
struct ParticleBytes {
    double fluid = 0, wall = 0;
};
ParticleBytes bytesPerParticle(const PhysicalParameters& physics, bool iterativePressure);

// SIGINT, SIGTERM and SIGHUP before the time loop (set-up, -dryRun): a message naming the
// signal, and the process ends as killed by it (exit status 128 + signal); there is no state
// worth writing yet. Simulation::run() takes them over for the time loop (finish the step,
// write it, stop) and gives them back after.
void stopAtOnceOnSignalsDuringSetUp();

class Simulation {
public:
    // forceLargeCase (-force): run a case whose particle estimate exceeds the memory available
    explicit Simulation(const std::filesystem::path& caseDir, bool forceLargeCase = false);
    ~Simulation();

    // Writes the initial state (unless restarting) and advances to endTime.
    RunSummary run();
    // Evaluates the initial accelerations and writes the start time only (-dryRun).
    void writeInitialState();

    Scene& scene() { return scene_; }
    const Scene& scene() const { return scene_; }
    const Case& caseFiles() const { return case_; }
    const TimeControl& timeControl() const { return *time_; }
    std::string schemesSummary() const;

    // -postProcess (PostProcess.cpp): the state written in the time directory 'timeName' of time
    // 'time' — the fluid's fields read from its fluid.vtp, the exact time and step from its
    // uniform/time (when present), the moving walls placed at that time, a passive system's particles and the bodies'
    // states read back, and the neighbour search built on it. Throws std::runtime_error when the time cannot be read.
    void loadWrittenTime(double time, const std::string& timeName);

    // One force evaluation at the current state, the moving boundaries placed at 'time', with
    // step size dt (public for tests).
    void evaluate(double time, Scalar dt);
    // The step size of the last step (of the time restarted from or post-processed).
    double lastDeltaT() const { return lastDeltaT_; }
    // The core's services to the models (Step.hpp).
    const StepServices& services() const;
    double stableDeltaT() const;
    // Every model the case names (for what they all declare: Model::maxTimeStep).
    std::vector<const Model*> models() const;

private:
    void readRunControls(const Dictionary& control);
    void startFunctionObjects();
    void rereadControlDictIfChanged();
    void buildParticles();
    // Refuses, before anything is allocated, a geometry whose particles would not fit in the
    // memory available (or not in the 32-bit particle index): the estimate and the memory named.
    void checkParticleEstimate() const;
    void resolveConstants();
    // The sampled blocks' initial pressure (a hydrostatic start: p = ρ0 |g| depth) and the density
    // the pressure model's equation of state gives it; before the models initialise, so solvers
    // warm-start from it.
    void applyInitialPressure();
    void checkIntegratorApplies(const Dictionary& schemes) const;
    // Moves the moving walls to where their motion puts them at 'time' (positions, velocities,
    // accelerations).
    void placeMovingWalls(double time);
    // The speed of a moving wall's fastest particle at 'time' (a bound: translation and rotation).
    double wallSpeed(const ParticleSystem& wall, double time) const;
    // Places the moving walls at 'time' and makes the neighbour lists those of the systems' current
    // positions with the boundaries there (kept when they are already).
    void updateLists(double time);
    // Advances every rigid body over dt with the fluid's force and moment of the last evaluation
    // and gravity, then keeps it out of the walls and the other bodies (resolveContacts).
    void advanceBodies(double dt);
    // Moves a body out of the walls and bodies it has entered (closer than Δx) and stops its
    // approach there (RigidBody::resolveContact).
    void resolveContacts(ParticleSystem& body);
    // Registers every system with the neighbour search and declares who interacts with whom:
    // each fluid with itself, the other fluids and every boundary.
    void declareInteractions();
    bool restartFromLatest();
    // Refuses a restart from time 'name' (in 'dir') of other particles than this set-up makes:
    // another dimension, particleSpacing, supportRadius, rho0, kernel, particle mass or fluid
    // systems than uniform/particles holds (an InputError naming the keyword and both values);
    // logs the walls added or removed since.
    void checkRestartMatches(const std::filesystem::path& dir, const ParticleSet& saved) const;
    // The case's times for this run (CaseWriter::beginRun), logged.
    void takeCaseTimes();
    void write();
    // uniform/particles of a written time: what a restart from it must match.
    std::string particlesFile() const;
    std::string timeFile() const;
    // uniform/bodies: every body's state in full precision (empty without bodies), and read back.
    std::string bodiesFile() const;
    // uniform/passive: the passive models' states of their own (empty when none has one), and
    // read back.
    std::string passiveStateFile() const;
    void readPassiveStates(const std::filesystem::path& timeDir);
    void readBodies(const std::filesystem::path& timeDir);
    // A restart's passive systems: their particles and restart fields from <name>.vtp of the time.
    void restorePassiveSystems(const std::filesystem::path& timeDir);
    // Describes the worst problem of the current state (empty when healthy); 'densityOnly'
    // tells that it is a density error (measured at the state before the last step).
    std::string findBlowUp(bool& densityOnly) const;
    std::string findBlowUp(const ParticleSystem& system, bool& densityOnly) const;
    // Removes the fluid particles beyond the domain (blowUpMin_, blowUpMax_; an open tank's
    // spill) with a log line, unless that would take the run's removals past maxRemovedFraction_
    // of the fluid (then they stay, and findBlowUp reports them). Returns how many it removed.
    std::size_t removeParticlesOutside();
    void checkWritable() const;
    // Every name in controlDict's writeFields is a field of some system (a misspelt one would
    // silently never be written).
    void checkWriteFields() const;

    Case case_;
    std::unique_ptr<CaseLock> lock_; // held from before the first write to the end (destroyed last but case_)
    Scene scene_;
    std::unique_ptr<TimeControl> time_;
    std::unique_ptr<CaseWriter> writer_;
    std::unique_ptr<Kernel> kernel_;
    std::unique_ptr<PressureModel> pressure_;
    std::unique_ptr<ViscosityModel> viscosity_;
    std::vector<std::unique_ptr<ExtraForce>> forces_;
    std::unique_ptr<SurfaceTensionModel> surfaceTension_;
    std::vector<std::unique_ptr<FunctionObject>> functions_;
    std::unique_ptr<PostProcessingFile> solverPerformance_; // iterative pressure solvers only
    std::unique_ptr<Integrator> integrator_;
    std::unique_ptr<BoundaryModel> boundaryModel_;
    std::unique_ptr<DensityDiffusion> densityDiffusion_;
    std::unique_ptr<ShiftingModel> shifting_;
    std::vector<std::unique_ptr<PassiveModel>> passive_;
    std::unique_ptr<CoreServices> services_;
    std::vector<std::string> writeFields_;
    int sortEvery_ = 10;
    int logInterval_ = 0; // controlDict logInterval: a step line every N steps (0: automatic)
    bool reduceDeltaTOnBlowUp_ = false;
    int blowUpRetries_ = 5;
    double blowUpDensityError_ = 0.2;
    // [m/s]: the setting (0 = automatic: 100 × max(c0, sqrt(2 g L), |u0|)) and the bound in use
    double blowUpSpeedSetting_ = 0, blowUpSpeedAuto_ = 1e300, blowUpSpeedFloor_ = 0, blowUpSpeed_ = 1e300;
    bool runTimeModifiable_ = true;
    std::filesystem::file_time_type controlDictTime_;
    double lastDeltaT_ = 0;
    // After a blow-up retry (onBlowUp reduceDeltaT) Δt is capped at half the step that blew up:
    // held there for blowUpHoldSteps good steps, then the cap grows by blowUpCapGrowth a step
    // until Δt no longer reaches it (as OpenFOAM limits Δt's growth). Kept in uniform/time while
    // it applies, so a restart continues with it.
    static constexpr int blowUpHoldSteps = 20;
    static constexpr double blowUpCapGrowth = 1.1;
    double deltaTCap_ = std::numeric_limits<double>::infinity();
    int deltaTHoldSteps_ = 0;
    std::vector<Scalar> initialDepths_; // of the fluid particles, where their block starts hydrostatic
    std::vector<Scalar> initialPressures_; // of the fluid particles, where their block gives it as an expression
    ParticleSystem* fluid_ = nullptr;   // the fluid system constant/geometry's fluid blocks make
    Vec3 domainMin_, domainMax_;   // of the neighbour grid
    Vec3 blowUpMin_, blowUpMax_;   // a particle beyond this box has left the domain
    bool removeOutside_ = true;    // onParticleOutside remove (else stop: a blow-up)
    double maxRemovedFraction_ = 0.01;
    std::size_t removedParticles_ = 0, fluidAtStart_ = 0; // this run's
    Periodicity periodic_;
    double listsBoundaryTime_ = std::numeric_limits<double>::quiet_NaN(); // where the boundaries were when the lists were made (NaN: bodies moved since)
    bool restarted_ = false;
    std::string restartedFrom_; // the time's name (restarted_)
    bool forceLargeCase_ = false;
};

} // namespace spindrift
