#include "waves/analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

#include "waves/dispersion.hpp"
#include "waves/theory.hpp"

namespace swell::waves {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string num(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

// Same lengths, finite values, strictly increasing times.
void check_series(std::span<const double> t, std::span<const double> eta, const char* what) {
  if (t.size() != eta.size())
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(t.size()) +
                                " times but " + std::to_string(eta.size()) + " values");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(eta[i]))
      throw std::invalid_argument(std::string(what) + ": sample " + std::to_string(i) +
                                  " is not finite (t = " + num(t[i]) + ", value " + num(eta[i]) +
                                  ")");
    if (i > 0 && !(t[i] > t[i - 1]))
      throw std::invalid_argument(std::string(what) + ": times not increasing at sample " +
                                  std::to_string(i) + " (t = " + num(t[i]) + " after " +
                                  num(t[i - 1]) + ")");
  }
}

// The samples [begin, end) inside the window (times increase, so they are contiguous).
struct Range {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};

Range window_range(std::span<const double> t, Window w, std::size_t min_samples, const char* what) {
  if (!(w.t0 <= w.t1))
    throw std::invalid_argument(std::string(what) + ": window from " + num(w.t0) + " to " +
                                num(w.t1) + " is empty");
  Range r;
  r.begin = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), w.t0) - t.begin());
  r.end = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), w.t1) - t.begin());
  if (r.end < r.begin) r.end = r.begin;
  if (r.size() < min_samples) {
    std::string span =
        t.empty() ? "no samples" : "samples from t = " + num(t.front()) + " to " + num(t.back());
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(r.size()) +
                                " samples in the window [" + num(w.t0) + ", " + num(w.t1) +
                                "], at least " + std::to_string(min_samples) + " needed (" + span +
                                ")");
  }
  return r;
}

void check_uniform_from(std::span<const double> t, std::size_t offset) {
  if (t.size() < 2) throw std::invalid_argument("uniform sampling: fewer than two samples");
  const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  if (!(dt > 0.0))
    throw std::invalid_argument("uniform sampling: times do not increase (sample " +
                                std::to_string(offset) + ")");
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double d = t[i + 1] - t[i];
    const double dev = std::abs(d - dt) / dt;
    if (!(dev <= kUniformTolerance))
      throw std::invalid_argument(
          "sampling is not uniform: the spacing after sample " + std::to_string(offset + i) +
          " (t = " + num(t[i]) + " s) is " + num(d) + " s, the mean spacing " + num(dt) +
          " s (relative deviation " + num(dev) + ", more than " + num(kUniformTolerance) +
          "); resample the record first (resample_uniform)");
  }
}

