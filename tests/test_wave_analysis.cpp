// Wave analysis (waves/analysis.hpp) on synthetic records whose answers are known:
// zero-crossing statistics, least-squares harmonics, Welch spectra (Parseval, a sinusoid, a
// JONSWAP sea), the Mansard-Funke three-gauge separation (regular and irregular waves with a
// known reflection coefficient), gauge CSV columns, and `swell waves analyse` end to end.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "validation/gauge_column.hpp"
#include "waves/analysis.hpp"
#include "waves/dispersion.hpp"
#include "waves/theory.hpp"

namespace swell::waves {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

struct Record {
  std::vector<double> t, eta;
};

template <class F>
Record sample(double t0, double t1, double dt, F&& f) {
  Record r;
  const auto n = static_cast<std::size_t>(std::llround((t1 - t0) / dt)) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = t0 + static_cast<double>(i) * dt;
    r.t.push_back(t);
    r.eta.push_back(f(t));
  }
  return r;
}

double integral(const Spectrum& s) {
  double m0 = 0.0;
  for (const double v : s.S) m0 += v * s.df;
  return m0;
}

// ---- Zero crossing ---------------------------------------------------------------------------

TEST(ZeroCrossing, SinusoidHeightAndPeriodExact) {
  const double a = 0.1, T = 1.7, phase = 0.4, dt = 0.005, t_end = 30.0;
  const double omega = 2.0 * kPi / T;
  const Record r =
      sample(0.0, t_end, dt, [&](double t) { return 0.5 + a * std::cos(omega * t + phase); });
  // Up-crossings of cos(theta) at theta = 3 pi / 2 (mod 2 pi).
  int crossings = 0;
  for (int m = -1; m < 100; ++m) {
    const double tc = (1.5 * kPi - phase + 2.0 * kPi * m) / omega;
    if (tc > 0.0 && tc < t_end) ++crossings;
  }
  for (const Crossing kind : {Crossing::Up, Crossing::Down}) {
    const auto z = zero_crossing(r.t, r.eta, kind);
    EXPECT_NEAR(z.mean_level, 0.5, 2e-3);
    if (kind == Crossing::Up) {
      EXPECT_EQ(z.count, crossings - 1);
    }
    ASSERT_GE(z.count, 15);
    for (const auto& w : z.waves) {
      EXPECT_NEAR(w.height, 2.0 * a, 2e-5);  // sampling error a (pi dt / T)^2 / 2 = 4e-6
      EXPECT_NEAR(w.period, T, 1e-6);
      EXPECT_NEAR(w.crest, -w.trough, 5e-3);  // the sample mean is off by < a T / (pi t_end)
    }
    EXPECT_NEAR(z.h_third, 2.0 * a, 2e-5);
    EXPECT_NEAR(z.h_max, 2.0 * a, 2e-5);
    EXPECT_NEAR(z.t_mean, T, 1e-6);
    EXPECT_NEAR(z.t_third, T, 1e-6);
  }
  // A window: only the waves inside it.
  const auto part = zero_crossing(r.t, r.eta, Crossing::Up, Window{10.0, 20.0});
  EXPECT_GE(part.count, 4);
  EXPECT_LE(part.count, 6);
  for (const auto& w : part.waves) EXPECT_GE(w.t_start, 10.0);
  for (const auto& w : part.waves) EXPECT_LE(w.t_start + w.period, 20.0);
}

TEST(ZeroCrossing, SumOfRegularWaves) {
  // A fundamental and a smaller second harmonic: one up-crossing per period T, every wave of
  // the same height, found here by dense evaluation over one period.
  const double a1 = 1.0, a2 = 0.2, T = 2.5, omega = 2.0 * kPi / T;
  auto eta = [&](double t) {
    return a1 * std::cos(omega * t) + a2 * std::cos(2.0 * omega * t + 0.7);
  };
  double hi = -1e9, lo = 1e9;
  for (int i = 0; i < 200000; ++i) {
    const double v = eta(T * i / 200000.0);
    hi = std::max(hi, v);
    lo = std::min(lo, v);
  }
  const Record r = sample(0.0, 40.0 * T, 0.002, eta);
  const auto z = zero_crossing(r.t, r.eta);
  EXPECT_EQ(z.count, 39);
  for (const auto& w : z.waves) {
    EXPECT_NEAR(w.height, hi - lo, 1e-5);
    EXPECT_NEAR(w.period, T, 1e-6);
  }
  EXPECT_NEAR(z.h_mean, hi - lo, 1e-5);
}

