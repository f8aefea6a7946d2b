#include "solver/compressible/riemann.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace swell::compressible {

RiemannSolver::RiemannSolver(GasState left, GasState right, double gamma)
    : left_(left), right_(right), gamma_(gamma) {
  if (!(gamma > 1.0)) throw std::invalid_argument("Riemann solver: gamma must be > 1");
  for (const GasState* s : {&left_, &right_})
    if (!(s->rho > 0.0) || !(s->p > 0.0))
      throw std::invalid_argument("Riemann solver: density and pressure must be positive");
  c_left_ = std::sqrt(gamma_ * left_.p / left_.rho);
  c_right_ = std::sqrt(gamma_ * right_.p / right_.rho);
  const double du = right_.u - left_.u;
  // Pressure positivity condition (Toro eq. 4.82): otherwise the waves leave a vacuum.
  if (2.0 / (gamma_ - 1.0) * (c_left_ + c_right_) <= du)
    throw std::invalid_argument("Riemann solver: the data generate a vacuum (not handled)");

  // Initial guess: the primitive-variable linearisation (Toro eq. 4.47), kept positive; the
  // pressure function is monotone and concave, so Newton from there converges.
  const double rho_bar = 0.5 * (left_.rho + right_.rho), c_bar = 0.5 * (c_left_ + c_right_);
  double p = std::max(1e-8 * std::min(left_.p, right_.p),
                      0.5 * (left_.p + right_.p) - 0.125 * du * rho_bar * c_bar);
  int it = 0;
  for (; it < 100; ++it) {
    double fl, dfl, fr, dfr;
    pressure_function(p, left_, c_left_, fl, dfl);
    pressure_function(p, right_, c_right_, fr, dfr);
    double p_new = p - (fl + fr + du) / (dfl + dfr);
    if (p_new <= 0.0) p_new = 0.1 * p;                              // stay in the domain of f
    const double change = 2.0 * std::abs(p_new - p) / (p_new + p);  // Toro eq. 4.48
    p = p_new;
    if (change < 1e-14) break;
  }
  if (it == 100)
    throw std::runtime_error("Riemann solver: Newton iteration for p* did not converge");
  double fl, dfl, fr, dfr;
  pressure_function(p, left_, c_left_, fl, dfl);
  pressure_function(p, right_, c_right_, fr, dfr);
  star_.p = p;
  star_.u = 0.5 * (left_.u + right_.u) + 0.5 * (fr - fl);  // Toro eq. 4.9
  star_.iterations = it + 1;
  star_.left_shock = p > left_.p;
  star_.right_shock = p > right_.p;
  const double g = (gamma_ - 1.0) / (gamma_ + 1.0);
  // Star densities: shock adiabat (Toro eq. 4.50, 4.57) or isentrope (eq. 4.53, 4.60).
  auto star_rho = [&](const GasState& k, bool shock) {
    const double ratio = p / k.p;
    return shock ? k.rho * (ratio + g) / (g * ratio + 1.0) : k.rho * std::pow(ratio, 1.0 / gamma_);
  };
  star_.rho_left = star_rho(left_, star_.left_shock);
  star_.rho_right = star_rho(right_, star_.right_shock);
}

void RiemannSolver::pressure_function(double p, const GasState& k, double c, double& f,
                                      double& df) const {
  if (p > k.p) {  // shock: Toro eq. 4.21
    const double a = 2.0 / ((gamma_ + 1.0) * k.rho);
    const double b = (gamma_ - 1.0) / (gamma_ + 1.0) * k.p;
    const double root = std::sqrt(a / (p + b));
    f = (p - k.p) * root;
    df = root * (1.0 - 0.5 * (p - k.p) / (b + p));
  } else {  // rarefaction: Toro eq. 4.26
    const double e = (gamma_ - 1.0) / (2.0 * gamma_);
    f = 2.0 * c / (gamma_ - 1.0) * (std::pow(p / k.p, e) - 1.0);
    df = 1.0 / (k.rho * c) * std::pow(p / k.p, -(gamma_ + 1.0) / (2.0 * gamma_));
  }
}

GasState RiemannSolver::sample(double s) const {
  // Toro section 4.5. Work on the left of the contact; the right is its mirror image
  // (x -> -x, u -> -u), so one code path serves both.
  const bool left_side = s <= star_.u;
  const double sign = left_side ? 1.0 : -1.0;
  const GasState k = left_side ? left_ : right_;
  const double c = left_side ? c_left_ : c_right_;
  const bool shock = left_side ? star_.left_shock : star_.right_shock;
  const double rho_star = left_side ? star_.rho_left : star_.rho_right;
  // Mirrored quantities: for the right side, sm = -s, uk = -u_R, um = -u*.
  const double sm = sign * s, uk = sign * k.u, um = sign * star_.u;
  const double g = gamma_;
  auto out = [&](double rho, double u, double p) { return GasState{rho, sign * u, p}; };
  if (shock) {
    const double ratio = star_.p / k.p;
    // Shock speed (Toro eq. 4.52) in the mirrored frame.
    const double ss = uk - c * std::sqrt((g + 1.0) / (2.0 * g) * ratio + (g - 1.0) / (2.0 * g));
    if (sm <= ss) return out(k.rho, uk, k.p);
    return out(rho_star, um, star_.p);
  }
  const double head = uk - c;  // Toro eq. 4.55
  const double c_star = c * std::pow(star_.p / k.p, (g - 1.0) / (2.0 * g));
  const double tail = um - c_star;
  if (sm <= head) return out(k.rho, uk, k.p);
  if (sm >= tail) return out(rho_star, um, star_.p);
  // Inside the fan (Toro eq. 4.56).
  const double base = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * c) * (uk - sm);
  const double rho = k.rho * std::pow(base, 2.0 / (g - 1.0));
  const double u = 2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * uk + sm);
  const double p = k.p * std::pow(base, 2.0 * g / (g - 1.0));
  return out(rho, u, p);
}

}  // namespace swell::compressible
