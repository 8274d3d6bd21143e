// Accuracy digits: how many significant digits of a simulated value agree with the exact one.
#pragma once

namespace simlab {

/// The most digits a double can carry: -log10(machine epsilon) = 15.65.
extern const double kMaxDigits;

/// -log10(|simulated - exact| / |exact|), clamped to [0, kMaxDigits]. 9.8 digits means the relative error is
/// 10^-9.8. A value equal to the exact one gets kMaxDigits; NaN or infinity gets 0. When the exact value is
/// (near) zero, pass `scale`: the error is then measured relative to max(|exact|, scale).
double accuracyDigits(double simulated, double exact, double scale = 0.0);

}  // namespace simlab