TEST(ZeroCrossing, TwoTrainsHighestThirdAndMax) {
  // 4 waves H = 2 m, T = 2 s, then 8 waves H = 1 m, T = 1 s (equal slopes at the crossings, so
  // the small mean offset shifts every crossing alike).
  auto eta = [](double t) {
    if (t < 8.0) return std::sin(kPi * t);
    return 0.5 * std::sin(2.0 * kPi * (t - 8.0));
  };
  const Record r = sample(-0.3, 16.3, 0.001, eta);
  const auto z = zero_crossing(r.t, r.eta);
  ASSERT_EQ(z.count, 12);
  EXPECT_NEAR(z.h_max, 2.0, 1e-4);
  EXPECT_NEAR(z.h_third, 2.0, 1e-4);  // the 4 highest of 12
  EXPECT_NEAR(z.h_mean, 16.0 / 12.0, 1e-4);
  EXPECT_NEAR(z.t_mean, 16.0 / 12.0, 1e-4);
  EXPECT_NEAR(z.t_third, 2.0, 1e-4);
  EXPECT_NEAR(z.waves.front().height, 2.0, 1e-4);
  EXPECT_NEAR(z.waves.back().height, 1.0, 1e-4);
  EXPECT_NEAR(z.waves.back().period, 1.0, 1e-4);
  const auto down = zero_crossing(r.t, r.eta, Crossing::Down);
  EXPECT_EQ(down.count, 11);  // down-crossings at 1, 3, 5, 7 then 8.5 ... 15.5
  EXPECT_NEAR(down.h_max, 2.0, 1e-4);
  // Down-crossing waves: 3 of H = 2, the 7 - 8.5 s wave from a trough of -1 to a crest of 0.5,
  // 7 of H = 1; H_1/3 is over floor(11 / 3) = 3 waves.
  EXPECT_NEAR(down.h_third, 2.0, 1e-4);
  EXPECT_NEAR(down.h_mean, 14.5 / 11.0, 1e-4);
  EXPECT_NEAR(down.waves[3].height, 1.5, 1e-4);
  EXPECT_NEAR(down.waves[3].crest, 0.5, 2e-3);

  // Too little data or a bad window is an error, not a silent zero.
  EXPECT_THROW(zero_crossing(r.t, r.eta, Crossing::Up, Window{100.0, 200.0}),
               std::invalid_argument);
  std::vector<double> t_bad = r.t;
  t_bad[50] = t_bad[49];
  EXPECT_THROW(zero_crossing(t_bad, r.eta), std::invalid_argument);
}

// ---- Harmonics -------------------------------------------------------------------------------

TEST(Harmonics, StokesLikeSignalWithNoise) {
  const double T = 1.6, omega = 2.0 * kPi / T;
  const double a[4] = {0.2, 0.05, 0.012, 0.003};
  const double phi[4] = {0.0, 0.3, -1.1, 2.0};
  auto clean = [&](double t) {
    double v = a[0];
    for (int n = 1; n <= 3; ++n) v += a[n] * std::cos(n * omega * t - phi[n]);
    return v;
  };
  std::mt19937 rng(20261202);
  std::normal_distribution<double> noise(0.0, 0.002);
  Record r = sample(0.0, 40.0, 0.01, clean);
  for (auto& v : r.eta) v += noise(rng);

  const auto fit = fit_harmonics(r.t, r.eta, 1.0 / T, 3, Window{5.0, 35.0});
  EXPECT_EQ(fit.samples, 3001);
  ASSERT_EQ(fit.harmonics.size(), 3u);
  // The standard error of each coefficient is sigma sqrt(2 / M) = 5e-5.
  EXPECT_NEAR(fit.mean, a[0], 2e-4);
  for (int n = 1; n <= 3; ++n) {
    const auto& h = fit.harmonics[n - 1];
    EXPECT_EQ(h.n, n);
    EXPECT_NEAR(h.frequency, n / T, 1e-12);
    EXPECT_NEAR(h.amplitude, a[n], 3e-4) << n;
    EXPECT_NEAR(h.phase, phi[n], 3e-4 / a[n]) << n;
  }
  EXPECT_NEAR(fit.rms_residual, 0.002, 2e-4);

  // Without noise, on jittered (non-uniform) sample times: exact.
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  Record j = sample(0.0, 10.0, 0.01, clean);
  for (std::size_t i = 1; i + 1 < j.t.size(); ++i) {
    j.t[i] += jitter(rng);
    j.eta[i] = clean(j.t[i]);
  }
  const auto exact = fit_harmonics(j.t, j.eta, 1.0 / T, 3);
  EXPECT_NEAR(exact.mean, a[0], 1e-12);
  for (int n = 1; n <= 3; ++n) {
    EXPECT_NEAR(exact.harmonics[n - 1].amplitude, a[n], 1e-12);
    EXPECT_NEAR(exact.harmonics[n - 1].phase, phi[n], 1e-9);
  }
  EXPECT_LT(exact.rms_residual, 1e-12);
  // A harmonic at the Nyquist frequency of uniform samples cannot be fitted.
  const Record nyq = sample(0.0, 10.0, 0.25, clean);
  EXPECT_THROW(fit_harmonics(nyq.t, nyq.eta, 1.0, 2), std::invalid_argument);
}

// Stokes' second-order wave at a gauge has no free second harmonic; adding one of known
// amplitude and phase is recovered exactly (noise-free samples, whole periods).
TEST(Harmonics, SecondHarmonicSplitsIntoBoundAndFree) {
  const double H = 0.05, T = 1.2, d = 0.4, x = 1.13, omega = 2.0 * kPi / T;
  const double k = wave_number(omega, d);
  const double bound = H / 2 * stokes2_harmonic_ratio(k, d, H);
  const double F = 0.0011, psi = 0.9;
  for (const double free : {0.0, F}) {
    Record r = sample(0.0, 12.0, 0.01, [&](double t) {
      return stokes2_elevation(H, T, d, x, t) + free * std::cos(2 * omega * t - psi);
    });
    const auto fit = fit_harmonics(r.t, r.eta, 1.0 / T, 3);
    const auto sp = split_second_harmonic(fit.harmonics[0], fit.harmonics[1], d);
    EXPECT_NEAR(fit.harmonics[0].amplitude, H / 2, 1e-12);
    EXPECT_NEAR(sp.bound, bound, 1e-12);
    EXPECT_NEAR(sp.free, free, 1e-12);
    if (free > 0.0) EXPECT_NEAR(sp.free_phase, psi, 1e-9);
  }
  // The bound part is not simply the fitted second harmonic: a first harmonic shifted in time
  // moves the bound part with it (phase 2 phi1), so a free part in antiphase is seen.
  Record r = sample(0.0, 12.0, 0.01, [&](double t) {
    return H / 2 * std::cos(omega * t - 0.5) + bound * std::cos(2 * omega * t - 1.0 - kPi);
  });
  const auto fit = fit_harmonics(r.t, r.eta, 1.0 / T, 2);
  EXPECT_NEAR(split_second_harmonic(fit.harmonics[0], fit.harmonics[1], d).free, 2 * bound, 1e-12);
  EXPECT_THROW(split_second_harmonic(fit.harmonics[1], fit.harmonics[0], d), std::invalid_argument);
}

