// `swell foam` without OpenFOAM: the generated dictionaries (mesh size, patches, water box,
// obstacle cells, probe positions) and the conversion of a postProcessing/ tree into the SPH
// gauge CSV format.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "case/reader.hpp"
#include "foam/foam.hpp"
#include "foam/plan.hpp"
#include "run/gauge_set.hpp"

namespace fs = std::filesystem;
using namespace swell;

namespace {

const std::string kCase = std::string(SWELL_SOURCE_DIR) + "/tests/data/foam_dambreak_small.yaml";

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(SWELL_BINARY_DIR) / "test_foam_case" / name;
  fs::remove_all(d);
  return d;
}

// The body of patch `name` in a blockMeshDict ("name { ... }"), empty if absent.
std::string patch_block(const std::string& dict, const std::string& name) {
  const auto k = dict.find("    " + name + "\n    {");
  if (k == std::string::npos) return "";
  return dict.substr(k, dict.find("\n    }", k) - k);
}

std::vector<double> numbers_after(const std::string& text, const std::string& key) {
  const auto k = text.find(key);
  std::vector<double> v;
  if (k == std::string::npos) return v;
  std::string line = text.substr(k + key.size(), text.find(';', k) - k - key.size());
  for (char& c : line)
    if (c == '(' || c == ')') c = ' ';
  std::istringstream in(line);
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

FoamOptions options(const fs::path& dir, double cell) {
  FoamOptions o;
  o.out_dir = dir.string();
  o.cell_size = cell;
  return o;
}

}  // namespace

