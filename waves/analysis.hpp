// Wave analysis of water-level records: zero-crossing statistics, harmonic amplitudes by least
// squares, variance density spectra (Welch) with their parameters, incident/reflected
// separation by three gauges (Mansard & Funke), and reading a gauge column from a CSV file.
// Pure maths over time series (SI units: t [s], eta [m], f [Hz]); used by `swell waves
// analyse` and by validation. Not for the time loop: the functions allocate freely.
#pragma once

#include <array>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "waves/dispersion.hpp"
#include "waves/window.hpp"

namespace swell::waves {

// Every function takes sample times t (strictly increasing) and elevations eta of the same
// length, and a time window [t0, t1] (swell::Window, default: everything); samples outside the
// window are ignored. Bad input (lengths differ, times not increasing, too few samples, a
// window without data) throws std::invalid_argument with the reason.

// ---- Zero-crossing analysis -----------------------------------------------------------------

enum class Crossing { Up, Down };

struct IndividualWave {
  double t_start = 0.0;  // crossing time opening the wave [s]
  double period = 0.0;   // time to the next crossing of the same kind [s]
  double crest = 0.0;    // highest sample in the wave, above the mean level [m]
  double trough = 0.0;   // lowest sample in the wave, above the mean level (negative) [m]
  double height = 0.0;   // crest - trough [m]
};

struct ZeroCrossingResult {
  double mean_level = 0.0;  // removed before the analysis [m]
  std::vector<IndividualWave> waves;
  int count = 0;
  double h_mean = 0.0, h_third = 0.0, h_max = 0.0;  // H_mean, H_1/3, H_max [m]
  double t_mean = 0.0, t_third = 0.0;  // mean period, mean period of the H_1/3 waves [s]
};

// Individual waves between consecutive zero crossings of the same kind (up: eta goes from < 0
// to >= 0; down: from > 0 to <= 0), after removing the mean level (the arithmetic mean of the
// window's samples). Crossing times are interpolated linearly between the two samples that
// bracket the crossing; crest and trough are the extreme samples between two crossings (no
// interpolation: sampling error ~ a (pi dt / T)^2 / 2). The incomplete waves before the first
// and after the last crossing are dropped. H_1/3 and T_1/3: means over the floor(count / 3)
// highest waves (at least one; ties keep time order). Sampling need not be uniform. A record
// without two crossings gives count = 0 and zero statistics.
ZeroCrossingResult zero_crossing(std::span<const double> t, std::span<const double> eta,
                                 Crossing kind = Crossing::Up, Window w = {});

// ---- Harmonic amplitudes --------------------------------------------------------------------

struct Harmonic {
  int n = 0;               // harmonic number (1: the fundamental)
  double frequency = 0.0;  // n f [Hz]
  double cos_coef = 0.0;   // A_n
  double sin_coef = 0.0;   // B_n
  double amplitude = 0.0;  // a_n = sqrt(A_n^2 + B_n^2) [m]
  double phase = 0.0;      // phi_n = atan2(B_n, A_n) [rad], in (-pi, pi]
};

struct HarmonicFit {
  double mean = 0.0;  // a0 [m]
  std::vector<Harmonic> harmonics;
  double rms_residual = 0.0;  // sqrt(mean of (eta - fit)^2) over the samples used [m]
  int samples = 0;
};

// Least-squares fit of eta(t) = a0 + sum_{n=1..N} (A_n cos(n w t) + B_n sin(n w t)),
// w = 2 pi frequency, i.e. a_n cos(n w t - phi_n), over the window's samples (times as given: the
// phases refer to t = 0, not to the window start). Solved by column-pivoting Householder QR
// of the design matrix (not the normal equations). Needs at least 2N + 1 samples; throws if the
// design matrix is rank deficient (window much shorter than a period, or a harmonic at the
// Nyquist frequency of uniformly sampled data). Sampling need not be uniform.
HarmonicFit fit_harmonics(std::span<const double> t, std::span<const double> eta, double frequency,
                          int harmonics, Window w = {});

// ---- Bound and free second harmonic --------------------------------------------------------

// A fitted second harmonic split into the part Stokes' second-order theory binds to the fitted
// first harmonic and the rest, the free second harmonic a paddle sheds (which travels at its
// own, slower speed; Madsen 1971 second-order generation is meant to suppress it). With
// eta = a1 cos(w t - phi1) + a2 cos(2 w t - phi2) at one point, the bound part is
// a1 * r(k, d, 2 a1) cos(2 w t - 2 phi1) (it crests with the first harmonic; r =
// waves::stokes2_harmonic_ratio, k from linear dispersion at w), and the free part is the
// complex difference a2 e^{i phi2} - a1 r e^{i 2 phi1}.
struct SecondHarmonicSplit {
  double bound = 0.0;       // Stokes' bound second-harmonic amplitude for the fitted a1 [m]
  double free = 0.0;        // amplitude of the remainder [m]
  double free_phase = 0.0;  // its phase [rad], in (-pi, pi]
};
SecondHarmonicSplit split_second_harmonic(const Harmonic& first, const Harmonic& second,
                                          double depth, double g = 9.81);

// ---- Uniform sampling -----------------------------------------------------------------------

inline constexpr double kUniformTolerance = 1e-6;

// Throws std::invalid_argument naming the first sample i whose spacing t[i+1] - t[i] differs
// from the mean spacing by more than kUniformTolerance relative (the spectral functions need
// uniform sampling; resample_uniform() makes it). Also checks that times increase.
void check_uniform(std::span<const double> t);

struct Samples {
  std::vector<double> t, eta;
};

// Linear interpolation onto t0 + i dt, i = 0 .. floor((t_last - t0) / dt), from the first
// sample; dt <= 0: the mean spacing (t_last - t0) / (n - 1). Linear interpolation damps a
// component of frequency f by about 1 - (pi f dt_input)^2 / 6 at worst (between samples):
// negligible for waves sampled 20 times a period or more.
Samples resample_uniform(std::span<const double> t, std::span<const double> eta, double dt = 0.0);

// Linear interpolation of (t, eta) at the times `at` (each within [t.front(), t.back()], else
// std::invalid_argument): used to put records with different sample times on one time base.
std::vector<double> interpolate_linear(std::span<const double> t, std::span<const double> eta,
                                       std::span<const double> at);

// ---- Variance density spectrum --------------------------------------------------------------

enum class Detrend { Mean, Linear };
enum class Taper { Hann, Rectangular };

struct SpectrumOptions {
  // Segment length [s], rounded to whole samples; <= 0: about 8 segments with 50 % overlap over
  // the record (the largest length <= 2 n / 9 samples with no prime factor above 5, for the
  // FFT's speed). Longer segments: finer df, more scatter.
  double segment_seconds = 0.0;
  Detrend detrend = Detrend::Linear;  // per segment, before the taper
  Taper taper = Taper::Hann;          // rectangular: for records of whole periods of regular waves
};

struct Spectrum {
  std::vector<double> f;  // 0, df, ..., the Nyquist frequency (or just below it) [Hz]
  std::vector<double> S;  // one-sided variance density [m^2/Hz]
  double df = 0.0, dt = 0.0;
  int segment_samples = 0, segments = 0;
  double variance = 0.0;  // of the window's samples about their mean [m^2]
};

// Welch's (1967) averaged modified periodogram: segments of L samples advancing by L / 2
// (periodic Hann taper w_n = (1 - cos(2 pi n / L)) / 2), each detrended, tapered and
// transformed (Eigen FFT); S(f_k) = c |X_k|^2 / (fs sum_n w_n^2), averaged over segments, with
// c = 2 except at f = 0 and the Nyquist frequency (c = 1). With this normalisation
// sum_k S(f_k) df is the taper-weighted mean square of the detrended segments, i.e. the
// variance for a stationary record (Parseval). Samples after the last whole segment are not
// used. Needs uniform sampling (check_uniform) and at least 8 samples per segment.
Spectrum welch_spectrum(std::span<const double> t, std::span<const double> eta,
                        const SpectrumOptions& opt = {}, Window w = {});

struct Band {
  double fmin = 0.0;
  double fmax = std::numeric_limits<double>::infinity();
  bool contains(double f) const { return f >= fmin && f <= fmax; }
};

struct SpectralParameters {
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;  // m_n = sum f^n S df over the band [m^2 Hz^n]
  double hm0 = 0.0;                     // 4 sqrt(m0) [m]
  double fp = 0.0, tp = 0.0;            // peak frequency [Hz], period 1 / fp [s]
  double tm01 = 0.0, tm02 = 0.0;        // m0 / m1, sqrt(m0 / m2) [s]
  int bins = 0;                         // frequencies used
};

// Moments by the rectangle rule over the bins f_k in the band with finite S (NaN bins, e.g.
// frequencies the reflection analysis skipped, are left out). The peak: the largest S; with
// `interpolate_peak`, refined by the parabola through it and its two neighbours,
// f_p = f_k + df (S_{k-1} - S_{k+1}) / (2 (S_{k-1} - 2 S_k + S_{k+1})) (kept within half a bin;
// not at the band's edges). `f` must be uniformly spaced. Empty band or zero spectrum: zeros.
SpectralParameters spectral_parameters(std::span<const double> f, std::span<const double> S,
                                       Band band = {}, bool interpolate_peak = true);

// ---- Reflection analysis (three gauges) -----------------------------------------------------

struct ReflectionOptions {
  SpectrumOptions spectrum;  // segments, detrend and taper, as for welch_spectrum
  Band band;                 // frequencies separated and integrated
  double g = kStandardGravity;
  // A frequency is skipped when the smaller eigenvalue of the normal matrix, relative to the
  // gauge count, is below this: 1 - |sum_p exp(2 i k x_p)| / 3 < min_conditioning.
  double min_conditioning = 0.1;
};

struct ReflectionResult {
  std::vector<double> f;            // the spectrum's frequencies [Hz]
  std::vector<double> S_incident;   // [m^2/Hz]; NaN outside the band, at f = 0 and where skipped
  std::vector<double> S_reflected;  // [m^2/Hz]; NaN likewise
  std::vector<double> skipped;      // frequencies in the band (f > 0) skipped as ill-conditioned
  SpectralParameters incident, reflected;  // over the band
  double hm0_incident = 0.0, hm0_reflected = 0.0;
  double kr = 0.0;  // sqrt(m0_reflected / m0_incident)
  double df = 0.0;
  int segment_samples = 0, segments = 0;
};

// Mansard & Funke (1980), "The measurement of incident and reflected spectra using a least
// squares method", Proc. 17th ICCE: three simultaneous records at x1 < x2 < x3 on a line, the
// waves' direction of travel. Convention: incident waves travel towards +x (increasing x),
// eta_I = a cos(w t - k x + phi); reflected ones towards -x. Per Fourier frequency f (the same
// segments and taper as welch_spectrum, eta_p's coefficient B_p), the model
// B_p = Z_I e^{-i k x_p} + Z_R e^{+i k x_p} + noise, k from the linear dispersion relation in
// depth d (waves/dispersion.hpp), is solved in the least-squares sense; the 2 x 2 normal
// equations are
//   [ 3      S  ] [Z_I]   [ sum_p B_p e^{+i k x_p} ]
//   [ conj S 3  ] [Z_R] = [ sum_p B_p e^{-i k x_p} ],   S = sum_p e^{2 i k x_p},
// with determinant 9 - |S|^2 = 4 sum_{p<q} sin^2(k x_pq): singular when every gauge spacing
// x_pq is a multiple of L/2 (in particular as f -> 0), where the records cannot tell the two
// waves apart. Those frequencies (see min_conditioning) are skipped and listed. S_I and S_R are
// normalised as welch_spectrum and averaged over segments; the skipped bins' energy is missing
// from both m0. Needs a common uniform time base t for the three records.
ReflectionResult mansard_funke(std::span<const double> t,
                               const std::array<std::span<const double>, 3>& eta,
                               const std::array<double, 3>& x, double depth,
                               const ReflectionOptions& opt = {}, Window w = {});

// The same three-gauge least squares at one frequency, for a regular wave of period T: each
// record's first harmonic at f = 1/T is fitted over the window (fit_harmonics), B_p = A_p - i
// B_p from its cos and sin coefficients, and Z_I, Z_R solve the 2 x 2 system above at that f.
// A spectral estimate (mansard_funke) spreads a regular wave's energy over the bins of a short
// segment; this one does not (its noise is only what the harmonic fit leaves). Throws
// std::invalid_argument where the gauge spacings cannot separate the two waves at f (the
// conditioning test of ReflectionOptions::min_conditioning).
struct RegularReflection {
  double frequency = 0.0;             // [Hz]
  double k = 0.0;                     // linear wave number [rad/m]
  double a_incident = 0.0;            // |Z_I| [m]
  double a_reflected = 0.0;           // |Z_R| [m]
  double kr = 0.0;                    // a_reflected / a_incident
  double residual = 0.0;              // max_p |B_p - model_p| [m]: what the two waves leave
  std::array<double, 3> amplitude{};  // each gauge's fitted first-harmonic amplitude [m]
};
RegularReflection mansard_funke_regular(std::span<const double> t,
                                        const std::array<std::span<const double>, 3>& eta,
                                        const std::array<double, 3>& x, double depth,
                                        double frequency, double g = kStandardGravity,
                                        Window w = {}, double min_conditioning = 0.1);

// ---- Gauge files ----------------------------------------------------------------------------

}  // namespace swell::waves