// ---- Spectrum --------------------------------------------------------------------------------

TEST(Spectrum, ParsevalIntegralEqualsVariance) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  Record r = sample(0.0, 65535 * 0.05, 0.05, [](double t) {
    return 0.3 + 0.02 * std::cos(2.0 * kPi * 0.31 * t + 0.2) + 0.01 * std::cos(2.0 * kPi * 1.7 * t);
  });
  for (auto& v : r.eta) v += noise(rng);
  for (const Detrend d : {Detrend::Linear, Detrend::Mean}) {
    SpectrumOptions opt;
    opt.detrend = d;
    const Spectrum s = welch_spectrum(r.t, r.eta, opt);
    EXPECT_EQ(s.segments, 8);
    EXPECT_NEAR(s.f.back(), 10.0, s.df);  // Nyquist of dt = 0.05 s
    EXPECT_NEAR(integral(s) / s.variance, 1.0, 0.01);
    opt.segment_seconds = 200.0;
    const Spectrum s2 = welch_spectrum(r.t, r.eta, opt);
    EXPECT_EQ(s2.segment_samples, 4000);
    EXPECT_NEAR(s2.df, 1.0 / 200.0, 1e-12);
    EXPECT_NEAR(integral(s2) / s2.variance, 1.0, 0.01);
  }
  // One segment, no taper, mean removed: Parseval holds exactly, for even and odd lengths (the
  // one-sided factor at f = 0 and at the Nyquist frequency).
  for (const std::size_t n : {1000u, 1001u}) {
    const std::vector<double> t(r.t.begin(), r.t.begin() + n), x(r.eta.begin(), r.eta.begin() + n);
    SpectrumOptions opt;
    opt.segment_seconds = static_cast<double>(n) * 0.05;
    opt.taper = Taper::Rectangular;
    opt.detrend = Detrend::Mean;
    const Spectrum s = welch_spectrum(t, x, opt);
    EXPECT_EQ(s.segments, 1);
    EXPECT_EQ(s.segment_samples, static_cast<int>(n));
    EXPECT_NEAR(integral(s) / s.variance, 1.0, 1e-12) << n;
  }
}

TEST(Spectrum, SinusoidHm0AndPeakPeriod) {
  const double a = 0.3, T = 2.3;  // 1/T is between two bins of the 100 s segments
  const Record r =
      sample(0.0, 400.0, 0.02, [&](double t) { return a * std::sin(2.0 * kPi * t / T); });
  SpectrumOptions opt;
  opt.segment_seconds = 100.0;
  const Spectrum s = welch_spectrum(r.t, r.eta, opt);
  EXPECT_EQ(s.segments, 7);
  const auto plain = spectral_parameters(s.f, s.S, {}, false);
  const auto refined = spectral_parameters(s.f, s.S, {}, true);
  EXPECT_NEAR(plain.hm0 / (2.0 * std::sqrt(2.0) * a), 1.0, 0.01);
  EXPECT_NEAR(plain.hm0 / (4.0 * std::sqrt(s.variance)), 1.0, 0.01);
  std::printf("sinusoid: fp error %.4f bins (peak bin), %.4f bins (parabola)\n",
              (plain.fp - 1.0 / T) / s.df, (refined.fp - 1.0 / T) / s.df);
  EXPECT_LE(std::abs(plain.fp - 1.0 / T), 0.5 * s.df + 1e-12);
  EXPECT_LT(std::abs(refined.fp - 1.0 / T), 0.1 * s.df);
  EXPECT_LT(std::abs(refined.fp - 1.0 / T), std::abs(plain.fp - 1.0 / T));
  EXPECT_NEAR(refined.tp, T, 0.1 * s.df * T * T);
  // A narrow band spectrum: the mean periods are the period too (Hann leakage is symmetric).
  EXPECT_NEAR(plain.tm01, T, 0.01 * T);
  EXPECT_NEAR(plain.tm02, T, 0.01 * T);
  // A band that excludes the wave holds (almost) nothing.
  const auto off = spectral_parameters(s.f, s.S, Band{1.0, 5.0});
  EXPECT_LT(off.hm0, 1e-3 * plain.hm0);

  // Non-uniform times are refused, naming the sample; resampling makes them usable.
  Record j = r;
  j.t[1234] += 1e-4;
  try {
    welch_spectrum(j.t, j.eta, opt);
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample 1233"), std::string::npos) << e.what();
  }
  const Samples u = resample_uniform(j.t, j.eta);
  EXPECT_EQ(u.t.size(), r.t.size());
  EXPECT_NO_THROW(check_uniform(u.t));
  EXPECT_NEAR(
      spectral_parameters(welch_spectrum(u.t, u.eta, opt).f, welch_spectrum(u.t, u.eta, opt).S)
              .hm0 /
          plain.hm0,
      1.0, 1e-3);
}