TEST(FoamCase, BlockMeshSpansTheTankWithTheCellSize) {
  const CaseSpec spec = load_case_file(kCase);
  const fs::path dir = scratch("mesh");
  std::ostringstream log;
  const FoamResult r = write_foam_case(spec, options(dir, 0.004), log);
  const std::string bm = read(dir / "system/blockMeshDict");
  EXPECT_NE(bm.find("hex (0 1 2 3 4 5 6 7) (146 146 1)"), std::string::npos) << bm;
  // Obstacle 0.024 x 0.048 m = 6 x 12 cells removed.
  EXPECT_EQ(r.cells, 146L * 146 - 72);
  EXPECT_EQ(r.case_dir, dir.string());
  EXPECT_TRUE(fs::exists(dir / "Allrun"));
  for (const char* f :
       {"system/controlDict", "system/fvSchemes", "system/fvSolution", "system/setFieldsDict",
        "system/topoSetDict.obstacle", "constant/g", "constant/transportProperties", "0.orig/U",
        "0.orig/p_rgh", "0.orig/alpha.water"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;

  // --cells-per-dp: cell = dp / K (dp = 8 mm).
  FoamOptions o = options(scratch("per_dp"), 0.0);
  o.cells_per_dp = 2.0;
  write_foam_case(spec, o, log);
  EXPECT_NE(read(fs::path(o.out_dir) / "system/blockMeshDict").find("(146 146 1)"),
            std::string::npos);
  o = options(scratch("coarse"), 0.0);
  write_foam_case(spec, o, log);
  EXPECT_NE(read(fs::path(o.out_dir) / "system/blockMeshDict").find("(73 73 1)"),
            std::string::npos);
}

TEST(FoamCase, OpenFacesBecomeAtmosphereAndTheRestWalls) {
  const CaseSpec spec = load_case_file(kCase);
  const fs::path dir = scratch("patches");
  std::ostringstream log;
  write_foam_case(spec, options(dir, 0.008), log);
  const std::string bm = read(dir / "system/blockMeshDict");
  const std::string atmosphere = patch_block(bm, "atmosphere"), tank = patch_block(bm, "tank"),
                    empty = patch_block(bm, "frontAndBack");
  EXPECT_NE(atmosphere.find("type patch"), std::string::npos);
  EXPECT_NE(atmosphere.find("(3 7 6 2)"), std::string::npos);  // ymax
  EXPECT_EQ(atmosphere.find("(1 5 4 0)"), std::string::npos);
  EXPECT_NE(tank.find("type wall"), std::string::npos);
  for (const char* f : {"(0 4 7 3)", "(2 6 5 1)", "(1 5 4 0)"})
    EXPECT_NE(tank.find(f), std::string::npos) << f;
  EXPECT_EQ(tank.find("(3 7 6 2)"), std::string::npos);
  EXPECT_NE(empty.find("type empty"), std::string::npos);
  EXPECT_NE(patch_block(bm, "obstacle").find("type wall"), std::string::npos);

  // The atmosphere conditions of the damBreak tutorial.
  EXPECT_NE(read(dir / "0.orig/p_rgh").find("totalPressure"), std::string::npos);
  EXPECT_NE(read(dir / "0.orig/U").find("pressureInletOutletVelocity"), std::string::npos);
  EXPECT_NE(read(dir / "0.orig/alpha.water").find("inletOutlet"), std::string::npos);
  EXPECT_NE(read(dir / "constant/g").find("(0 -9.81 0)"), std::string::npos);

  // A closed tank has no atmosphere patch at all.
  CaseSpec closed = spec;
  closed.bodies[0].open.clear();
  const fs::path dir2 = scratch("closed");
  write_foam_case(closed, options(dir2, 0.008), log);
  EXPECT_TRUE(patch_block(read(dir2 / "system/blockMeshDict"), "atmosphere").empty());
  EXPECT_EQ(read(dir2 / "0.orig/U").find("atmosphere"), std::string::npos);
}

TEST(FoamCase, WaterBoxGoesToSetFields) {
  const CaseSpec spec = load_case_file(kCase);
  const fs::path dir = scratch("setfields");
  std::ostringstream log;
  write_foam_case(spec, options(dir, 0.004), log);
  const std::string sf = read(dir / "system/setFieldsDict");
  const auto box = numbers_after(sf, "box ");
  ASSERT_EQ(box.size(), 6u) << sf;
  const std::vector<double> expected{0, 0, -1, 0.1461, 0.292, 1};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(box[i], expected[i], 1e-6) << i;
  EXPECT_NE(sf.find("volScalarFieldValue alpha.water 1"), std::string::npos);

  // The plan's water cells: centres inside the box, 37 x 73 at 4 mm.
  const foam::Plan plan = foam::make_plan(spec, options(dir, 0.004));
  long wet = 0;
  for (auto w : plan.wet) wet += w;
  EXPECT_EQ(wet, 37L * 73);
}

TEST(FoamCase, ObstacleCellsAreThoseWhoseCentreIsInside) {
  CaseSpec spec = load_case_file(kCase);
  const foam::Plan plan = foam::make_plan(spec, options(scratch("obstacle"), 0.004));
  ASSERT_EQ(plan.obstacles.size(), 1u);
  const auto& ob = plan.obstacles[0];
  EXPECT_TRUE(ob.is_box);
  std::vector<long> expected;
  for (int j = 0; j < 12; ++j)
    for (int i = 73; i < 79; ++i) expected.push_back(i + 146L * j);
  EXPECT_EQ(ob.cells, expected);

  // A disc (not a box): selected cell by cell, cut after the box, labels in the cut mesh.
  BodySpec disc = spec.bodies[1];
  disc.name = "post";
  disc.shape = ShapeSpec{};
  disc.shape.type = ShapeSpec::Type::Cylinder;
  disc.shape.p1 = Eigen::Vector3d(0.45, 0.1, 0.0);
  disc.shape.radius = 0.03;
  spec.bodies.insert(spec.bodies.begin() + 2, disc);
  const fs::path dir = scratch("disc");
  const foam::Plan p2 = foam::make_plan(spec, options(dir, 0.004));
  ASSERT_EQ(p2.obstacles.size(), 2u);
  const auto& post = p2.obstacles[1];
  EXPECT_FALSE(post.is_box);
  long inside = 0;
  for (long c = 0; c < p2.grid.count(); ++c) {
    const Eigen::Vector3d x = p2.grid.centre(c);
    const bool in = std::hypot(x[0] - 0.45, x[1] - 0.1) < 0.03;
    inside += in;
    EXPECT_EQ(in, std::binary_search(post.cells.begin(), post.cells.end(), c)) << c;
  }
  EXPECT_EQ(static_cast<long>(post.cells.size()), inside);
  EXPECT_NEAR(inside * 0.004 * 0.004, M_PI * 0.03 * 0.03, 0.05 * M_PI * 0.03 * 0.03);
  // Labels count the cells left after the box cut (72 cells, all with lower row indices or
  // interleaved): label = cell - (box cells numbered before it).
  for (std::size_t k = 0; k < post.cells.size(); ++k) {
    const long c = post.cells[k];
    const long before =
        std::count_if(ob.cells.begin(), ob.cells.end(), [&](long b) { return b < c; });
    EXPECT_EQ(post.labels[k], c - before);
  }
  std::ostringstream log;
  write_foam_case(spec, options(dir, 0.004), log);
  EXPECT_NE(read(dir / "system/topoSetDict.post").find("labelToCell"), std::string::npos);
  EXPECT_EQ(p2.kept_cells, 146L * 146 - 72 - inside);
}

TEST(FoamCase, ProbesSitAtTheGauges) {
  CaseSpec spec = load_case_file(kCase);
  GaugeSpec right;
  right.name = "P_right";
  right.kind = GaugeSpec::Kind::Pressure;
  right.at = Eigen::Vector3d(0.584, 0.03, 0);
  right.normal = Eigen::Vector3d(-1, 0, 0);
  spec.gauges.push_back(right);
  GaugeSpec obst = right;  // on the obstacle's upstream face
  obst.name = "P_obst";
  obst.at = Eigen::Vector3d(0.292, 0.01, 0);
  spec.gauges.push_back(obst);
  const fs::path dir = scratch("probes");
  const foam::Plan plan = foam::make_plan(spec, options(dir, 0.004));
  ASSERT_EQ(plan.probes.size(), 5u);
  // P_wall at (0, 0.02), normal +x: the first cell centre, 2 mm off the wall (y = 0.02 lies on
  // a cell face and is moved 1e-4 cell up).
  const auto& pw = plan.probes[1];
  EXPECT_EQ(pw.spec.name, "P_wall");
  EXPECT_NEAR(pw.point.x(), 0.002, 1e-12);
  EXPECT_NEAR(pw.point.y(), 0.02, 1e-6);
  EXPECT_GT(pw.point.y(), 0.02);
  EXPECT_NEAR(plan.probes[3].point.x(), 0.582, 1e-12);
  EXPECT_NEAR(plan.probes[3].point.y(), 0.03, 1e-12);  // cell centre 0.03 = (7 + 1/2) 4 mm
  EXPECT_NEAR(plan.probes[4].point.x(), 0.290, 1e-12);
  for (const auto& p : plan.probes) EXPECT_FALSE(p.skipped) << p.spec.name;
  // Height: vertical line from `at` to the tank top.
  const auto& h = plan.probes[2];
  EXPECT_NEAR(h.start.x(), 0.073, 1e-12);
  EXPECT_NEAR(h.start.y(), 0.0, 1e-12);
  EXPECT_NEAR(h.end.y(), 0.584, 1e-12);
  // Front: the first cell row above the water's bottom.
  const auto& f = plan.probes[0];
  ASSERT_EQ(f.line_starts.size(), 1u);
  EXPECT_NEAR(f.line_starts[0].y(), 0.002, 1e-12);
  EXPECT_NEAR(f.line_starts[0].x(), 0.002, 1e-12);
  EXPECT_NEAR(f.line_ends[0].x(), 0.582, 1e-12);
  EXPECT_EQ(f.points, 146);

  std::ostringstream log;
  write_foam_case(spec, options(dir, 0.004), log);
  const std::string cd = read(dir / "system/controlDict");
  EXPECT_NE(cd.find("(0.002 0.0200004 0)  // P_wall"), std::string::npos) << cd;
  EXPECT_NE(cd.find("(0.582 0.03 0)  // P_right"), std::string::npos);
  EXPECT_NE(cd.find("writeInterval   0.01;"), std::string::npos);  // output.gauge_every
  EXPECT_NE(cd.find("maxCo           0.5;"), std::string::npos);
  EXPECT_NE(cd.find("endTime         0.3;"), std::string::npos);
}

TEST(FoamCase, FrontFromARowOfCells) {
  const double nan = std::nan("");
  // Wet run from the wall, then a partly filled cell.
  EXPECT_NEAR(foam::front_from_row({1, 1, 0.9, 0.3, 0, 0}, 0.0, 0.1), 0.33, 1e-12);
  // Water levels, both definitions, on a column of 0.3 with a detached layer above a dry gap:
  // the surface level is where alpha crosses 0.5 (0.25 + 0.1 * 0.4 / 0.8), the integral adds
  // the layer.
  const std::vector<double> col = {1, 1, 0.9, 0.1, 0, 0, 1, 1, 0, 0};
  EXPECT_NEAR(foam::level_surface(col, 0.0, 0.1), 0.25, 1e-12);
  EXPECT_NEAR(foam::level_integral(col, 0.0, 0.1), 0.1 * (0.5 + 1 + 0.9 + 0.1 + 1 + 1), 1e-12);
  EXPECT_NEAR(foam::level_surface({0, 0, 0, 0, 1, 1}, 0.5, 0.1), 0.5, 1e-12);  // dry bed
  EXPECT_NEAR(foam::level_surface({1, 1, 1}, 0.0, 0.1), 0.2, 1e-12);           // full line
  // A solid gap (NaN) is crossed when the water continues behind it.
  EXPECT_NEAR(foam::front_from_row({1, 1, nan, nan, 1, 0.2}, 0.0, 0.1), 0.52, 1e-12);
  // Stopped at the gap.
  EXPECT_NEAR(foam::front_from_row({1, 1, nan, nan, 0, 0}, 0.0, 0.1), 0.2, 1e-12);
  // A detached droplet further on is not the front.
  EXPECT_NEAR(foam::front_from_row({1, 0, 0, 1, 0}, 1.0, 0.1), 1.1, 1e-12);
  EXPECT_TRUE(std::isnan(foam::front_from_row({0, 0.2, 0}, 0.0, 0.1)));
}

TEST(FoamCase, PostProcessingConvertsToTheSphCsvFormat) {
  CaseSpec spec = load_case_file(kCase);
  GaugeSpec v;
  v.name = "V1";
  v.kind = GaugeSpec::Kind::Velocity;
  v.at = Eigen::Vector3d(0.1, 0.02, 0);
  v.every = 0.02;
  spec.gauges.push_back(v);
  GaugeSpec force;
  force.name = "F_obs";
  force.kind = GaugeSpec::Kind::Force;
  force.body = "obstacle";
  spec.gauges.push_back(force);
  const fs::path dir = scratch("convert");
  const FoamOptions opt = options(dir, 0.008);
  std::ostringstream log;
  write_foam_case(spec, opt, log);
  const foam::Plan plan = foam::make_plan(spec, opt);

  // A synthetic postProcessing/ tree as interFoam (v1912) writes it.
  const fs::path pp = dir / "postProcessing";
  fs::create_directories(pp / "pressure_0/0");
  std::ofstream(pp / "pressure_0/0/p") << "# Probe 0 (0.004 0.0200008 0)\n#     Probe    0\n"
                                       << "#      Time\n      0.01   863.5\n      0.02  900.25\n";
  fs::create_directories(pp / "velocity_0/0");
  std::ofstream(pp / "velocity_0/0/U") << "# Probe 0 (0.1 0.02 0)\n#   Probe 0\n#   Time\n"
                                       << "   0.02   (0.5 -0.25 0)\n";
  for (const char* t : {"0.01", "0.02"}) {
    fs::create_directories(pp / "height_0" / t);
    std::ofstream h(pp / "height_0" / t / "H1_alpha.water.xy");
    const auto& hp = plan.probes[2];
    for (int k = 0; k < hp.points; ++k) {
      const double y = hp.start.y() + k * (hp.end.y() - hp.start.y()) / (hp.points - 1);
      h << "0.073\t" << y << "\t0\t" << (y < 0.1 ? 1.0 : 0.0) << "\n";
    }
    fs::create_directories(pp / "front_0" / t);
    std::ofstream f(pp / "front_0" / t / "front_0_alpha.water.xy");
    for (int i = 0; i < 20; ++i)  // the first 20 cells of the row; the rest dry
      f << 0.004 + 0.008 * i << "\t0.004\t0\t" << (i < 10 ? 1.0 : i == 10 ? 0.25 : 0.0) << "\n";
  }
  fs::create_directories(pp / "force_F_obs/0");
  std::ofstream(pp / "force_F_obs/0/force.dat")
      << "# Force\n# CofR : (0 0 0)\n#\n# Time\t(total_x total_y total_z)\t(pressure_x ...)\n"
      << "0.01\t(0.008 -0.016 0)\t(0.008 -0.016 0)\t(0 0 0)\n";
  std::ofstream(pp / "force_F_obs/0/moment.dat")
      << "# Moment\n#\n0.01\t(0 0 0.004)\t(0 0 0.004)\t(0 0 0)\n";

  const auto files = convert_foam_gauges(spec, opt, (dir / "gauges").string(), log);
  EXPECT_EQ(files.size(), 5u);

  // Headers: the SPH run's column names (run/gauge_set.cpp) for the same gauges.
  auto header = [](const std::string& text) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
      if (line.empty() || line[0] != '#') return line;
    return std::string();
  };
  const std::string pcsv = read(dir / "gauges/gauges_pressure.csv");
  EXPECT_EQ(pcsv.rfind("# ", 0), 0u);
  EXPECT_EQ(header(pcsv), "time [s],P_wall [Pa]");
  EXPECT_NE(pcsv.find("\n0.01,863.5\n0.02,900.25\n"), std::string::npos) << pcsv;
  const std::string vcsv = read(dir / "gauges/gauges_velocity.csv");
  EXPECT_EQ(header(vcsv), "time [s],V1_vx [m/s],V1_vy [m/s]");
  EXPECT_NE(vcsv.find("\n0.02,0.5,-0.25\n"), std::string::npos) << vcsv;
  // Height: the line is wet up to y = 0.1 (sampled every 2 mm): 0.1 within one sample.
  const std::string hcsv = read(dir / "gauges/gauges_height.csv");
  EXPECT_EQ(header(hcsv), "time [s],H1 [m]");
  std::istringstream hin(hcsv.substr(hcsv.find("\n0.01,") + 6));
  double height = 0;
  hin >> height;
  EXPECT_NEAR(height, 0.1, 0.002);
  // Front: 10 wet cells of 8 mm + a quarter of the next.
  const std::string fcsv = read(dir / "gauges/gauges_front.csv");
  EXPECT_EQ(header(fcsv), "time [s],front [m]");
  EXPECT_NE(fcsv.find("\n0.01,0.082\n0.02,0.082\n"), std::string::npos) << fcsv;
  // Force: per metre of width (the 2D mesh is one 8 mm cell thick).
  const std::string ccsv = read(dir / "gauges/gauges_force.csv");
  EXPECT_EQ(header(ccsv), "time [s],F_obs_fx [N/m],F_obs_fy [N/m],F_obs_mz [N m/m]");
  EXPECT_NE(ccsv.find("\n0.01,1,-2,0.5\n"), std::string::npos) << ccsv;

  // A location interFoam (v1912) finds in no cell keeps its header line, marked "# Not Found",
  // and its column holds -VGREAT: the gauge is not converted (no -1e300 Pa), and the log says
  // why.
  std::ofstream(pp / "pressure_0/0/p") << "# Probe 0 (0.004 0.0200008 0) # Not Found\n"
                                       << "#     Probe    0\n#      Time\n"
                                       << "      0.01   -1e+300\n";
  std::ostringstream log2;
  convert_foam_gauges(spec, opt, (dir / "gauges").string(), log2);
  EXPECT_NE(log2.str().find("gauge P_wall not converted"), std::string::npos) << log2.str();
  EXPECT_NE(log2.str().find("\"Not Found\""), std::string::npos) << log2.str();
  EXPECT_EQ(read(dir / "gauges/gauges_pressure.csv").find("e+300"), std::string::npos);
  // A header that lists another number of locations than the case has (output of an earlier
  // version of the case): the columns cannot be matched to the gauges.
  std::ofstream(pp / "pressure_0/0/p") << "# Probe 0 (0.004 0.0200008 0)\n# Probe 1 (0.1 0.1 0)\n"
                                       << "#     Probe    0    1\n#      Time\n"
                                       << "      0.01   863.5   12.0\n";
  std::ostringstream log3;
  convert_foam_gauges(spec, opt, (dir / "gauges").string(), log3);
  EXPECT_NE(log3.str().find("declares 2 probe locations where the case has 1"), std::string::npos)
      << log3.str();
  EXPECT_EQ(read(dir / "gauges/gauges_pressure.csv").find("863.5"), std::string::npos);
  // A -VGREAT sample under an unmarked header reads as no value (nan), never as -1e300 Pa.
  std::ofstream(pp / "pressure_0/0/p")
      << "# Probe 0 (0.004 0.0200008 0)\n#     Probe    0\n"
      << "#      Time\n      0.01   -1e+300\n      0.02   900.25\n";
  convert_foam_gauges(spec, opt, (dir / "gauges").string(), log3);
  const std::string nan_csv = read(dir / "gauges/gauges_pressure.csv");
  EXPECT_NE(nan_csv.find("\n0.01,nan\n0.02,900.25\n"), std::string::npos) << nan_csv;
}

TEST(FoamCase, CasesItCannotMeshAreRefused) {
  CaseSpec spec = load_case_file(kCase);
  std::ostringstream log;
  FoamOptions bad = options(scratch("bad"), 0.0);
  bad.cells_per_dp = 0.0;
  EXPECT_THROW(write_foam_case(spec, bad, log), std::invalid_argument);
  spec.bodies[0].walls = BodySpec::Walls::Outside;  // no tank left
  try {
    write_foam_case(spec, options(scratch("bad"), 0.008), log);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("box tank"), std::string::npos) << e.what();
  }
}