// The largest m <= n whose prime factors are 2, 3 and 5 (the FFT's fast radices; a length with
// a large prime factor costs up to O(L^2)).
long smooth_size(long n) {
  for (long m = n; m > 1; --m) {
    long r = m;
    for (const long p : {2L, 3L, 5L})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
  return n;
}

// Welch segmentation shared by the spectrum and the reflection analysis.
struct Segmentation {
  int length = 0;  // samples per segment
  int step = 0;
  int count = 0;
  double dt = 0.0;
  std::vector<double> taper;
  double taper_power = 0.0;  // sum_n w_n^2
};

Segmentation segmentation(std::span<const double> t, const SpectrumOptions& opt) {
  Segmentation s;
  const std::size_t n = t.size();
  s.dt = (t.back() - t.front()) / static_cast<double>(n - 1);
  long length = 0;
  if (opt.segment_seconds > 0.0) {
    length = std::lround(opt.segment_seconds / s.dt);
  } else {
    length = smooth_size(static_cast<long>(2 * n / 9));
  }
  if (length > static_cast<long>(n))
    throw std::invalid_argument("spectrum: segment of " + num(opt.segment_seconds) + " s (" +
                                std::to_string(length) + " samples) is longer than the record (" +
                                std::to_string(n) + " samples, " + num(s.dt * (n - 1)) + " s)");
  if (length < 8)
    throw std::invalid_argument("spectrum: segment of " + std::to_string(length) +
                                " samples, at least 8 needed (longer segment or record)");
  s.length = static_cast<int>(length);
  s.step = std::max(1, s.length / 2);
  s.count = 1 + static_cast<int>((n - static_cast<std::size_t>(s.length)) /
                                 static_cast<std::size_t>(s.step));
  s.taper.assign(static_cast<std::size_t>(s.length), 1.0);
  if (opt.taper == Taper::Hann)
    for (int i = 0; i < s.length; ++i)
      s.taper[i] = 0.5 * (1.0 - std::cos(2.0 * kPi * i / s.length));
  s.taper_power = 0.0;
  for (const double w : s.taper) s.taper_power += w * w;
  return s;
}

// One segment: detrended, tapered, transformed; `out` holds the L/2 + 1 non-negative
// frequencies' coefficients.
class SegmentTransform {
 public:
  SegmentTransform(const Segmentation& seg, Detrend detrend)
      : seg_(seg), detrend_(detrend), buf_(static_cast<std::size_t>(seg.length)) {}

  void operator()(const double* x, std::vector<std::complex<double>>& out) {
    const int L = seg_.length;
    double mean = 0.0;
    for (int i = 0; i < L; ++i) mean += x[i];
    mean /= L;
    double slope = 0.0;
    const double centre = 0.5 * (L - 1);
    if (detrend_ == Detrend::Linear) {
      // Least-squares line over the sample index.
      double sxy = 0.0, sxx = 0.0;
      for (int i = 0; i < L; ++i) {
        sxy += (i - centre) * (x[i] - mean);
        sxx += (i - centre) * (i - centre);
      }
      slope = sxy / sxx;
    }
    for (int i = 0; i < L; ++i) buf_[i] = (x[i] - mean - slope * (i - centre)) * seg_.taper[i];
    fft_.fwd(full_, buf_);
    out.assign(full_.begin(), full_.begin() + (L / 2 + 1));
  }

 private:
  const Segmentation& seg_;
  Detrend detrend_;
  std::vector<double> buf_;
  std::vector<std::complex<double>> full_;
  Eigen::FFT<double> fft_;
};

// One-sided factor: 1 at f = 0 and at the Nyquist frequency (even L), else 2.
double one_sided(int k, int L) {
  return (k == 0 || 2 * k == L) ? 1.0 : 2.0;
}

double mean_of(std::span<const double> v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

}  // namespace

// ---- Zero crossing ---------------------------------------------------------------------------

ZeroCrossingResult zero_crossing(std::span<const double> t, std::span<const double> eta,
                                 Crossing kind, Window w) {
  check_series(t, eta, "zero-crossing analysis");
  const Range r = window_range(t, w, 2, "zero-crossing analysis");
  ZeroCrossingResult res;
  res.mean_level = mean_of(eta.subspan(r.begin, r.size()));
  const double sign = kind == Crossing::Up ? 1.0 : -1.0;
  auto y = [&](std::size_t i) { return sign * (eta[i] - res.mean_level); };

  // Crossings: time and the first sample after it.
  std::vector<std::pair<double, std::size_t>> crossings;
  for (std::size_t i = r.begin; i + 1 < r.end; ++i) {
    const double a = y(i), b = y(i + 1);
    if (a < 0.0 && b >= 0.0) {
      const double tc = t[i] + (t[i + 1] - t[i]) * (-a) / (b - a);
      crossings.emplace_back(tc, i + 1);
    }
  }
  for (std::size_t c = 0; c + 1 < crossings.size(); ++c) {
    const auto [t_a, i_a] = crossings[c];
    const auto [t_b, i_b] = crossings[c + 1];
    double hi = y(i_a), lo = y(i_a);
    for (std::size_t i = i_a; i < i_b; ++i) {
      hi = std::max(hi, y(i));
      lo = std::min(lo, y(i));
    }
    IndividualWave wave;
    wave.t_start = t_a;
    wave.period = t_b - t_a;
    wave.crest = kind == Crossing::Up ? hi : -lo;
    wave.trough = kind == Crossing::Up ? lo : -hi;
    wave.height = hi - lo;
    res.waves.push_back(wave);
  }
  res.count = static_cast<int>(res.waves.size());
  if (res.count == 0) return res;

  for (const auto& wv : res.waves) {
    res.h_mean += wv.height;
    res.t_mean += wv.period;
    res.h_max = std::max(res.h_max, wv.height);
  }
  res.h_mean /= res.count;
  res.t_mean /= res.count;
  std::vector<int> order(static_cast<std::size_t>(res.count));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return res.waves[a].height > res.waves[b].height; });
  const int third = std::max(1, res.count / 3);
  for (int j = 0; j < third; ++j) {
    res.h_third += res.waves[order[j]].height;
    res.t_third += res.waves[order[j]].period;
  }
  res.h_third /= third;
  res.t_third /= third;
  return res;
}