// Components of a JONSWAP spectrum (Hasselmann et al. 1973, gamma = 3.3) at the record's
// Fourier frequencies, amplitudes a_j = sqrt(2 S(f_j) df), random phases.
struct Sea {
  std::vector<double> f, a, phase;
  double m0 = 0.0;  // sum a_j^2 / 2
};

Sea jonswap(double fp, double hm0, double f_lo, double f_hi, double df, unsigned seed) {
  Sea sea;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 2.0 * kPi);
  for (int j = static_cast<int>(std::ceil(f_lo / df)); j * df <= f_hi; ++j) {
    const double f = j * df;
    const double sigma = f <= fp ? 0.07 : 0.09;
    const double peak =
        std::pow(3.3, std::exp(-std::pow(f - fp, 2) / (2.0 * sigma * sigma * fp * fp)));
    const double S = std::pow(f, -5.0) * std::exp(-1.25 * std::pow(fp / f, 4.0)) * peak;
    sea.f.push_back(f);
    sea.a.push_back(std::sqrt(2.0 * S * df));
    sea.phase.push_back(uni(rng));
  }
  double m0 = 0.0;
  for (const double v : sea.a) m0 += 0.5 * v * v;
  const double scale = hm0 / (4.0 * std::sqrt(m0));
  for (auto& v : sea.a) v *= scale;
  sea.m0 = m0 * scale * scale;
  return sea;
}

TEST(Spectrum, JonswapSeaReproducesItsHm0AndTp) {
  const double fp = 0.5, hm0 = 0.1, duration = 1200.0, dt = 0.05;
  const Sea sea = jonswap(fp, hm0, 0.2, 2.0, 1.0 / duration, 11);
  Record r;
  for (int i = 0; i * dt < duration; ++i) {
    const double t = i * dt;
    double v = 0.0;
    for (std::size_t j = 0; j < sea.f.size(); ++j)
      v += sea.a[j] * std::cos(2.0 * kPi * sea.f[j] * t + sea.phase[j]);
    r.t.push_back(t);
    r.eta.push_back(v);
  }
  SpectrumOptions opt;
  opt.segment_seconds = 100.0;
  const Spectrum s = welch_spectrum(r.t, r.eta, opt);
  const auto p = spectral_parameters(s.f, s.S);
  std::printf("JONSWAP: Hm0 %.5f (built %.5f), Tp %.4f s (built %.4f), Tm01 %.4f, Tm02 %.4f\n",
              p.hm0, 4.0 * std::sqrt(sea.m0), p.tp, 1.0 / fp, p.tm01, p.tm02);
  EXPECT_NEAR(p.hm0 / (4.0 * std::sqrt(sea.m0)), 1.0, 0.03);
  EXPECT_NEAR(p.tp * fp, 1.0, 0.05);
  // The moments' periods against those of the built components.
  double m1 = 0.0, m2 = 0.0;
  for (std::size_t j = 0; j < sea.f.size(); ++j) {
    m1 += sea.f[j] * 0.5 * sea.a[j] * sea.a[j];
    m2 += sea.f[j] * sea.f[j] * 0.5 * sea.a[j] * sea.a[j];
  }
  EXPECT_NEAR(p.tm01 / (sea.m0 / m1), 1.0, 0.03);
  EXPECT_NEAR(p.tm02 / std::sqrt(sea.m0 / m2), 1.0, 0.03);
}

// ---- Reflection ------------------------------------------------------------------------------

// Incident components travelling towards +x and reflected ones (amplitude kr a, phase shift
// `shift`) towards -x, at the three gauges.
struct Gauges {
  std::vector<double> t;
  std::array<std::vector<double>, 3> eta;
};

Gauges three_gauges(const std::vector<double>& f, const std::vector<double>& a,
                    const std::vector<double>& phase, const std::vector<double>& shift, double kr,
                    const std::array<double, 3>& x, double depth, double duration, double dt) {
  // eta_p(t) = Re sum_j c_pj e^{i w_j t}; e^{i w_j t} by rotation, recomputed every 256 samples.
  using C = std::complex<double>;
  const std::size_t m = f.size();
  std::array<std::vector<C>, 3> c;
  for (int p = 0; p < 3; ++p)
    for (std::size_t j = 0; j < m; ++j) {
      const double k = wave_number(2.0 * kPi * f[j], depth);
      c[p].push_back(std::polar(a[j], -k * x[p] + phase[j]) +
                     std::polar(kr * a[j], k * x[p] + phase[j] + shift[j]));
    }
  std::vector<C> z(m), step(m);
  for (std::size_t j = 0; j < m; ++j) step[j] = std::polar(1.0, 2.0 * kPi * f[j] * dt);
  Gauges g;
  for (int i = 0; i * dt < duration; ++i) {
    const double t = i * dt;
    for (std::size_t j = 0; j < m; ++j)
      z[j] = i % 256 == 0 ? std::polar(1.0, 2.0 * kPi * f[j] * t) : z[j] * step[j];
    g.t.push_back(t);
    for (int p = 0; p < 3; ++p) {
      double v = 0.0;
      for (std::size_t j = 0; j < m; ++j) v += (z[j] * c[p][j]).real();
      g.eta[p].push_back(v);
    }
  }
  return g;
}

