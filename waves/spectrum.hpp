// Wave spectra and the linear component sets synthesised from them: irregular seas (JONSWAP,
// Pierson-Moskowitz) with a reproducible random phase set, and focused wave groups.
#pragma once

#include <cstdint>
#include <vector>

#include "waves/wavemaker.hpp"

namespace swell::waves {

struct SpectrumSpec {
  enum class Shape { Jonswap, PiersonMoskowitz };
  Shape shape = Shape::Jonswap;
  double hs = 0.0;       // significant height Hm0 = 4 sqrt(m0) of the synthesised set [m]
  double tp = 0.0;       // peak period [s]
  double gamma = 3.3;    // JONSWAP peak enhancement (1 gives Pierson-Moskowitz)
  int components = 200;  // number of frequencies
  double f_min = 0.0;    // [Hz]; 0: 0.5 / tp
  double f_max = 0.0;    // [Hz]; 0: 3 / tp
  std::uint64_t seed = 1;
};

// Spectral density shape at frequency f [Hz] (not normalised): the JONSWAP form of Hasselmann
// et al. (1973), f^-5 exp(-5/4 (fp/f)^4) gamma^exp(-(f - fp)^2 / (2 sigma^2 fp^2)), sigma =
// 0.07 below fp and 0.09 above; Pierson-Moskowitz (1964) is gamma = 1.
double spectrum_shape(const SpectrumSpec& spec, double f);

// The component set of an irregular sea: `components` frequencies at the centres of equal bins
// dF over [f_min, f_max], amplitudes a_i = sqrt(2 S(f_i) dF) scaled so that sum a_i^2 / 2 =
// (Hs/4)^2 exactly, phases phi_i = 2 pi u_i with u_i from std::mt19937_64(seed) (its sequence is
// fixed by the C++ standard; u = (x >> 11) 2^-53, no std:: distribution, whose output differs
// between libraries), so a seed gives the same sea on every machine. The sea repeats after
// 1 / dF. Throws std::invalid_argument for Hs, Tp <= 0, gamma < 1, fewer than 1 component or a
// bad frequency range.
std::vector<SurfaceComponent> irregular_sea(const SpectrumSpec& spec);

// A focused wave group (linear "NewWave" focusing): amplitudes proportional to S(f_i) dF with
// sum a_i = crest amplitude A, phases phi_i = k_i x_f - omega_i t_f, so that every component
// has its crest at x_f (distance from the paddle) at time t_f: eta(x_f, t_f) = A.
std::vector<SurfaceComponent> focused_group(const SpectrumSpec& spec, double crest_amplitude,
                                            double focus_distance, double focus_time, double depth,
                                            double g = kStandardGravity);

}  // namespace swell::waves