// ---- Harmonic fit ----------------------------------------------------------------------------

HarmonicFit fit_harmonics(std::span<const double> t, std::span<const double> eta, double frequency,
                          int harmonics, Window w) {
  check_series(t, eta, "harmonic fit");
  if (!(frequency > 0.0) || !std::isfinite(frequency))
    throw std::invalid_argument("harmonic fit: the frequency must be > 0, got " + num(frequency));
  if (harmonics < 1 || harmonics > 1000)
    throw std::invalid_argument("harmonic fit: harmonics must be in 1..1000, got " +
                                std::to_string(harmonics));
  const int unknowns = 2 * harmonics + 1;
  const Range r = window_range(t, w, static_cast<std::size_t>(unknowns), "harmonic fit");
  const Eigen::Index m = static_cast<Eigen::Index>(r.size());
  Eigen::MatrixXd a(m, unknowns);
  Eigen::VectorXd b(m);
  const double omega = 2.0 * kPi * frequency;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double ti = t[r.begin + static_cast<std::size_t>(i)];
    a(i, 0) = 1.0;
    for (int n = 1; n <= harmonics; ++n) {
      a(i, 2 * n - 1) = std::cos(n * omega * ti);
      a(i, 2 * n) = std::sin(n * omega * ti);
    }
    b(i) = eta[r.begin + static_cast<std::size_t>(i)];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  // Pivots below 1e-10 of the largest count as zero: such columns are numerically dependent
  // (Eigen's default, ~1e-15, misses a sine sampled at its zeros by rounding).
  qr.setThreshold(1e-10);
  if (qr.rank() < unknowns)
    throw std::invalid_argument(
        "harmonic fit: the " + std::to_string(harmonics) + " harmonics of " + num(frequency) +
        " Hz cannot be told apart on these " + std::to_string(m) +
        " samples (rank-deficient least squares: window shorter than a period, or a harmonic at "
        "the sampling's Nyquist frequency)");
  const Eigen::VectorXd c = qr.solve(b);
  HarmonicFit fit;
  fit.samples = static_cast<int>(m);
  fit.mean = c(0);
  for (int n = 1; n <= harmonics; ++n) {
    Harmonic h;
    h.n = n;
    h.frequency = n * frequency;
    h.cos_coef = c(2 * n - 1);
    h.sin_coef = c(2 * n);
    h.amplitude = std::hypot(h.cos_coef, h.sin_coef);
    h.phase = std::atan2(h.sin_coef, h.cos_coef);
    fit.harmonics.push_back(h);
  }
  const Eigen::VectorXd residual = a * c - b;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) sum += residual(i) * residual(i);
  fit.rms_residual = std::sqrt(sum / static_cast<double>(m));
  return fit;
}

// ---- Uniform sampling ------------------------------------------------------------------------

void check_uniform(std::span<const double> t) {
  check_uniform_from(t, 0);
}

Samples resample_uniform(std::span<const double> t, std::span<const double> eta, double dt) {
  check_series(t, eta, "resampling");
  if (t.size() < 2) throw std::invalid_argument("resampling: fewer than two samples");
  if (!(dt > 0.0)) dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  // A rounding error must not drop the last point nor put it past the last sample.
  const auto n = static_cast<std::size_t>(std::floor((t.back() - t.front()) / dt + 1e-9)) + 1;
  Samples out;
  out.t.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    out.t[i] = std::min(t.front() + static_cast<double>(i) * dt, t.back());
  out.eta = interpolate_linear(t, eta, out.t);
  return out;
}