TEST(MansardFunke, RegularWavesKnownReflection) {
  const double a = 0.05, T = 2.0, depth = 0.5, kr = 0.3;
  const double L = wave_length(T, depth);
  const std::array<double, 3> x = {1.0, 1.0 + 0.12 * L, 1.0 + 0.31 * L};
  const Gauges g = three_gauges({1.0 / T}, {a}, {0.4}, {0.8}, kr, x, depth, 200.0, 0.02);
  ReflectionOptions opt;
  opt.spectrum.segment_seconds = 100.0;
  const auto r = mansard_funke(g.t, {g.eta[0], g.eta[1], g.eta[2]}, x, depth, opt);
  std::printf("regular: Kr %.5f (built %.2f), Hm0_I %.5f (built %.5f), Hm0_R %.5f, %zu skipped\n",
              r.kr, kr, r.hm0_incident, 2.0 * std::sqrt(2.0) * a, r.hm0_reflected,
              r.skipped.size());
  EXPECT_NEAR(r.kr / kr, 1.0, 0.02);
  EXPECT_NEAR(r.hm0_incident / (2.0 * std::sqrt(2.0) * a), 1.0, 0.02);
  EXPECT_NEAR(r.hm0_reflected / (2.0 * std::sqrt(2.0) * kr * a), 1.0, 0.02);
  EXPECT_NEAR(r.incident.tp, T, 0.01 * T);
  // The skipped frequencies are those where every spacing is near a multiple of L/2 (f -> 0).
  for (const double f : r.skipped) {
    const double k = wave_number(2.0 * kPi * f, depth);
    std::complex<double> s = 0.0;
    for (const double xp : x) s += std::polar(1.0, 2.0 * k * xp);
    EXPECT_LT(1.0 - std::abs(s) / 3.0, opt.min_conditioning) << f;
  }
  ASSERT_FALSE(r.skipped.empty());
  EXPECT_LT(r.skipped.front(), 0.1);

  // Whole periods, one segment, no taper: the separation is exact.
  ReflectionOptions exact;
  exact.spectrum.segment_seconds = 200.0;
  exact.spectrum.taper = Taper::Rectangular;
  exact.spectrum.detrend = Detrend::Mean;  // a line fitted to whole periods is not zero
  const auto e = mansard_funke(g.t, {g.eta[0], g.eta[1], g.eta[2]}, x, depth, exact);
  EXPECT_NEAR(e.kr, kr, 1e-6);
  EXPECT_NEAR(e.hm0_incident, 2.0 * std::sqrt(2.0) * a, 1e-6);

  // Swapping the roles (gauges mirrored, x -> -x) swaps incident and reflected.
  const std::array<double, 3> mirrored = {-x[2], -x[1], -x[0]};
  const auto m = mansard_funke(g.t, {g.eta[2], g.eta[1], g.eta[0]}, mirrored, depth, exact);
  EXPECT_NEAR(m.kr, 1.0 / kr, 1e-5);
  EXPECT_THROW(mansard_funke(g.t, {g.eta[0], g.eta[1], g.eta[2]}, {x[1], x[0], x[2]}, depth),
               std::invalid_argument);
}

// The regular-wave separation (one frequency, each gauge's first harmonic by least squares)
// is exact for a pure incident + reflected pair whatever the record's length, also over a
// window that is not a whole number of periods, where a spectral estimate's bins leak; a
// second harmonic and noise on top move it little; a single incident wave gives Kr 0.
TEST(MansardFunke, RegularSeparationAtOneFrequency) {
  const double a = 0.02, T = 1.2, depth = 0.4, kr = 0.1;
  const double L = wave_length(T, depth);
  const std::array<double, 3> x = {5.95, 5.95 + 0.098 * L, 5.95 + 0.247 * L};
  const Gauges g = three_gauges({1.0 / T}, {a}, {0.4}, {0.8}, kr, x, depth, 10.3, 0.01);
  const auto r = mansard_funke_regular(g.t, {g.eta[0], g.eta[1], g.eta[2]}, x, depth, 1.0 / T);
  EXPECT_NEAR(r.kr, kr, 1e-9);
  EXPECT_NEAR(r.a_incident, a, 1e-11);
  EXPECT_NEAR(r.a_reflected, kr * a, 1e-11);
  EXPECT_LT(r.residual, 1e-11);
  EXPECT_NEAR(r.k, 2.0 * kPi / L, 1e-9);
  // The spectral estimate on the same 10.3 s record (one segment): leakage, a worse Kr.
  ReflectionOptions opt;
  opt.spectrum.segment_seconds = 10.3;
  const auto sp = mansard_funke(g.t, {g.eta[0], g.eta[1], g.eta[2]}, x, depth, opt);
  std::printf("regular separation Kr %.6f, spectral on the same record %.4f (built %.2f)\n", r.kr,
              sp.kr, kr);

  // A second harmonic (a wave of its own, 2 f, 10 % of a) and noise of 1 % of a.
  const Gauges g2 = three_gauges({1.0 / T, 2.0 / T}, {a, 0.1 * a}, {0.4, 1.3}, {0.8, 0.0}, kr, x,
                                 depth, 10.3, 0.01);
  std::array<std::vector<double>, 3> noisy = g2.eta;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.01 * a);
  for (auto& e : noisy)
    for (double& v : e) v += noise(rng);
  const auto n = mansard_funke_regular(g2.t, {noisy[0], noisy[1], noisy[2]}, x, depth, 1.0 / T);
  EXPECT_NEAR(n.kr, kr, 0.01);
  EXPECT_NEAR(n.a_incident / a, 1.0, 0.01);

  // Incident only: nothing reflected.
  const Gauges gi = three_gauges({1.0 / T}, {a}, {0.4}, {0.0}, 0.0, x, depth, 10.3, 0.01);
  EXPECT_LT(mansard_funke_regular(gi.t, {gi.eta[0], gi.eta[1], gi.eta[2]}, x, depth, 1.0 / T).kr,
            1e-9);
  // Mirrored gauges swap the two waves.
  const std::array<double, 3> mirrored = {-x[2], -x[1], -x[0]};
  EXPECT_NEAR(
      mansard_funke_regular(g.t, {g.eta[2], g.eta[1], g.eta[0]}, mirrored, depth, 1.0 / T).kr,
      1.0 / kr, 1e-7);
  // Gauges L/2 apart cannot separate the two waves; positions must increase.
  const std::array<double, 3> half = {1.0, 1.0 + 0.5 * L, 1.0 + L};
  EXPECT_THROW(mansard_funke_regular(g.t, {g.eta[0], g.eta[1], g.eta[2]}, half, depth, 1.0 / T),
               std::invalid_argument);
  EXPECT_THROW(mansard_funke_regular(g.t, {g.eta[0], g.eta[1], g.eta[2]}, {x[1], x[0], x[2]}, depth,
                                     1.0 / T),
               std::invalid_argument);
}

