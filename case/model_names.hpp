// The names of the solver's model choices (solver/physics/kernels.hpp KernelType,
// solver/solver_params.hpp ViscosityModel, DiffusionModel, IntegratorType) as written in case
// files and outputs (HDF5 metadata): one name function per enum, and every value of each enum
// in the order the case-file reader lists them. The reader turns names into enums once, at
// parse time; nothing downstream compares model names.
#pragma once

#include <array>
#include <type_traits>

#include "solver/physics/kernels.hpp"
#include "solver/solver_params.hpp"

namespace swell {

inline constexpr std::array kKernelTypes{KernelType::Wendland, KernelType::Cubic,
                                         KernelType::Quintic, KernelType::Gaussian};
inline constexpr std::array kViscosityModels{ViscosityModel::Artificial, ViscosityModel::Laminar};
inline constexpr std::array kDiffusionModels{
    DiffusionModel::Fourtakas, DiffusionModel::MolteniColagrossi, DiffusionModel::None};
inline constexpr std::array kIntegratorTypes{IntegratorType::Symplectic, IntegratorType::Verlet};
inline constexpr std::array kBoundaryTypes{BoundaryType::Dbc, BoundaryType::Mdbc};
inline constexpr std::array kMdbcSlips{MdbcSlip::Wall, MdbcSlip::NoSlip, MdbcSlip::FreeSlip};
inline constexpr std::array kMdbcPressures{MdbcPressure::Linear, MdbcPressure::Hydrostatic};
inline constexpr std::array kShiftingModels{ShiftingModel::None, ShiftingModel::Fickian};
inline constexpr std::array kShiftModes{ShiftMode::Full, ShiftMode::NoBound, ShiftMode::NoFixed};

// The kernel type's own name (its kName: wendland, cubic, quintic, gaussian), the name
// kernel_from_name() reads back.
inline const char* kernel_name(KernelType k) {
  return with_kernel<3>(k, 1.0,
                        [](const auto& kernel) { return std::decay_t<decltype(kernel)>::kName; });
}

inline const char* viscosity_name(ViscosityModel m) {
  switch (m) {
    case ViscosityModel::Artificial:
      return "artificial";
    case ViscosityModel::Laminar:
      return "laminar";
  }
  return "viscosity";
}

inline const char* diffusion_name(DiffusionModel m) {
  switch (m) {
    case DiffusionModel::Fourtakas:
      return "fourtakas";
    case DiffusionModel::MolteniColagrossi:
      return "molteni";
    case DiffusionModel::None:
      return "none";
  }
  return "diffusion";
}

inline const char* integrator_name(IntegratorType t) {
  switch (t) {
    case IntegratorType::Symplectic:
      return "symplectic";
    case IntegratorType::Verlet:
      return "verlet";
  }
  return "integrator";
}

inline const char* boundary_name(BoundaryType t) {
  switch (t) {
    case BoundaryType::Dbc:
      return "dbc";
    case BoundaryType::Mdbc:
      return "mdbc";
  }
  return "boundary";
}

inline const char* mdbc_slip_name(MdbcSlip m) {
  switch (m) {
    case MdbcSlip::Wall:
      return "wall";
    case MdbcSlip::NoSlip:
      return "noslip";
    case MdbcSlip::FreeSlip:
      return "freeslip";
  }
  return "slip";
}

inline const char* mdbc_pressure_name(MdbcPressure m) {
  switch (m) {
    case MdbcPressure::Linear:
      return "linear";
    case MdbcPressure::Hydrostatic:
      return "hydrostatic";
  }
  return "pressure";
}

inline const char* shifting_name(ShiftingModel m) {
  switch (m) {
    case ShiftingModel::None:
      return "none";
    case ShiftingModel::Fickian:
      return "fickian";
  }
  return "shifting";
}

inline const char* shift_mode_name(ShiftMode m) {
  switch (m) {
    case ShiftMode::Full:
      return "full";
    case ShiftMode::NoBound:
      return "nobound";
    case ShiftMode::NoFixed:
      return "nofixed";
  }
  return "mode";
}

}  // namespace swell