std::vector<double> interpolate_linear(std::span<const double> t, std::span<const double> eta,
                                       std::span<const double> at) {
  check_series(t, eta, "interpolation");
  if (t.size() < 2) throw std::invalid_argument("interpolation: fewer than two samples");
  std::vector<double> out(at.size());
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double ti = at[i];
    if (!(ti >= t.front() && ti <= t.back()))
      throw std::invalid_argument("interpolation: t = " + num(ti) + " is outside the record (" +
                                  num(t.front()) + " to " + num(t.back()) + ")");
    const auto it = std::upper_bound(t.begin(), t.end(), ti);
    const std::size_t j = std::min(static_cast<std::size_t>(it - t.begin()), t.size() - 1);
    const double u = (ti - t[j - 1]) / (t[j] - t[j - 1]);
    out[i] = (1.0 - u) * eta[j - 1] + u * eta[j];
  }
  return out;
}

// ---- Spectrum --------------------------------------------------------------------------------

Spectrum welch_spectrum(std::span<const double> t, std::span<const double> eta,
                        const SpectrumOptions& opt, Window w) {
  check_series(t, eta, "spectrum");
  const Range r = window_range(t, w, 8, "spectrum");
  const auto tw = t.subspan(r.begin, r.size());
  const auto xw = eta.subspan(r.begin, r.size());
  check_uniform_from(tw, r.begin);
  const Segmentation seg = segmentation(tw, opt);
  const int L = seg.length;
  const int nf = L / 2 + 1;
  const double fs = 1.0 / seg.dt;

  Spectrum s;
  s.dt = seg.dt;
  s.df = fs / L;
  s.segment_samples = L;
  s.segments = seg.count;
  s.f.resize(static_cast<std::size_t>(nf));
  s.S.assign(static_cast<std::size_t>(nf), 0.0);
  for (int k = 0; k < nf; ++k) s.f[k] = k * s.df;
  const double mean = mean_of(xw);
  for (const double v : xw) s.variance += (v - mean) * (v - mean);
  s.variance /= static_cast<double>(xw.size());

  SegmentTransform transform(seg, opt.detrend);
  std::vector<std::complex<double>> c;
  for (int j = 0; j < seg.count; ++j) {
    transform(xw.data() + static_cast<std::size_t>(j) * seg.step, c);
    for (int k = 0; k < nf; ++k) s.S[k] += one_sided(k, L) * std::norm(c[k]);
  }
  const double scale = 1.0 / (seg.count * fs * seg.taper_power);
  for (auto& v : s.S) v *= scale;
  return s;
}

SpectralParameters spectral_parameters(std::span<const double> f, std::span<const double> S,
                                       Band band, bool interpolate_peak) {
  if (f.size() != S.size())
    throw std::invalid_argument("spectral parameters: " + std::to_string(f.size()) +
                                " frequencies but " + std::to_string(S.size()) + " densities");
  SpectralParameters p;
  if (f.size() < 2) return p;
  const double df = f[1] - f[0];
  auto usable = [&](std::size_t k) { return band.contains(f[k]) && std::isfinite(S[k]); };
  std::size_t peak = f.size();
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (!usable(k)) continue;
    ++p.bins;
    p.m0 += S[k] * df;
    p.m1 += f[k] * S[k] * df;
    p.m2 += f[k] * f[k] * S[k] * df;
    if (peak == f.size() || S[k] > S[peak]) peak = k;
  }
  if (p.bins == 0 || !(p.m0 > 0.0)) return SpectralParameters{.bins = p.bins};
  p.hm0 = 4.0 * std::sqrt(p.m0);
  p.fp = f[peak];
  if (interpolate_peak && peak > 0 && peak + 1 < f.size() && usable(peak - 1) && usable(peak + 1)) {
    const double a = S[peak - 1], b = S[peak], c = S[peak + 1];
    const double curvature = a - 2.0 * b + c;
    if (curvature < 0.0) p.fp += df * std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
  }
  p.tp = p.fp > 0.0 ? 1.0 / p.fp : 0.0;
  p.tm01 = p.m1 > 0.0 ? p.m0 / p.m1 : 0.0;
  p.tm02 = p.m2 > 0.0 ? std::sqrt(p.m0 / p.m2) : 0.0;
  return p;
}