TEST(FoamCase, MissingOpenFoamIsAClearErrorAndTheCaseIsStillWritten) {
  const CaseSpec spec = load_case_file(kCase);
  const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", "/nonexistent", 1);
  std::string why;
  const bool available = openfoam_available(&why);
  const fs::path dir = scratch("missing");
  FoamOptions o = options(dir, 0.008);
  o.run = true;
  std::ostringstream log;
  bool thrown = false;
  try {
    run_foam_case(spec, o, log);
  } catch (const FoamError& e) {
    thrown = true;
    EXPECT_EQ(e.kind(), FoamError::Kind::Missing);
    const std::string m = e.what();
    EXPECT_NE(m.find("interFoam"), std::string::npos) << m;
    EXPECT_NE(m.find("apt-get install openfoam"), std::string::npos) << m;
    EXPECT_NE(m.find(dir.string()), std::string::npos) << m;
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_FALSE(available);
  EXPECT_NE(why.find("blockMesh"), std::string::npos) << why;
  EXPECT_TRUE(thrown);
  EXPECT_TRUE(fs::exists(dir / "system/controlDict"));
}

TEST(FoamCase, SolverLogVerdicts) {
  const fs::path dir = scratch("logs");
  fs::create_directories(dir);
  const std::string banner =
      "trapFpe: Floating point exception trapping enabled (FOAM_SIGFPE).\n"
      "sigFpe : Enabling floating point exception trapping (FOAM_SIGFPE).\n";
  auto write = [&](const std::string& name, const std::string& body) {
    std::ofstream(dir / name) << banner << body;
    return (dir / name).string();
  };
  const std::string ok = write("ok",
                               "Courant Number mean: 0 max: 0.1\ndeltaT = 0.001\nTime = 0.1\n"
                               "deltaT = 0.001\nTime = 0.2\nEnd\n");
  auto v = foam::check_solver_log(ok, 0.2, 0, "");
  EXPECT_TRUE(v.problem.empty()) << v.problem;  // the banner is no floating point exception
  EXPECT_EQ(v.steps, 2);
  EXPECT_DOUBLE_EQ(v.last_time, 0.2);

  v = foam::check_solver_log(ok, 0.5, 0, "");  // ended before the end time
  EXPECT_EQ(v.kind, FoamError::Kind::Diverged);
  EXPECT_NE(v.problem.find("before the end time"), std::string::npos);

  const std::string nan = write("nan",
                                "deltaT = 0.001\nTime = 0.1\n"
                                "Courant Number mean: nan max: nan\n");
  v = foam::check_solver_log(nan, 0.2, 136, "");
  EXPECT_EQ(v.kind, FoamError::Kind::Diverged);
  EXPECT_TRUE(v.nan);

  const std::string fpe = write("fpe",
                                "Time = 0.1\n#1  Foam::sigFpe::sigHandler(int) at ??\n"
                                "Floating point exception (core dumped)\n");
  v = foam::check_solver_log(fpe, 0.2, 136, "");
  EXPECT_EQ(v.kind, FoamError::Kind::Diverged);
  EXPECT_NE(v.problem.find("floating point"), std::string::npos);

  const std::string fatal = write("fatal", "--> FOAM FATAL ERROR:\ncannot find patch\n");
  v = foam::check_solver_log(fatal, 0.2, 1, "");
  EXPECT_EQ(v.kind, FoamError::Kind::Failed);
  EXPECT_TRUE(v.fatal);

  v = foam::check_solver_log(ok, 0.2, 143, "time step collapsed to 1e-09 s");
  EXPECT_EQ(v.kind, FoamError::Kind::Diverged);
  EXPECT_NE(v.problem.find("collapsed"), std::string::npos);
}

// Sampling lines: OpenFOAM's own `uniform` set where every point lies strictly inside the kept
// mesh, a cloud of the same points where a line crosses an obstacle or starts on the boundary.
TEST(FoamCase, SampleLinesAreUniformWhereTheyFitAndCloudsElse) {
  const CaseSpec spec = load_case_file(kCase);
  std::ostringstream log;
  const fs::path dir = scratch("sets_obstacle");
  write_foam_case(spec, options(dir, 0.004), log);
  std::string cd = read(dir / "system/controlDict");
  // The front row (y = 2 mm) runs through the obstacle, the height line starts on the floor.
  auto block = [](const std::string& text, const std::string& name) {
    const auto k = text.find("            " + name + "\n            {");
    return k == std::string::npos ? std::string()
                                  : text.substr(k, text.find("            }", k) - k);
  };
  EXPECT_NE(block(cd, "front_0").find("type    cloud;"), std::string::npos) << cd;
  EXPECT_NE(block(cd, "H1").find("type    cloud;"), std::string::npos);

  // Without the obstacle the front row fits: a uniform line of the same 146 cell centres.
  CaseSpec open = spec;
  open.bodies.erase(std::remove_if(open.bodies.begin(), open.bodies.end(),
                                   [](const BodySpec& b) { return b.name == "obstacle"; }),
                    open.bodies.end());
  const fs::path dir2 = scratch("sets_open");
  write_foam_case(open, options(dir2, 0.004), log);
  cd = read(dir2 / "system/controlDict");
  const std::string f = block(cd, "front_0");
  EXPECT_NE(f.find("type    uniform;"), std::string::npos) << f;
  EXPECT_NE(f.find("start   (0.002 0.002 0);"), std::string::npos) << f;
  EXPECT_NE(f.find("end     (0.582 0.002 0);"), std::string::npos) << f;
  EXPECT_NE(f.find("nPoints 146;"), std::string::npos) << f;
  EXPECT_EQ(f.find("points\n"), std::string::npos);
  EXPECT_LT(cd.size(), read(dir / "system/controlDict").size());
}

// Allclean removes what a run makes (time folders, logs, mesh, postProcessing, gauges) and
// keeps the generated case (system/, constant/ dictionaries, 0.orig/, Allrun).
TEST(FoamCase, AllcleanRemovesTheRunAndKeepsTheCase) {
  const CaseSpec spec = load_case_file(kCase);
  std::ostringstream log;
  const fs::path dir = scratch("allclean");
  write_foam_case(spec, options(dir, 0.008), log);
  for (const char* d : {"0", "0.1", "0.25", "1e-05", "postProcessing/probes/0", "processor0/0",
                        "gauges", "constant/polyMesh", "notes"})
    fs::create_directories(dir / d);
  for (const char* f : {"log.blockMesh", "log.interFoam", "gauges/x.csv", "notes/keep.txt"})
    std::ofstream(dir / f) << "x\n";
  ASSERT_EQ(std::system(("sh " + (dir / "Allclean").string()).c_str()), 0);
  for (const char* gone : {"0", "0.1", "0.25", "1e-05", "postProcessing", "processor0", "gauges",
                           "constant/polyMesh", "log.blockMesh", "log.interFoam"})
    EXPECT_FALSE(fs::exists(dir / gone)) << gone;
  for (const char* kept :
       {"0.orig/U", "system/controlDict", "constant/g", "Allrun", "Allclean", "notes/keep.txt"})
    EXPECT_TRUE(fs::exists(dir / kept)) << kept;
  // Allrun passes --allow-run-as-root to mpirun only when run as root.
  const std::string run = read(dir / "Allrun");
  EXPECT_NE(run.find("[ \"$(id -u)\" -eq 0 ] && ROOT=--allow-run-as-root"), std::string::npos);
  EXPECT_EQ(run.find("mpirun --allow-run-as-root"), std::string::npos);
}

// `swell foam --run` progress: time of end time, Courant numbers, time left at the mean rate.
TEST(FoamCase, ProgressLineFromTheSolverLog) {
  const fs::path dir = scratch("progress");
  fs::create_directories(dir);
  std::ofstream(dir / "log") << "Courant Number mean: 0.01 max: 0.31\n"
                                "Interface Courant Number mean: 0 max: 0.12\n"
                                "deltaT = 0.0005\nTime = 0.5\n"
                                "Courant Number mean: 0.02 max: 0.42\n"
                                "Interface Courant Number mean: 0 max: 0.17\n"
                                "deltaT = 0.0004\nTime = 1\n";
  const auto v = foam::check_solver_log((dir / "log").string(), 4.0, 0, "");
  EXPECT_DOUBLE_EQ(v.courant_max, 0.42);
  EXPECT_DOUBLE_EQ(v.interface_courant_max, 0.17);
  const std::string line = foam::progress_line(v, 4.0, 20.0);
  EXPECT_NE(line.find("t = 1 of 4 s (25 %)"), std::string::npos) << line;
  EXPECT_NE(line.find("Courant max 0.42 (interface 0.17)"), std::string::npos) << line;
  EXPECT_NE(line.find("dt 0.0004 s"), std::string::npos) << line;
  EXPECT_NE(line.find("about 60 s left"), std::string::npos) << line;  // 20 s per 1 s, 3 s left
  foam::SolverLog none;
  EXPECT_EQ(foam::progress_line(none, 4.0, 3.0).find("left"), std::string::npos);
}
