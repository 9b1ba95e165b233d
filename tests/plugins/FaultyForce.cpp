// A force that fails on purpose, for the solver's signal tests (tests/cases/interruptions.sh),
// loaded with libs ("<build>/lib/testPlugins/libspindriftTestFaultyForce.so"):
//   sphSchemes:  forces { fault { type faulty; segfaultAfterStep 5; setUpSeconds 0; } }
//   segfaultAfterStep N  dereferences a null pointer in addAcceleration once N steps are
//                        complete (the evaluation of step N + 1); -1 (default): never
//   setUpSeconds S       sleeps S seconds in initialise(), after the log line "faulty: sleeping
//                        in set-up", so that a test can signal the solver during set-up
#include "Log.hpp"
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

#include <chrono>
#include <thread>

namespace {
using namespace spindrift;

// volatile: the compiler cannot know it is null, so the store below is a real memory access
// (a literal null dereference may be compiled to a trap instruction: SIGILL, not SIGSEGV)
int* volatile nowhere = nullptr;

class FaultyForce final : public ExtraForce {
public:
    explicit FaultyForce(const ModelContext& c)
        : segfaultAfterStep_(c.dict.getOrDefault<long>("segfaultAfterStep", -1)),
          setUpSeconds_(c.dict.getOrDefault<double>("setUpSeconds", 0)) {}

    void initialise(Scene&) override {
        if (setUpSeconds_ <= 0) return;
        log::info("faulty: sleeping in set-up");
        std::this_thread::sleep_for(std::chrono::duration<double>(setUpSeconds_));
    }

    void addAcceleration(Scene& s, ParticleSystem&, const Step&) override {
        if (segfaultAfterStep_ >= 0 && s.step >= segfaultAfterStep_) *nowhere = 1;
    }

    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    long segfaultAfterStep_;
    double setUpSeconds_;
};
} // namespace

SPINDRIFT_PLUGIN(ExtraForce, FaultyForce)
