#include "bc/dbc.hpp"

#include "solver/physics/wcsph_forces.hpp"

namespace swell {

template <int D>
void DbcBoundary<D>::forces(StepState<D>& s) {
  compute_forces<D, Selection>(s.particles, s.grid, s.params, s.eos, s.forces);
}

template class DbcBoundary<2>;
template class DbcBoundary<3>;

}  // namespace swell
