// Spindrift — basic numeric types shared by the core and every plugin.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace spindrift {

#ifdef SPINDRIFT_SINGLE_PRECISION
using Scalar = float;
#else
using Scalar = double;
#endif

// 3-vectors throughout; z = 0 in two dimensions.
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
using Index = std::uint32_t;

// Bumped whenever a header a plugin compiles against changes its layout or virtual interface
// (2: the plugin's kind from its base class, the ABI tag below; 3: particle systems as peers, Step;
// 4: BoundaryModel::correctAcceleration and addReactions, adami's contact; 5: Motion a rigid transform;
// 6: a single layer's surface normals in ParticleSystem and SourceView).
inline constexpr std::uint32_t pluginInterfaceVersion = 6;

// What a plugin must share with the core to be called: exported by every plugin (Plugin.hpp)
// and compared by the ModelRegistry before anything in the library is used. A plugin built for
// another interface or another precision (-DSPINDRIFT_PRECISION=float) is refused with a message.
struct PluginAbiTag {
    std::uint32_t interfaceVersion;
    std::uint32_t scalarBytes; // sizeof(Scalar): 4 single precision, 8 double
};
inline constexpr PluginAbiTag pluginAbiTag{pluginInterfaceVersion, sizeof(Scalar)};

} // namespace spindrift
