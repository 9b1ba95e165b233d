// The blend weights of the isobaric pressure term (Perea & Cordero, seed 000, eqs. 15–16;
// docs/MODELS.md §isobaric), header-only so the unit tests can check them directly.
//
// Relative pressure (eq. 16): 𝒫 = |p_i − p_j| / max(|p_i|, |p_j|), 𝒫 = 0 when both vanish
// (𝒫 ∈ [0, 2]; > 1 only when the signs differ).
// Weight of the difference form (eq. 15 as docs/MODELS.md §isobaric restates its intent):
//   α(𝒫) = (1 + 1/(4δ)) 𝒫² − 𝒫/δ + 2 for 𝒫 < 𝒫*, 0 beyond,
// with 𝒫* the first root of the quadratic (≈ 2δ): α falls smoothly and monotonically from 2
// at 𝒫 = 0 to 0 at 𝒫*, is continuous, and stays in [0, 2]. A real root in (0, 1] exists for
// 0 < δ ≤ 1/4 (discriminant 1/δ² − 2/δ − 8 ≥ 0), the range the model accepts.
// β = 2 − α is the weight of the symmetric sum form.
#pragma once

#include <algorithm>
#include <cmath>

namespace spindrift::isobaric {

struct Blend {
    double a = 0, b = 0, root = 0; // α = a𝒫² − b𝒫 + 2 on [0, root)

    explicit Blend(double delta) : a(1 + 1 / (4 * delta)), b(1 / delta) {
        const double disc = std::max(0.0, b * b - 8 * a);
        // first root, written to avoid cancellation for small δ: 4 / (b + sqrt(b² − 8a))
        root = 4 / (b + std::sqrt(disc));
    }
    static bool validDelta(double delta) { return delta > 0 && delta <= 0.25; }

    static double relativePressure(double pi, double pj) {
        const double m = std::max(std::abs(pi), std::abs(pj));
        return m > 0 ? std::abs(pi - pj) / m : 0.0;
    }
    double alpha(double P) const { return P < root ? std::clamp((a * P - b) * P + 2, 0.0, 2.0) : 0.0; }
    // α(𝒫(p_i, p_j)) for a pair, without a division outside the blend zone (the common case)
    double alpha(double pi, double pj) const {
        const double diff = std::abs(pi - pj), m = std::max(std::abs(pi), std::abs(pj));
        if (m == 0) return 2.0;
        if (diff >= root * m) return 0.0;
        return alpha(diff / m);
    }
};

} // namespace spindrift::isobaric