TEST(MansardFunke, IrregularWavesKnownReflection) {
  const double depth = 0.6, kr = 0.3, duration = 1200.0, dt = 0.05;
  const Sea sea = jonswap(0.6, 0.08, 0.3, 1.3, 1.0 / duration, 5);
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> uni(0.0, 2.0 * kPi);
  std::vector<double> shift(sea.f.size());
  for (auto& s : shift) s = uni(rng);
  const std::array<double, 3> x = {0.0, 0.25, 0.65};
  const Gauges g = three_gauges(sea.f, sea.a, sea.phase, shift, kr, x, depth, duration, dt);
  ReflectionOptions opt;
  opt.spectrum.segment_seconds = 100.0;
  opt.band = Band{0.25, 1.5};
  const auto r = mansard_funke(g.t, {g.eta[0], g.eta[1], g.eta[2]}, x, depth, opt);
  const double hm0 = 4.0 * std::sqrt(sea.m0);
  std::printf("irregular: Kr %.5f (built %.2f), Hm0_I %.5f (built %.5f), Tp_I %.4f, %zu skipped\n",
              r.kr, kr, r.hm0_incident, hm0, r.incident.tp, r.skipped.size());
  EXPECT_NEAR(r.kr / kr, 1.0, 0.02);
  EXPECT_NEAR(r.hm0_incident / hm0, 1.0, 0.02);
  EXPECT_NEAR(r.hm0_reflected / (kr * hm0), 1.0, 0.02);
  EXPECT_NEAR(r.incident.tp * 0.6, 1.0, 0.05);
  // Outside the band and at f = 0 nothing is reported.
  EXPECT_TRUE(std::isnan(r.S_incident[0]));
  EXPECT_TRUE(std::isnan(r.S_incident.back()));
  // Welch's estimate of a random-phase sea scatters by ~1-2 % (the statistics of the segments);
  // the separation itself is exact: one untapered segment over the whole record, whose Fourier
  // frequencies are the components'.
  ReflectionOptions whole = opt;
  whole.spectrum.segment_seconds = duration;
  whole.spectrum.taper = Taper::Rectangular;
  whole.spectrum.detrend = Detrend::Mean;
  const auto e = mansard_funke(g.t, {g.eta[0], g.eta[1], g.eta[2]}, x, depth, whole);
  std::printf("irregular, one untapered segment: Kr %.7f, Hm0_I %.7f\n", e.kr, e.hm0_incident);
  EXPECT_NEAR(e.kr, kr, 1e-6);
  EXPECT_NEAR(e.hm0_incident / hm0, 1.0, 1e-6);
}

// ---- Gauge files and the command line --------------------------------------------------------

fs::path test_dir(const std::string& name) {
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_wave_analysis" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A gauge CSV as Swell writes it: comments, `time [s],<name> [m],...`, %.9g numbers.
void write_gauge_csv(const fs::path& path, const std::vector<std::string>& names,
                     const std::vector<double>& t, const std::vector<std::vector<double>>& cols) {
  std::ofstream out(path);
  out << "# gauges of a synthetic case\n# kind: height\ntime [s]";
  for (const auto& n : names) out << ',' << n << " [m]";
  out << '\n';
  char buf[40];
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.9g", t[i]);
    out << buf;
    for (const auto& c : cols) {
      std::snprintf(buf, sizeof buf, "%.9g", c[i]);
      out << ',' << buf;
    }
    out << '\n';
  }
}

