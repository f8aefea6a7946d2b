// The header of a run's log: the case, its particles and domain, the derived quantities with
// their formulas (h, c0, B, mass, dt, wall layers), the wall model and shifting, the
// wavemakers, absorption, damping and settling, with the warnings of the set-up.
#pragma once

#include <string>

#include "case/setup.hpp"
#include "case/spec.hpp"

namespace swell {

// The header's lines (each ends with a newline), for a run on `ranks` ranks of the current
// OpenMP thread count.
template <int D>
std::string run_header(const CaseSpec& spec, const CaseSetup<D>& setup, int ranks);

}  // namespace swell
