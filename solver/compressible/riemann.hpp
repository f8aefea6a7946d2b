// Exact solution of the Riemann problem for the 1D Euler equations of an ideal gas
// (Toro 2009, "Riemann Solvers and Numerical Methods for Fluid Dynamics", 3rd ed., ch. 4):
// the star pressure from Newton iterations on the pressure function, then the self-similar
// solution sampled at x/t. The reference for the Sod shock tube of verify/sod.
#pragma once

namespace swell::compressible {

struct GasState {
  double rho = 0.0, u = 0.0, p = 0.0;  // density, velocity, pressure
};

// What lies between the two nonlinear waves: p* and u* on both sides of the contact, the
// densities left and right of it, and which kind each outer wave is.
struct StarRegion {
  double p = 0.0, u = 0.0;
  double rho_left = 0.0, rho_right = 0.0;
  bool left_shock = false, right_shock = false;
  int iterations = 0;  // Newton iterations used for p*
};

class RiemannSolver {
 public:
  // Throws std::invalid_argument for non-positive density or pressure, gamma <= 1, or data that
  // generate a vacuum (Toro eq. 4.82), which this solver does not handle.
  RiemannSolver(GasState left, GasState right, double gamma);

  const StarRegion& star() const { return star_; }
  // The solution at similarity coordinate s = (x - x0)/t.
  GasState sample(double s) const;
  // The solution at x for a discontinuity at x0 at t = 0; t > 0.
  GasState at(double x, double x0, double t) const { return sample((x - x0) / t); }

 private:
  // Toro eq. 4.6/4.7: f_K(p) and its derivative for side K.
  void pressure_function(double p, const GasState& k, double c, double& f, double& df) const;

  GasState left_, right_;
  double gamma_, c_left_, c_right_;
  StarRegion star_;
};

}  // namespace swell::compressible
