// `swell verify sod`: the Sod shock tube with the compressible path (solver/compressible)
// against the exact Riemann solution (Toro 2009 Test 1).
#pragma once

#include <memory>

#include "solver/compressible/gas_solver.hpp"
#include "verify/verify.hpp"

namespace swell::verify {

// The Sod tube on [-0.5, 0.5] (mirror walls at both ends), rho, p = 1, 1 | 0.125, 0.1,
// gamma = 1.4, equal-mass particles: n_left in the left half, n_left/8 in the right.
std::unique_ptr<compressible::GasSolver<1>> make_sod_1d(int n_left);
// Runs to t_end with the CFL step (dt_fixed <= 0) or a fixed step; returns the step count.
// (GasSolver<1>, GasSolver<2> and GasSolver3W.)
template <class Gas>
int run_gas(Gas& gas, double t_end, double dt_fixed);
// The same tube as a 2D slab: x in [-0.5, 0.5], y in [0, W], mirror walls on all four sides,
// lattices of spacing d = 0.5 / n_left (left) and 2d (right), masses for the densities,
// h = eta (m/rho)^(1/2) with the cubic spline.
std::unique_ptr<compressible::GasSolver<2>> make_sod_slab(int n_left, int rows_left, double eta);
// As a 3D slab (y, z in [0, W]): spacings d and 2d give equal masses; the Wendland C2 kernel.
using GasSolver3W = compressible::GasSolver<3, WendlandC2<3>>;
std::unique_ptr<GasSolver3W> make_sod_slab_3d(int n_left, int rows_left, double eta);

Result run_sod(const Options& opt);

}  // namespace swell::verify
