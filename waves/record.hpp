// Linear propagation of a measured paddle record: the surface elevation that linear wavemaker
// theory predicts at a distance from the paddle, for a paddle displacement sampled in time
// (pure maths, SI units). Used by `swell waves predict` to check a measured piston record and
// its probes against the theory the SPH paddle is built on (waves/wavemaker.hpp).
//
// Each Fourier component X_j sin(w_j t + phi_j) of the displacement makes, far from the paddle,
// the progressive wave F(k_j d) X_j cos(w_j t + phi_j - k_j x) (Biesel; the elevation leads the
// displacement by a quarter period). Evanescent modes are left out, so the prediction holds a
// few depths away from the paddle and beyond. The record is extended to a power of two at least
// twice its length, blending its last value back to its first with a raised cosine over the
// extension, so that the periodic transform sees neither a jump nor wrap-around within the
// record (a wave needs the extension's duration to come round again).
#pragma once

#include <vector>

#include "waves/dispersion.hpp"
#include "waves/wavemaker.hpp"

namespace swell::waves {

// eta(x, t_n) for the displacement record X_n = X(t_0 + n dt), n = 0..N-1 (the mean of the
// record does not make a wave). Components above f_max [Hz] are dropped (0: keep all below the
// Nyquist frequency). Throws std::invalid_argument for fewer than 4 samples, dt <= 0 or x < 0.
std::vector<double> propagate_paddle_record(const std::vector<double>& displacement, double dt,
                                            const PaddleGeometry& paddle, double x,
                                            double g = kStandardGravity, double f_max = 0.0);

}  // namespace swell::waves
