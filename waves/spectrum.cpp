#include "waves/spectrum.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace swell::waves {

namespace {

void check(const SpectrumSpec& s, double& f_min, double& f_max) {
  if (!(s.tp > 0.0)) throw std::invalid_argument("wave spectrum: Tp must be > 0 s");
  if (!(s.gamma >= 1.0)) throw std::invalid_argument("wave spectrum: gamma must be >= 1");
  if (s.components < 1) throw std::invalid_argument("wave spectrum: needs at least 1 component");
  f_min = s.f_min > 0.0 ? s.f_min : 0.5 / s.tp;
  f_max = s.f_max > 0.0 ? s.f_max : 3.0 / s.tp;
  if (!(f_max > f_min))
    throw std::invalid_argument("wave spectrum: f_max (" + std::to_string(f_max) +
                                " Hz) must exceed f_min (" + std::to_string(f_min) + " Hz)");
}

}  // namespace

double spectrum_shape(const SpectrumSpec& spec, double f) {
  if (!(f > 0.0)) return 0.0;
  const double fp = 1.0 / spec.tp;
  const double base = std::pow(f, -5.0) * std::exp(-1.25 * std::pow(fp / f, 4.0));
  const double gamma = spec.shape == SpectrumSpec::Shape::PiersonMoskowitz ? 1.0 : spec.gamma;
  if (gamma == 1.0) return base;
  const double sigma = f <= fp ? 0.07 : 0.09;
  const double r = std::exp(-(f - fp) * (f - fp) / (2.0 * sigma * sigma * fp * fp));
  return base * std::pow(gamma, r);
}

std::vector<SurfaceComponent> irregular_sea(const SpectrumSpec& spec) {
  double f_min = 0.0, f_max = 0.0;
  check(spec, f_min, f_max);
  if (!(spec.hs > 0.0)) throw std::invalid_argument("wave spectrum: Hs must be > 0 m");
  const int n = spec.components;
  const double df = (f_max - f_min) / n;
  std::mt19937_64 rng(spec.seed);
  std::vector<SurfaceComponent> out(static_cast<std::size_t>(n));
  double m0 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double f = f_min + (i + 0.5) * df;
    auto& c = out[static_cast<std::size_t>(i)];
    c.omega = 2.0 * std::numbers::pi * f;
    c.amplitude = std::sqrt(2.0 * spectrum_shape(spec, f) * df);
    c.phase = 2.0 * std::numbers::pi * static_cast<double>(rng() >> 11) * 0x1.0p-53;
    m0 += 0.5 * c.amplitude * c.amplitude;
  }
  if (!(m0 > 0.0)) throw std::invalid_argument("wave spectrum: no energy in the frequency range");
  const double scale = (spec.hs / 4.0) / std::sqrt(m0);
  for (auto& c : out) c.amplitude *= scale;
  return out;
}

std::vector<SurfaceComponent> focused_group(const SpectrumSpec& spec, double crest_amplitude,
                                            double focus_distance, double focus_time, double depth,
                                            double g) {
  double f_min = 0.0, f_max = 0.0;
  check(spec, f_min, f_max);
  if (!(crest_amplitude > 0.0))
    throw std::invalid_argument("focused wave group: the crest amplitude must be > 0 m");
  const int n = spec.components;
  const double df = (f_max - f_min) / n;
  std::vector<SurfaceComponent> out(static_cast<std::size_t>(n));
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double f = f_min + (i + 0.5) * df;
    auto& c = out[static_cast<std::size_t>(i)];
    c.omega = 2.0 * std::numbers::pi * f;
    c.amplitude = spectrum_shape(spec, f) * df;
    c.phase = wave_number(c.omega, depth, g) * focus_distance - c.omega * focus_time;
    sum += c.amplitude;
  }
  if (!(sum > 0.0)) throw std::invalid_argument("focused wave group: no energy in the range");
  for (auto& c : out) c.amplitude *= crest_amplitude / sum;
  return out;
}

}  // namespace swell::waves