// ---- Reflection ------------------------------------------------------------------------------

namespace {

// The three-gauge separation's inputs: increasing finite positions, depth and g > 0.
void check_reflection_setup(const std::array<double, 3>& x, double depth, double g) {
  if (!(std::isfinite(x[0]) && std::isfinite(x[2]) && x[0] < x[1] && x[1] < x[2]))
    throw std::invalid_argument(
        "reflection analysis: gauge positions must increase, x1 < x2 < x3 (got " + num(x[0]) +
        ", " + num(x[1]) + ", " + num(x[2]) + ")");
  if (!(depth > 0.0) || !std::isfinite(depth))
    throw std::invalid_argument("reflection analysis: the depth must be > 0, got " + num(depth));
  if (!(g > 0.0)) throw std::invalid_argument("reflection analysis: g must be > 0");
}

}  // namespace

RegularReflection mansard_funke_regular(std::span<const double> t,
                                        const std::array<std::span<const double>, 3>& eta,
                                        const std::array<double, 3>& x, double depth,
                                        double frequency, double g, Window w,
                                        double min_conditioning) {
  check_reflection_setup(x, depth, g);
  if (!(frequency > 0.0) || !std::isfinite(frequency))
    throw std::invalid_argument("reflection analysis: the frequency must be > 0, got " +
                                num(frequency));
  using C = std::complex<double>;
  RegularReflection res;
  res.frequency = frequency;
  res.k = wave_number(2.0 * kPi * frequency, depth, g);
  Eigen::Matrix<C, 3, 2> m;
  Eigen::Matrix<C, 3, 1> b;
  C s = 0.0;
  for (int p = 0; p < 3; ++p) {
    const HarmonicFit fit = fit_harmonics(t, eta[p], frequency, 1, w);
    const Harmonic& h = fit.harmonics.front();
    b(p) = C(h.cos_coef, -h.sin_coef);  // A cos(w t) + B sin(w t) = Re[(A - i B) e^{i w t}]
    res.amplitude[p] = h.amplitude;
    m(p, 0) = std::polar(1.0, -res.k * x[p]);  // incident, towards +x
    m(p, 1) = std::polar(1.0, res.k * x[p]);   // reflected, towards -x
    s += m(p, 1) * m(p, 1);
  }
  if (1.0 - std::abs(s) / 3.0 < min_conditioning)
    throw std::invalid_argument(
        "reflection analysis: at f = " + num(frequency) +
        " Hz every gauge spacing is near a multiple of L/2 (L = " + num(2.0 * kPi / res.k) +
        " m): the gauges cannot separate the two waves");
  const Eigen::Matrix<C, 2, 1> z = m.colPivHouseholderQr().solve(b);
  res.a_incident = std::abs(z(0));
  res.a_reflected = std::abs(z(1));
  res.kr = res.a_incident > 0.0 ? res.a_reflected / res.a_incident : 0.0;
  res.residual = (m * z - b).cwiseAbs().maxCoeff();
  return res;
}

