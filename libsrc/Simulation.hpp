// Spindrift — one run of a case: set-up (dictionaries → particle systems → constants → models)
// and the time loop
//   walls placed → neighbour search → density → boundary → non-pressure → pressure → integrator → write.
#pragma once

#include "Case.hpp"
#include "CaseWriter.hpp"
#include "ModelRegistry.hpp"
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
};

// Mass of a fluid particle such that a particle with a full neighbourhood on the initial
// lattice has exactly the rest density: m = ρ0 / Σ_lattice W (instead of ρ0 Δx^d, which is off
// by the kernel's lattice-sum error, ~1 % for the Wendland C2 at h = 2.6Δx in 2D).
Scalar latticeParticleMass(const KernelTable& kernel, const PhysicalParameters& physics);

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
    const Case& caseFiles() const { return case_; }
    const TimeControl& timeControl() const { return *time_; }
    std::string schemesSummary() const;

    // -postProcess (PostProcess.cpp): the state written in the time directory 'timeName' of time
    // 'time' — the fluid's fields read from its fluid.vtp, the exact time and step from its
    // uniform/time (when present), the moving walls placed at that time and the neighbour search
    // built on it. Throws std::runtime_error when the time cannot be read.
    void loadWrittenTime(double time, const std::string& timeName);

    // One force evaluation at the current state, the walls placed at 'time', with step size dt
    // (public for tests).
    void evaluate(double time, Scalar dt);
    double stableDeltaT() const;

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
    bool restartFromLatest();
    void write();
    std::string timeFile() const;
    // Describes the worst problem of the current state (empty when healthy); 'densityOnly'
    // tells that it is a density error (measured at the state before the last step).
    std::string findBlowUp(bool& densityOnly) const;
    void checkWritable() const;
    // Every name in controlDict's writeFields is a field of the fluid or of a wall (a misspelt
    // one would silently never be written).
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
    std::vector<std::unique_ptr<FunctionObject>> functions_;
    std::unique_ptr<PostProcessingFile> solverPerformance_; // iterative pressure solvers only
    std::unique_ptr<Integrator> integrator_;
    std::unique_ptr<BoundaryModel> boundaryModel_;
    std::unique_ptr<DensityDiffusion> densityDiffusion_;
    std::unique_ptr<ShiftingModel> shifting_;
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
    Vec3 domainMin_, domainMax_;   // of the neighbour grid
    Vec3 blowUpMin_, blowUpMax_;   // a particle beyond this box has blown up
    Periodicity periodic_;
    bool staticWallsWritten_ = false;
    bool restarted_ = false;
    bool forceLargeCase_ = false;
    int writes_ = 0;
};

} // namespace spindrift
