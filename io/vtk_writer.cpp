#include "io/vtk_writer.hpp"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTypeUInt16Array.h>
#include <vtkTypeUInt32Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace swell {

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::error_code ec;
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + tmp + ": " + std::strerror(errno));
    f << text;
    f.flush();
    if (!f) {
      const int err = errno;
      f.close();
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error("error while writing " + tmp + ": " + std::strerror(err));
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
}

void require_output_folder(const std::string& path, const std::string& option) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
    throw std::invalid_argument(option + ": the folder " + folder.string() +
                                " does not exist (create it first)");
}

template <int D>
void write_vtp(const std::string& path, const ParticleSet<D>& ps,
               const std::vector<double>& pressure, ParticleFilter filter,
               const std::vector<std::string>* body_names, double time) {
  std::vector<std::size_t> sel;
  sel.reserve(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const bool fluid = ps.role[i] == Role::Fluid;
    if (filter == ParticleFilter::All || (filter == ParticleFilter::Fluid) == fluid)
      sel.push_back(i);
  }
  const auto n = static_cast<vtkIdType>(sel.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> vel, rho, press;
  vel->SetName("velocity");
  vel->SetNumberOfComponents(3);
  vel->SetNumberOfTuples(n);
  rho->SetName("density");
  rho->SetNumberOfTuples(n);
  press->SetName("pressure");
  press->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> type;
  type->SetName("type");  // 0 fluid, 1 boundary
  type->SetNumberOfTuples(n);
  vtkNew<vtkTypeUInt16Array> body;
  body->SetName("body");
  body->SetNumberOfTuples(n);
  vtkNew<vtkTypeUInt32Array> id;
  id->SetName("id");
  id->SetNumberOfTuples(n);
  vtkNew<vtkIdTypeArray> conn;
  conn->SetNumberOfTuples(n);

  for (vtkIdType k = 0; k < n; ++k) {
    const std::size_t i = sel[static_cast<std::size_t>(k)];
    double x[3] = {0.0, 0.0, 0.0};
    float v[3] = {0.0f, 0.0f, 0.0f};
    for (int d = 0; d < D; ++d) {
      x[d] = ps.pos[i][d];
      v[d] = static_cast<float>(ps.vel[i][d]);
    }
    points->SetPoint(k, x);
    vel->SetTypedTuple(k, v);
    rho->SetValue(k, static_cast<float>(ps.rho[i]));
    press->SetValue(k, static_cast<float>(pressure[i]));
    type->SetValue(k, static_cast<unsigned char>(ps.role[i]));
    body->SetValue(k, ps.body[i]);
    id->SetValue(k, ps.id[i]);
    conn->SetValue(k, k);
  }
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(n + 1);
  for (vtkIdType k = 0; k <= n; ++k) offsets->SetValue(k, k);
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, conn);

  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetVerts(verts);
  poly->GetPointData()->AddArray(vel);
  poly->GetPointData()->AddArray(rho);
  poly->GetPointData()->AddArray(press);
  poly->GetPointData()->AddArray(type);
  poly->GetPointData()->AddArray(body);
  poly->GetPointData()->AddArray(id);
  // mDBC runs: each wall particle's vector to its wall surface (the ghost node is at
  // pos + 2 normal), so users can check the normals the geometry gave; zero for fluid.
  if (ps.normal.size() == ps.total()) {
    vtkNew<vtkFloatArray> normal;
    normal->SetName("wall_normal");
    normal->SetNumberOfComponents(3);
    normal->SetNumberOfTuples(n);
    for (vtkIdType k = 0; k < n; ++k) {
      float v[3] = {0.0f, 0.0f, 0.0f};
      const std::size_t i = sel[static_cast<std::size_t>(k)];
      for (int d = 0; d < D; ++d) v[d] = static_cast<float>(ps.normal[i][d]);
      normal->SetTypedTuple(k, v);
    }
    poly->GetPointData()->AddArray(normal);
  }
  if (body_names) {
    vtkNew<vtkStringArray> names;
    names->SetName("body_name");
    names->SetNumberOfValues(n);
    for (vtkIdType k = 0; k < n; ++k) {
      const std::size_t b = ps.body[sel[static_cast<std::size_t>(k)]];
      names->SetValue(k, b < body_names->size() ? (*body_names)[b] : std::string());
    }
    poly->GetPointData()->AddArray(names);
    vtkNew<vtkStringArray> all;
    all->SetName("body_names");
    all->SetNumberOfValues(static_cast<vtkIdType>(body_names->size()));
    for (std::size_t b = 0; b < body_names->size(); ++b)
      all->SetValue(static_cast<vtkIdType>(b), (*body_names)[b]);
    poly->GetFieldData()->AddArray(all);
  }
  if (std::isfinite(time)) {
    vtkNew<vtkDoubleArray> t;
    t->SetName("TimeValue");
    t->SetNumberOfTuples(1);
    t->SetValue(0, time);
    poly->GetFieldData()->AddArray(t);
  }

  const std::string tmp = path + ".tmp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(poly);
  writer->SetDataModeToBinary();
  std::error_code ec;
  if (writer->Write() != 1) {
    const int err = errno;  // the failed write's reason (VTK keeps only its own codes)
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("VTK writer failed on " + tmp + ": " + std::strerror(err));
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
}

std::string vtk_piece_name(const std::string& vtp, int rank) {
  const std::string stem = vtp.ends_with(".vtp") ? vtp.substr(0, vtp.size() - 4) : vtp;
  return stem + "_p" + std::to_string(rank) + ".vtp";
}

void write_pvtp(const std::string& path, const std::vector<std::string>& pieces, bool normals,
                bool body_names) {
  // The arrays write_vtp writes, in its order (the pieces' types: VTK XML type names).
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n"
    << "  <PPolyData GhostLevel=\"0\">\n"
    << "    <PPointData>\n"
    << "      <PDataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\"/>\n"
    << "      <PDataArray type=\"Float32\" Name=\"density\"/>\n"
    << "      <PDataArray type=\"Float32\" Name=\"pressure\"/>\n"
    << "      <PDataArray type=\"UInt8\" Name=\"type\"/>\n"
    << "      <PDataArray type=\"UInt16\" Name=\"body\"/>\n"
    << "      <PDataArray type=\"UInt32\" Name=\"id\"/>\n";
  if (normals)
    s << "      <PDataArray type=\"Float32\" Name=\"wall_normal\" NumberOfComponents=\"3\"/>\n";
  if (body_names) s << "      <PDataArray type=\"String\" Name=\"body_name\"/>\n";
  s << "    </PPointData>\n"
    << "    <PPoints>\n"
    << "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
    << "    </PPoints>\n";
  for (const auto& p : pieces) s << "    <Piece Source=\"" << p << "\"/>\n";
  s << "  </PPolyData>\n</VTKFile>\n";
  write_file_atomically(path, s.str());
}

void PvdSeries::resume(double t_keep) {
  entries_.clear();
  std::ifstream in(path_);
  std::string line;
  while (std::getline(in, line)) {
    const auto ts = line.find("timestep=\""), fs = line.find("file=\"");
    if (ts == std::string::npos || fs == std::string::npos) continue;
    const double t = std::stod(line.substr(ts + 10));
    const auto fe = line.find('"', fs + 6);
    if (t <= t_keep * (1.0 + 1e-9) + 1e-12)
      entries_.emplace_back(t, line.substr(fs + 6, fe - fs - 6));
  }
}

void PvdSeries::add(double time, const std::string& file) {
  entries_.emplace_back(time, file);
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n";
  s << std::setprecision(12);
  for (const auto& [t, f] : entries_)
    s << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, s.str());
}

template void write_vtp<2>(const std::string&, const ParticleSet<2>&, const std::vector<double>&,
                           ParticleFilter, const std::vector<std::string>*, double);
template void write_vtp<3>(const std::string&, const ParticleSet<3>&, const std::vector<double>&,
                           ParticleFilter, const std::vector<std::string>*, double);

}  // namespace swell
