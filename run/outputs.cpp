#include "run/outputs.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "case/model_names.hpp"
#include "swell/version.hpp"

namespace swell {

namespace fs = std::filesystem;

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long total = static_cast<long>(s + 0.5);
  std::ostringstream o;
  if (total >= 3600)
    o << total / 3600 << ":" << std::setw(2) << std::setfill('0') << (total / 60) % 60;
  else
    o << total / 60;
  o << ":" << std::setw(2) << std::setfill('0') << total % 60;
  return o.str();
}

std::string vtk_file(const std::string& name, const char* part, int k, bool pieces) {
  char num[32];
  std::snprintf(num, sizeof(num), "_%04d", k);
  return "vtk/" + name + part + num + (pieces ? ".pvtp" : ".vtp");
}

template <int D>
bool shared_snapshot(const fs::path& out, const CaseSpec& spec, int k, long step, double time,
                     const ParticleSet<D>& ps, const std::vector<double>& p,
                     const std::vector<std::string>& body_names, bool normals,
                     const WriteShare& share, const parallel::Comm& comm, Hdf5RunFile* h5,
                     std::vector<PvdSeries*> pvds) {
  const bool root = comm.rank() == 0;
  // Every rank's pieces, agreed; then rank 0's .pvtp files and .pvd entries, agreed: a .pvtp
  // is listed only once all its pieces exist.
  auto agreed = [&](const std::string& err, const std::string& what) {
    if (comm.min(err.empty() ? 1.0 : 0.0) == 1.0) return true;
    if (!root) {
      if (!err.empty()) std::fprintf(stderr, "swell (rank %d): %s\n", comm.rank(), err.c_str());
      return false;
    }
    throw std::runtime_error(err.empty() ? what : err);
  };
  if (spec.vtk) {
    std::vector<std::pair<const char*, ParticleFilter>> parts = {{"", ParticleFilter::All}};
    if (spec.vtk_split)
      parts.insert(parts.end(),
                   {{"_fluid", ParticleFilter::Fluid}, {"_boundary", ParticleFilter::Boundary}});
    auto piece_of = [&](std::size_t j) {
      const std::string rel = vtk_file(spec.name, parts[j].first, k, true);
      return rel.substr(0, rel.size() - 5) + ".vtp";  // vtk_piece_name adds the rank
    };
    std::string err;
    try {
      for (std::size_t j = 0; j < parts.size(); ++j)
        write_vtp<D>((out / vtk_piece_name(piece_of(j), comm.rank())).string(), ps, p,
                     parts[j].second, &body_names, time);
    } catch (const std::exception& e) {
      err = e.what();
    }
    if (!agreed(err, "another rank could not write its VTK piece of snapshot " + std::to_string(k) +
                         " (that rank's message is above)"))
      return false;
    try {
      for (std::size_t j = 0; j < parts.size() && root; ++j) {
        const std::string rel = vtk_file(spec.name, parts[j].first, k, true);
        std::vector<std::string> pieces;
        for (int r = 0; r < comm.size(); ++r)
          pieces.push_back(fs::path(vtk_piece_name(piece_of(j), r)).filename().string());
        write_pvtp((out / rel).string(), pieces, normals, true);
        pvds.at(j)->add(time, rel);
      }
    } catch (const std::exception& e) {
      err = e.what();
    }
    if (!agreed(err, "")) return false;
  }
  if (!spec.hdf5) return true;
  if (root) {
    h5->write_snapshot<D>(step, time, ps, p, &share);
    return true;
  }
  return write_snapshot_rows<D>((out / (spec.name + ".h5")).string(), step, ps, p, share);
}

template <int D>
RunMetadata make_metadata(const CaseSpec& spec, const CaseSetup<D>& setup, const RunSummary& sum,
                          const Provenance& prov) {
  RunMetadata m;
  m.provenance = prov;
  m.case_name = spec.name;
  m.case_file = spec.file;
  m.case_text = spec.text;
  m.version = SWELL_VERSION;
  m.dim = D;
  m.dp = spec.dp;
  m.h = setup.params.h;
  m.c0 = setup.params.c0;
  m.rho0 = setup.params.rho0;
  m.kernel = kernel_name(setup.params.kernel);
  m.n_fluid = sum.fluid;
  m.n_boundary = sum.boundary;
  for (const auto& b : setup.bodies) m.body_names.push_back(b.name);
  return m;
}

template bool shared_snapshot<2>(const fs::path&, const CaseSpec&, int, long, double,
                                 const ParticleSet<2>&, const std::vector<double>&,
                                 const std::vector<std::string>&, bool, const WriteShare&,
                                 const parallel::Comm&, Hdf5RunFile*, std::vector<PvdSeries*>);
template bool shared_snapshot<3>(const fs::path&, const CaseSpec&, int, long, double,
                                 const ParticleSet<3>&, const std::vector<double>&,
                                 const std::vector<std::string>&, bool, const WriteShare&,
                                 const parallel::Comm&, Hdf5RunFile*, std::vector<PvdSeries*>);
template RunMetadata make_metadata<2>(const CaseSpec&, const CaseSetup<2>&, const RunSummary&,
                                      const Provenance&);
template RunMetadata make_metadata<3>(const CaseSpec&, const CaseSetup<3>&, const RunSummary&,
                                      const Provenance&);

}  // namespace swell
