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

// Bumped whenever a header a plugin compiles against changes its layout or virtual interface.
// A plugin built against another version is refused at load time (never called).
inline constexpr std::uint32_t pluginAbiVersion = 1;

} // namespace spindrift