ReflectionResult mansard_funke(std::span<const double> t,
                               const std::array<std::span<const double>, 3>& eta,
                               const std::array<double, 3>& x, double depth,
                               const ReflectionOptions& opt, Window w) {
  for (int p = 0; p < 3; ++p) check_series(t, eta[p], "reflection analysis");
  check_reflection_setup(x, depth, opt.g);
  const Range r = window_range(t, w, 8, "reflection analysis");
  const auto tw = t.subspan(r.begin, r.size());
  check_uniform_from(tw, r.begin);
  const Segmentation seg = segmentation(tw, opt.spectrum);
  const int L = seg.length;
  const int nf = L / 2 + 1;
  const double fs = 1.0 / seg.dt;

  ReflectionResult res;
  res.df = fs / L;
  res.segment_samples = L;
  res.segments = seg.count;
  res.f.resize(static_cast<std::size_t>(nf));
  for (int k = 0; k < nf; ++k) res.f[k] = k * res.df;
  res.S_incident.assign(static_cast<std::size_t>(nf), kNaN);
  res.S_reflected.assign(static_cast<std::size_t>(nf), kNaN);

  // Per frequency: e^{i k x_p}, the normal matrix's S and whether it is solvable.
  using C = std::complex<double>;
  std::vector<std::array<C, 3>> phase(static_cast<std::size_t>(nf));
  std::vector<C> s_sum(static_cast<std::size_t>(nf));
  std::vector<bool> used(static_cast<std::size_t>(nf), false);
  for (int k = 1; k < nf; ++k) {
    if (!opt.band.contains(res.f[k])) continue;
    const double wn = wave_number(2.0 * kPi * res.f[k], depth, opt.g);
    C s = 0.0;
    for (int p = 0; p < 3; ++p) {
      phase[k][p] = std::polar(1.0, wn * x[p]);
      s += phase[k][p] * phase[k][p];
    }
    s_sum[k] = s;
    if (1.0 - std::abs(s) / 3.0 < opt.min_conditioning) {
      res.skipped.push_back(res.f[k]);
      continue;
    }
    used[k] = true;
    res.S_incident[k] = 0.0;
    res.S_reflected[k] = 0.0;
  }

  std::array<SegmentTransform, 3> transforms{SegmentTransform(seg, opt.spectrum.detrend),
                                             SegmentTransform(seg, opt.spectrum.detrend),
                                             SegmentTransform(seg, opt.spectrum.detrend)};
  std::array<std::vector<C>, 3> coef;
  for (int j = 0; j < seg.count; ++j) {
    const std::size_t start = r.begin + static_cast<std::size_t>(j) * seg.step;
    for (int p = 0; p < 3; ++p) transforms[p](eta[p].data() + start, coef[p]);
    for (int k = 1; k < nf; ++k) {
      if (!used[k]) continue;
      // Normal equations of min sum_p |B_p - Z_I e^{-i k x_p} - Z_R e^{+i k x_p}|^2.
      C r_inc = 0.0, r_ref = 0.0;
      for (int p = 0; p < 3; ++p) {
        r_inc += coef[p][k] * phase[k][p];
        r_ref += coef[p][k] * std::conj(phase[k][p]);
      }
      const C s = s_sum[k];
      const double det = 9.0 - std::norm(s);
      const C z_inc = (3.0 * r_inc - s * r_ref) / det;
      const C z_ref = (3.0 * r_ref - std::conj(s) * r_inc) / det;
      res.S_incident[k] += one_sided(k, L) * std::norm(z_inc);
      res.S_reflected[k] += one_sided(k, L) * std::norm(z_ref);
    }
  }
  const double scale = 1.0 / (seg.count * fs * seg.taper_power);
  for (int k = 0; k < nf; ++k) {
    if (!used[k]) continue;
    res.S_incident[k] *= scale;
    res.S_reflected[k] *= scale;
  }
  res.incident = spectral_parameters(res.f, res.S_incident, opt.band);
  res.reflected = spectral_parameters(res.f, res.S_reflected, opt.band);
  res.hm0_incident = res.incident.hm0;
  res.hm0_reflected = res.reflected.hm0;
  res.kr = res.incident.m0 > 0.0 ? std::sqrt(res.reflected.m0 / res.incident.m0) : 0.0;
  return res;
}

SecondHarmonicSplit split_second_harmonic(const Harmonic& first, const Harmonic& second,
                                          double depth, double g) {
  if (first.n != 1 || second.n != 2)
    throw std::invalid_argument("split_second_harmonic: expected harmonics 1 and 2");
  if (!(depth > 0.0) || !(first.frequency > 0.0))
    throw std::invalid_argument("split_second_harmonic: depth and frequency must be positive");
  const double k = wave_number(2.0 * std::numbers::pi * first.frequency, depth, g);
  SecondHarmonicSplit r;
  r.bound = first.amplitude * stokes2_harmonic_ratio(k, depth, 2.0 * first.amplitude);
  const std::complex<double> rest =
      std::polar(second.amplitude, second.phase) - std::polar(r.bound, 2.0 * first.phase);
  r.free = std::abs(rest);
  r.free_phase = std::arg(rest);
  return r;
}

}  // namespace swell::waves
