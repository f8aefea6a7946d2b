// OpenFOAM (interFoam) reference runs generated from a Swell case file: `swell foam`.
//
// write_foam_case() turns a CaseSpec into a complete interFoam case on a Cartesian mesh
// (blockMesh for the tank, obstacles removed with topoSet + subsetMesh, water placed with
// setFields, probes and sampling lines at the case's gauges). run_foam_case() also runs it and
// converts the sampled output into gauges_<kind>.csv files in the exact format of an SPH run,
// so both can be compared column by column. The OpenFOAM programs are needed only at run time.
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include "case/spec.hpp"

namespace swell {

struct FoamOptions {
  std::string out_dir;        // the OpenFOAM case folder to write (created)
  double cell_size = 0.0;     // explicit cell size [m]; 0: from cells_per_dp
  double cells_per_dp = 1.0;  // cell = dp / cells_per_dp
  double end_time = -1.0;     // < 0: the case's time.end
  bool run = false;           // run_foam_case: run the case (write_foam_case ignores it)
  int np = 1;                 // > 1: decomposePar + mpirun -np N interFoam -parallel
};

struct FoamResult {
  std::string case_dir;   // the OpenFOAM case
  std::string gauge_dir;  // folder with gauges_<kind>.csv, same format/column names as SPH
  bool ran = false;
  double wall_seconds = 0.0;       // interFoam (solver only) wall time
  long cells = 0;                  // cells after obstacle removal
  double cell_size = 0.0;          // [m]
  long steps = 0;                  // interFoam time steps taken
  double end_time = 0.0;           // simulated end time [s]
  std::vector<std::string> notes;  // gauges skipped, approximations made
};

// A failure of an OpenFOAM step: absent programs, a failed utility, or a diverged run. The
// message names the step, its log file and the last relevant lines of the log.
class FoamError : public std::runtime_error {
 public:
  enum class Kind { Missing, Failed, Diverged };
  FoamError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const noexcept { return kind_; }

 private:
  Kind kind_;
};

// Writes the interFoam case for `spec` into opt.out_dir (generation only: no OpenFOAM needed).
// Throws std::invalid_argument for cases that cannot be meshed (no box tank, bad cell size).
FoamResult write_foam_case(const CaseSpec& spec, const FoamOptions& opt, std::ostream& log);

// write_foam_case, then blockMesh, topoSet + subsetMesh (obstacles), setFields, interFoam
// (serial or parallel), then converts postProcessing/ into <case>/gauges/gauges_<kind>.csv.
// Throws FoamError (Missing, Failed, Diverged).
FoamResult run_foam_case(const CaseSpec& spec, const FoamOptions& opt, std::ostream& log);

// Converts the postProcessing/ tree of the case in opt.out_dir (finished or not) into
// gauges_<kind>.csv files in `gauge_dir`, in the format and with the column names of an SPH
// run. `spec` and `opt` must be those the case was written with. Returns the files written.
std::vector<std::string> convert_foam_gauges(const CaseSpec& spec, const FoamOptions& opt,
                                             const std::string& gauge_dir, std::ostream& log);

// True when the OpenFOAM programs needed (blockMesh, setFields, interFoam, ...) are found;
// otherwise `why` (if given) says which are missing.
bool openfoam_available(std::string* why);

}  // namespace swell
