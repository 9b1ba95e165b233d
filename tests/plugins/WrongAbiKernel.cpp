// A kernel plugin that claims another core ABI version: the registry must refuse to call it.
#include "Kernel.hpp"
#include "ModelContext.hpp"

#include <boost/dll/alias.hpp>

namespace {
class Flat final : public spindrift::Kernel {
public:
    explicit Flat(const spindrift::ModelContext& c) : Kernel(c.physics.supportRadius, c.physics.dimension) {}
    spindrift::Scalar W(spindrift::Scalar r) const override { return r < h_ ? 1 : 0; }
    spindrift::Scalar dWdr(spindrift::Scalar) const override { return 0; }
    spindrift::Scalar laplacian(spindrift::Scalar) const override { return 0; }
};
} // namespace

namespace wrong_abi_exports {
std::unique_ptr<spindrift::Kernel> create(const spindrift::ModelContext& c) { return std::make_unique<Flat>(c); }
const char* const kind = "kernel";
const char* const name = "wrongAbi";
const std::uint32_t abiVersion = 999;
} // namespace wrong_abi_exports
BOOST_DLL_ALIAS(wrong_abi_exports::create, spindrift_create)
BOOST_DLL_ALIAS(wrong_abi_exports::kind, spindrift_kind)
BOOST_DLL_ALIAS(wrong_abi_exports::name, spindrift_name)
BOOST_DLL_ALIAS(wrong_abi_exports::abiVersion, spindrift_abi_version)
