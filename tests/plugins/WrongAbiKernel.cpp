// Kernel plugins the registry must refuse before calling anything in them, one source built
// several ways (tests/plugins/CMakeLists.txt):
//   SPINDRIFT_TEST_INTERFACE_VERSION=999  exports, by hand, the ABI tag of another interface
//   SPINDRIFT_TEST_OTHER_PRECISION        built for the precision the core is not (float in a
//                                         double build, double in a float build)
//   SPINDRIFT_TEST_CALLS_CORE             ... and its constructor calls the core with a Vec3 of
//                                         that precision, a symbol the core lacks
//                                         (Dictionary::getOrDefault<Vec3>): it cannot be bound
//   none                                  an ordinary kernel, given a file name of another kind
#ifdef SPINDRIFT_TEST_OTHER_PRECISION
#ifdef SPINDRIFT_SINGLE_PRECISION
#undef SPINDRIFT_SINGLE_PRECISION
#else
#define SPINDRIFT_SINGLE_PRECISION
#endif
#endif

#include "Kernel.hpp"
#include "ModelContext.hpp"

namespace {
class Flat final : public spindrift::Kernel {
public:
    explicit Flat(const spindrift::ModelContext& c)
        : Kernel(c.constants.supportRadius, c.physics.dimension)
#ifdef SPINDRIFT_TEST_CALLS_CORE
        , height_(c.dict.getOrDefault<spindrift::Vec3>("height", spindrift::Vec3::Ones()).x())
#endif
    {
    }
    spindrift::Scalar W(spindrift::Scalar r) const override { return r < h_ ? height_ : 0; }
    spindrift::Scalar dWdr(spindrift::Scalar) const override { return 0; }
    spindrift::Scalar laplacian(spindrift::Scalar) const override { return 0; }

private:
    spindrift::Scalar height_ = 1;
};
} // namespace

#ifdef SPINDRIFT_TEST_INTERFACE_VERSION
#include <boost/dll/alias.hpp>
namespace wrong_abi_exports {
std::unique_ptr<spindrift::Kernel> create(const spindrift::ModelContext& c) { return std::make_unique<Flat>(c); }
const char* const kind = "kernel";
const char* const name = "wrongAbi";
const spindrift::PluginAbiTag abiTag{SPINDRIFT_TEST_INTERFACE_VERSION, sizeof(spindrift::Scalar)};
} // namespace wrong_abi_exports
BOOST_DLL_ALIAS(wrong_abi_exports::create, spindrift_create)
BOOST_DLL_ALIAS(wrong_abi_exports::kind, spindrift_kind)
BOOST_DLL_ALIAS(wrong_abi_exports::name, spindrift_name)
BOOST_DLL_ALIAS(wrong_abi_exports::abiTag, spindrift_abi_tag)
#else
#include "Plugin.hpp"
SPINDRIFT_PLUGIN(Kernel, Flat)
#endif
