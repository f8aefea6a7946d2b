#include "waves/record.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

namespace swell::waves {

std::vector<double> propagate_paddle_record(const std::vector<double>& displacement, double dt,
                                            const PaddleGeometry& paddle, double x, double g,
                                            double f_max) {
  const std::size_t n = displacement.size();
  if (n < 4) throw std::invalid_argument("paddle record: at least 4 samples are needed");
  if (!(dt > 0.0)) throw std::invalid_argument("paddle record: the time step must be > 0");
  if (!(x >= 0.0)) throw std::invalid_argument("paddle record: the distance must be >= 0");
  std::size_t m = 1;
  while (m < 2 * n) m *= 2;
  // The record, then a raised-cosine blend from its last value back to its first.
  std::vector<double> padded(m);
  for (std::size_t i = 0; i < n; ++i) padded[i] = displacement[i];
  const double first = displacement.front(), last = displacement.back();
  const std::size_t tail = m - n;
  for (std::size_t i = 0; i < tail; ++i) {
    const double s = (static_cast<double>(i) + 1.0) / (static_cast<double>(tail) + 1.0);
    padded[n + i] = last + (first - last) * 0.5 * (1.0 - std::cos(std::numbers::pi * s));
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, padded);  // full spectrum, bin j at +j / (m dt) Hz, m - j at -j / (m dt)
  const double df = 1.0 / (static_cast<double>(m) * dt);
  const std::complex<double> i_unit(0.0, 1.0);
  spectrum[0] = 0.0;
  spectrum[m / 2] = 0.0;
  for (std::size_t j = 1; j < m / 2; ++j) {
    const double f = static_cast<double>(j) * df;
    if (f_max > 0.0 && f > f_max) {
      spectrum[j] = spectrum[m - j] = 0.0;
      continue;
    }
    const double omega = 2.0 * std::numbers::pi * f;
    const double k = wave_number(omega, paddle.depth, g);
    const double gain = transfer_function(paddle, k);
    // sin -> cos is a factor i on the positive frequency (and -i on its mirror); the wave at x
    // lags by k x: e^{i (w t - k x)}.
    const std::complex<double> shift = std::polar(1.0, -k * x);
    spectrum[j] *= gain * i_unit * shift;
    spectrum[m - j] *= gain * -i_unit * std::conj(shift);
  }
  std::vector<double> eta;
  fft.inv(eta, spectrum);
  eta.resize(n);
  return eta;
}

}  // namespace swell::waves
