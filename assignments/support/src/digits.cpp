#include "simlab/digits.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simlab {

const double kMaxDigits = -std::log10(std::numeric_limits<double>::epsilon());

double accuracyDigits(double simulated, double exact, double scale) {
    if (!std::isfinite(simulated) || !std::isfinite(exact)) return 0.0;
    const double error = std::abs(simulated - exact);
    if (error == 0.0) return kMaxDigits;
    const double reference = std::max(std::abs(exact), std::abs(scale));
    if (reference == 0.0) return 0.0;
    const double digits = -std::log10(error / reference);
    return digits > 0 ? std::min(digits, kMaxDigits) : 0.0;  // never -0
}

}  // namespace simlab