TEST(GaugeFile, ColumnByNameWithOrWithoutUnit) {
  const fs::path dir = test_dir("read");
  const fs::path file = dir / "gauges_height.csv";
  write_gauge_csv(file, {"H1", "H2"}, {0.0, 0.1, 0.2}, {{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}});
  const auto a = read_gauge_column(file.string(), "H2");
  const auto b = read_gauge_column(file.string(), "H2 [m]");
  EXPECT_EQ(a.name, "H2");
  EXPECT_EQ(a.unit, "m");
  EXPECT_EQ(a.eta, (std::vector<double>{4.0, 5.0, 6.0}));
  EXPECT_EQ(b.eta, a.eta);
  EXPECT_EQ(b.t, (std::vector<double>{0.0, 0.1, 0.2}));
  auto message = [&](const std::string& path, const std::string& column) {
    try {
      read_gauge_column(path, column);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing = message(file.string(), "H7");
  EXPECT_NE(missing.find(file.string()), std::string::npos) << missing;
  EXPECT_NE(missing.find("H7"), std::string::npos) << missing;
  EXPECT_NE(missing.find("H1, H2"), std::string::npos) << missing;
  EXPECT_NE(message(file.string(), "H1 [Pa]").find("[m]"), std::string::npos);
  {
    std::ofstream bad(dir / "bad.csv");
    bad << "# c\ntime [s],H1 [m]\n0,1\n0.1,x1\n";
  }
  const std::string malformed = message((dir / "bad.csv").string(), "H1");
  EXPECT_NE(malformed.find("bad.csv:4"), std::string::npos) << malformed;
  EXPECT_NE(malformed.find("not a number"), std::string::npos) << malformed;
  EXPECT_NE(message((dir / "none.csv").string(), "H1").find("none.csv"), std::string::npos);
}

struct CommandResult {
  int code = -1;
  std::string output;
};

CommandResult swell_command(const std::string& args) {
  const std::string cmd =
      "timeout 60 " + std::string(SWELL_BINARY_DIR) + "/swell " + args + " 2>&1";
  CommandResult r;
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The number after `key` in the report (NaN if absent).
double reported(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + key.size(), nullptr);
}

TEST(WavesAnalyseCommand, ReportsKnownNumbers) {
  const double a = 0.05, T = 2.0, depth = 0.5, kr = 0.3;
  const double L = wave_length(T, depth);
  const std::array<double, 3> x = {1.0, 1.0 + 0.12 * L, 1.0 + 0.31 * L};
  const Gauges g = three_gauges({1.0 / T}, {a}, {0.4}, {0.8}, kr, x, depth, 200.0, 0.02);
  const fs::path dir = test_dir("cli");
  const fs::path file = dir / "gauges_height.csv";
  write_gauge_csv(file, {"H1", "H2", "H3"}, g.t, {g.eta[0], g.eta[1], g.eta[2]});
  // The local amplitude at gauge 1: |a e^{-i k x1 + i 0.4} + kr a e^{i k x1 + i (0.4 + 0.8)}|.
  const double k = wave_number(2.0 * kPi / T, depth);
  const double local =
      std::abs(std::polar(a, -k * x[0] + 0.4) + std::polar(kr * a, k * x[0] + 1.2));

  char positions[128];
  std::snprintf(positions, sizeof positions, "%.9g,%.9g,%.9g", x[0], x[1], x[2]);
  const fs::path csv = dir / "spectrum.csv";
  const CommandResult r = swell_command("waves analyse " + file.string() +
                                        " --gauge H1 --from 10 --to 190 --period 2 --harmonics 2 "
                                        "--segment 100 --reflection H1,H2,H3 --positions " +
                                        positions + " --depth 0.5 --csv " + csv.string());
  std::printf("%s", r.output.c_str());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NEAR(reported(r.output, "H_1/3 = "), 2.0 * local, 1e-4);
  EXPECT_NEAR(reported(r.output, "T_1/3 = "), T, 1e-4);
  EXPECT_NEAR(reported(r.output, "n = 1: f = 0.5 Hz, a = "), local, 1e-5);
  EXPECT_NEAR(reported(r.output, "n = 2: f = 1 Hz, a = "), 0.0, 1e-5);
  EXPECT_NEAR(reported(r.output, "Hm0 = ") / (2.0 * std::sqrt(2.0) * local), 1.0, 0.01);
  EXPECT_NEAR(reported(r.output, "Tp = "), T, 0.02);
  EXPECT_NEAR(reported(r.output, "Kr = ") / kr, 1.0, 0.02);
  EXPECT_NEAR(reported(r.output, "Hm0_incident = ") / (2.0 * std::sqrt(2.0) * a), 1.0, 0.02);
  // With --period, the regular-wave separation at 1/T as well: exact here.
  EXPECT_NEAR(reported(r.output, "a_incident = "), a, 1e-6);
  EXPECT_NEAR(reported(r.output, "a_reflected = "), kr * a, 1e-6);
  std::ifstream in(csv);
  std::string header;
  while (std::getline(in, header) && header.starts_with("#")) {
  }  // the title and the provenance lines
  EXPECT_EQ(header, "f [Hz],S_H1 [m^2/Hz],S_incident [m^2/Hz],S_reflected [m^2/Hz]");
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 2501);  // 5000-sample segments: f = 0 .. 25 Hz in steps of 0.01 Hz

  // Times jittered as step times are: resampled for the spectrum, the same answers.
  std::vector<double> tj = g.t;
  std::vector<double> ej = g.eta[0];
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  const double omega = 2.0 * kPi / T;
  for (std::size_t i = 1; i + 1 < tj.size(); ++i) {
    tj[i] += jitter(rng);
    ej[i] = a * std::cos(omega * tj[i] - k * x[0] + 0.4) +
            kr * a * std::cos(omega * tj[i] + k * x[0] + 1.2);
  }
  const fs::path jittered = dir / "jittered.csv";
  write_gauge_csv(jittered, {"H1"}, tj, {ej});
  const CommandResult rj =
      swell_command("waves analyse " + jittered.string() + " --gauge 'H1 [m]'");
  ASSERT_EQ(rj.code, 0) << rj.output;
  EXPECT_NE(rj.output.find("resampled linearly"), std::string::npos) << rj.output;
  EXPECT_NEAR(reported(rj.output, "Hm0 = ") / (2.0 * std::sqrt(2.0) * local), 1.0, 0.01);
}

TEST(WavesAnalyseCommand, BadInputExitsTwo) {
  const fs::path dir = test_dir("bad");
  const fs::path file = dir / "gauges_height.csv";
  const Record r = sample(0.0, 20.0, 0.05, [](double t) { return std::sin(t); });
  write_gauge_csv(file, {"H1"}, r.t, {r.eta});
  const CommandResult missing = swell_command("waves analyse " + file.string() + " --gauge H9");
  EXPECT_EQ(missing.code, 2) << missing.output;
  EXPECT_NE(missing.output.find(file.string()), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("'H9'"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("error: "), std::string::npos) << missing.output;

  const CommandResult no_file =
      swell_command("waves analyse " + (dir / "absent.csv").string() + " --gauge H1");
  EXPECT_EQ(no_file.code, 2) << no_file.output;
  EXPECT_NE(no_file.output.find("absent.csv"), std::string::npos) << no_file.output;
  const CommandResult no_depth =
      swell_command("waves analyse " + file.string() + " --reflection H1,H1,H1");
  EXPECT_EQ(no_depth.code, 2) << no_depth.output;
  const CommandResult nothing = swell_command("waves analyse " + file.string());
  EXPECT_EQ(nothing.code, 2) << nothing.output;
  const CommandResult crossing =
      swell_command("waves analyse " + file.string() + " --gauge H1 --crossing sideways");
  EXPECT_EQ(crossing.code, 2) << crossing.output;
  const CommandResult window =
      swell_command("waves analyse " + file.string() + " --gauge H1 --from 50 --to 60");
  EXPECT_EQ(window.code, 2) << window.output;
  EXPECT_NE(window.output.find("window"), std::string::npos) << window.output;
  // Every `swell waves` command refuses a --csv into a folder that does not exist (exit 2,
  // naming the folder) before it computes anything.
  const std::string missing_folder = (dir / "no_such_folder").string();
  for (const std::string& cmd :
       {"waves analyse " + file.string() + " --gauge H1 --period 6.2832",
        "waves predict " + file.string() + " --paddle H1 --depth 0.5 --at 1",
        std::string("waves goda 1 8 10")}) {
    const CommandResult r = swell_command(cmd + " --csv " + missing_folder + "/out.csv");
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.output;
    EXPECT_NE(r.output.find("no_such_folder"), std::string::npos) << cmd << "\n" << r.output;
    EXPECT_FALSE(fs::exists(missing_folder)) << cmd;
  }
  // An error found late (a segment longer than the record) prints no partial report.
  const CommandResult segment =
      swell_command("waves analyse " + file.string() + " --gauge H1 --segment 100");
  EXPECT_EQ(segment.code, 2) << segment.output;
  EXPECT_NE(segment.output.find("longer than the record"), std::string::npos) << segment.output;
  EXPECT_EQ(segment.output.find("zero crossing"), std::string::npos) << segment.output;
  // The regular-wave separation at 1/T with gauges half a wave length apart (T 1 s in 0.5 m:
  // L = 1.50 m): refused, naming why, with no partial report.
  const double half = 0.5 * wave_length(1.0, 0.5);
  char positions[128];
  std::snprintf(positions, sizeof positions, "0,%.9g,%.9g", half, 2.0 * half);
  const fs::path three = dir / "three.csv";
  write_gauge_csv(three, {"A", "B", "C"}, r.t, {r.eta, r.eta, r.eta});
  const CommandResult spacing =
      swell_command("waves analyse " + three.string() + " --reflection A,B,C --positions " +
                    positions + " --depth 0.5 --period 1 --segment 5");
  EXPECT_EQ(spacing.code, 2) << spacing.output;
  EXPECT_NE(spacing.output.find("cannot separate"), std::string::npos) << spacing.output;
  EXPECT_EQ(spacing.output.find("Kr = "), std::string::npos) << spacing.output;
}

// `swell waves H T d`: second-order generation on a flap is refused (exit 2, naming the
// option, no report), as a case file's `order: 2` on a flap is; order 1 on a flap and order 2
// on a piston report.
TEST(WavesTheoryCommand, SecondOrderFlapExitsTwo) {
  const CommandResult flap2 = swell_command("waves 0.05 1.6 0.6 --paddle flap --order 2");
  EXPECT_EQ(flap2.code, 2) << flap2.output;
  EXPECT_NE(flap2.output.find("--order 2"), std::string::npos) << flap2.output;
  EXPECT_NE(flap2.output.find("pistons only"), std::string::npos) << flap2.output;
  EXPECT_EQ(flap2.output.find("wave length"), std::string::npos) << flap2.output;
  const CommandResult flap1 = swell_command("waves 0.05 1.6 0.6 --paddle flap --order 1");
  EXPECT_EQ(flap1.code, 0) << flap1.output;
  EXPECT_NE(flap1.output.find("transfer function H/S"), std::string::npos) << flap1.output;
  const CommandResult piston2 = swell_command("waves 0.05 1.6 0.6 --order 2");
  EXPECT_EQ(piston2.code, 0) << piston2.output;
  EXPECT_NE(piston2.output.find("2nd-order (Madsen) term"), std::string::npos) << piston2.output;
}

}  // namespace
}  // namespace swell::waves
