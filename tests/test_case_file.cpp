// Tests for case/reader: valid cases parse to the expected values and defaults, and each class
// of mistake in a case file is reported as "<file>:<line>: ..." naming the offending key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "case/model_names.hpp"
#include "case/reader.hpp"

namespace swell {
namespace {

const char* const kLabel = "cases/test.yaml";

// Succeeds when parsing `text` throws a CaseError located at `line` of kLabel whose message
// contains every string in `parts`.
testing::AssertionResult ThrowsCaseError(const std::string& text, int line,
                                         const std::vector<std::string>& parts) {
  try {
    parse_case_text(text, kLabel);
  } catch (const CaseError& e) {
    const std::string what = e.what();
    const std::string prefix = std::string(kLabel) + ":" + std::to_string(line) + ": ";
    if (e.line() != line || what.rfind(prefix, 0) != 0) {
      return testing::AssertionFailure() << "expected line " << line << ", got: " << what;
    }
    for (const std::string& part : parts) {
      if (what.find(part) == std::string::npos) {
        return testing::AssertionFailure() << "'" << part << "' not in: " << what;
      }
    }
    return testing::AssertionSuccess() << what;
  }
  return testing::AssertionFailure() << "no CaseError thrown";
}

// A minimal valid 2D case; error tests below spell out their whole text so lines are visible.
const char* const kMinimal2d = R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}}}
)";

// ---------------------------------------------------------------------------------------------
// Valid cases

TEST(CaseFile, Parses2dCaseWithAllKeys) {
  const std::string text = R"(# a comment line
name: dambreak2d
dim: 2
dp: 0.0014
physics:
  rho0: 1000
  gravity: [0, -9.81]
  coefsound: 20
  coefh: 1.0
  hswl: 0.3
  kernel: cubic
  viscosity: {model: laminar, nu: 1e-6}
  density_diffusion: {model: molteni, delta: 0.05}
  density_bounds: [0.8, 1.2]
time: {end: 0.5, cfl: 0.25, integrator: verlet, verlet_steps: 30}
domain: {min: [-0.1, -0.1], max: [0.4, 0.5]}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [0.3, 0.2]}}, walls: inside, layers: 3, open: [ymax]}
  - name: water
    kind: fluid
    shape: {box: {min: [0, 0], max: [0.057, 0.114]}}
output: {every: 0.01, vtk: false, vtk_split: true, hdf5: false, checkpoint_every: 0, gauge_every: 0.002}
)";
  const CaseSpec spec = parse_case_text(text, kLabel);
  EXPECT_EQ(spec.file, kLabel);
  EXPECT_EQ(spec.text, text);
  EXPECT_EQ(spec.name, "dambreak2d");
  EXPECT_EQ(spec.dim, 2);
  EXPECT_DOUBLE_EQ(spec.dp, 0.0014);
  EXPECT_DOUBLE_EQ(spec.rho0, 1000.0);
  EXPECT_EQ(spec.gravity, Eigen::Vector3d(0.0, -9.81, 0.0));
  EXPECT_DOUBLE_EQ(spec.coefsound, 20.0);
  EXPECT_DOUBLE_EQ(spec.coefh, 1.0);
  ASSERT_TRUE(spec.hswl.has_value());
  EXPECT_DOUBLE_EQ(*spec.hswl, 0.3);
  EXPECT_EQ(spec.kernel, KernelType::Cubic);
  EXPECT_EQ(spec.viscosity_model, ViscosityModel::Laminar);
  EXPECT_DOUBLE_EQ(spec.nu, 1e-6);
  EXPECT_EQ(spec.diffusion_model, DiffusionModel::MolteniColagrossi);
  EXPECT_DOUBLE_EQ(spec.delta, 0.05);
  EXPECT_DOUBLE_EQ(spec.rho_min_factor, 0.8);
  EXPECT_DOUBLE_EQ(spec.rho_max_factor, 1.2);
  EXPECT_DOUBLE_EQ(spec.t_end, 0.5);
  EXPECT_DOUBLE_EQ(spec.cfl, 0.25);
  EXPECT_EQ(spec.integrator, IntegratorType::Verlet);
  EXPECT_EQ(spec.verlet_steps, 30);
  ASSERT_TRUE(spec.domain_min && spec.domain_max);
  EXPECT_EQ(*spec.domain_min, Eigen::Vector3d(-0.1, -0.1, 0.0));
  EXPECT_EQ(*spec.domain_max, Eigen::Vector3d(0.4, 0.5, 0.0));
  EXPECT_DOUBLE_EQ(spec.output_every, 0.01);
  EXPECT_FALSE(spec.vtk);
  EXPECT_TRUE(spec.vtk_split);
  EXPECT_FALSE(spec.hdf5);
  EXPECT_DOUBLE_EQ(spec.checkpoint_every, 0.0);
  EXPECT_DOUBLE_EQ(spec.gauge_every, 0.002);
  EXPECT_TRUE(spec.gauges.empty());

  ASSERT_EQ(spec.bodies.size(), 2u);
  const BodySpec& tank = spec.bodies[0];
  EXPECT_EQ(tank.name, "tank");
  EXPECT_EQ(tank.kind, BodySpec::Kind::Boundary);
  EXPECT_EQ(tank.shape.type, ShapeSpec::Type::Box);
  EXPECT_EQ(tank.shape.box.min, Eigen::Vector3d(0.0, 0.0, 0.0));
  EXPECT_EQ(tank.shape.box.max, Eigen::Vector3d(0.3, 0.2, 0.0));
  EXPECT_EQ(tank.walls, BodySpec::Walls::Inside);
  EXPECT_EQ(tank.layers, 3);
  EXPECT_EQ(tank.open, std::vector<std::string>{"ymax"});
  EXPECT_EQ(tank.line, 18);
  const BodySpec& water = spec.bodies[1];
  EXPECT_EQ(water.name, "water");
  EXPECT_EQ(water.kind, BodySpec::Kind::Fluid);
  EXPECT_EQ(water.shape.box.max, Eigen::Vector3d(0.057, 0.114, 0.0));
  EXPECT_EQ(water.line, 19);
}

TEST(CaseFile, Parses3dCaseAndAppliesDefaults) {
  const std::string text = R"(dim: 3
dp: 0.02
time: {end: 2}
bodies:
  - name: box
    kind: boundary
    shape: {box: {min: [0, 0, 0], max: [1, 0.5, 0.6]}}
    walls: outside
    open: [zmax, xmin]
  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [0.4, 0.5, 0.3]}}}
)";
  const CaseSpec spec = parse_case_text(text, "some/dir/wave_tank.yaml");
  const CaseSpec defaults;
  EXPECT_EQ(spec.name, "wave_tank");  // default: file stem
  EXPECT_EQ(spec.dim, 3);
  EXPECT_DOUBLE_EQ(spec.dp, 0.02);
  EXPECT_EQ(spec.gravity, Eigen::Vector3d(0.0, 0.0, -9.81));  // default in 3D: -z
  EXPECT_DOUBLE_EQ(spec.rho0, defaults.rho0);
  EXPECT_DOUBLE_EQ(spec.coefsound, defaults.coefsound);
  EXPECT_DOUBLE_EQ(spec.coefh, defaults.coefh);
  EXPECT_FALSE(spec.hswl.has_value());
  EXPECT_EQ(spec.kernel, KernelType::Wendland);
  EXPECT_EQ(spec.viscosity_model, ViscosityModel::Artificial);
  EXPECT_DOUBLE_EQ(spec.alpha, defaults.alpha);
  EXPECT_EQ(spec.diffusion_model, DiffusionModel::Fourtakas);
  EXPECT_DOUBLE_EQ(spec.delta, defaults.delta);
  EXPECT_DOUBLE_EQ(spec.rho_min_factor, defaults.rho_min_factor);
  EXPECT_DOUBLE_EQ(spec.rho_max_factor, defaults.rho_max_factor);
  EXPECT_DOUBLE_EQ(spec.t_end, 2.0);
  EXPECT_DOUBLE_EQ(spec.cfl, defaults.cfl);
  EXPECT_EQ(spec.integrator, IntegratorType::Symplectic);
  EXPECT_EQ(spec.verlet_steps, defaults.verlet_steps);
  EXPECT_FALSE(spec.domain_min.has_value());
  EXPECT_FALSE(spec.domain_max.has_value());
  EXPECT_DOUBLE_EQ(spec.output_every, 0.0);
  EXPECT_TRUE(spec.vtk);
  EXPECT_FALSE(spec.vtk_split);
  EXPECT_TRUE(spec.hdf5);
  EXPECT_DOUBLE_EQ(spec.checkpoint_every, 0.0);
  EXPECT_DOUBLE_EQ(spec.gauge_every, 0.0);
  EXPECT_TRUE(spec.gauges.empty());

  ASSERT_EQ(spec.bodies.size(), 2u);
  EXPECT_EQ(spec.bodies[0].walls, BodySpec::Walls::Outside);
  EXPECT_EQ(spec.bodies[0].layers, 3);
  EXPECT_EQ(spec.bodies[0].open, (std::vector<std::string>{"zmax", "xmin"}));
  EXPECT_EQ(spec.bodies[0].shape.box.max, Eigen::Vector3d(1.0, 0.5, 0.6));
  EXPECT_EQ(spec.bodies[0].line, 5);
  EXPECT_EQ(spec.bodies[1].line, 10);
  EXPECT_TRUE(spec.bodies[1].open.empty());
}

TEST(CaseFile, ParsesModelVariants) {
  const std::string text = R"(dim: 2
dp: 0.01
physics:
  gravity: [1, -5]
  viscosity: {alpha: 0.05}
  density_diffusion: {model: none}
time: {end: 1, cfl: 1}
bodies:
  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}}}
)";
  const CaseSpec spec = parse_case_text(text, kLabel);
  EXPECT_EQ(spec.gravity, Eigen::Vector3d(1.0, -5.0, 0.0));
  EXPECT_EQ(spec.viscosity_model, ViscosityModel::Artificial);
  EXPECT_DOUBLE_EQ(spec.alpha, 0.05);
  EXPECT_EQ(spec.diffusion_model, DiffusionModel::None);
  EXPECT_DOUBLE_EQ(spec.cfl, 1.0);
  EXPECT_EQ(spec.name, "test");
}

// Every model name the reader accepts is the name function's, and reads back as its enum.
TEST(CaseFile, ModelNamesReadBackAsTheirEnums) {
  const auto parse = [](const std::string& physics, const std::string& time) {
    return parse_case_text("dim: 2\ndp: 0.01\nphysics: " + physics + "\ntime: {end: 1" + time +
                               "}\nbodies:\n  - {name: water, kind: fluid, shape: {box: "
                               "{min: [0, 0], max: [1, 1]}}}\n",
                           kLabel);
  };
  for (const KernelType k : kKernelTypes) {
    EXPECT_EQ(parse("{kernel: " + std::string(kernel_name(k)) + "}", "").kernel, k);
    EXPECT_EQ(kernel_from_name(kernel_name(k)), k);  // the solver's reader of the HDF5 name
  }
  for (const ViscosityModel m : kViscosityModels) {
    const std::string text = "{viscosity: {model: " + std::string(viscosity_name(m)) + "}}";
    EXPECT_EQ(parse(text, "").viscosity_model, m);
  }
  for (const DiffusionModel m : kDiffusionModels) {
    const std::string text = "{density_diffusion: {model: " + std::string(diffusion_name(m)) + "}}";
    EXPECT_EQ(parse(text, "").diffusion_model, m);
  }
  for (const IntegratorType t : kIntegratorTypes)
    EXPECT_EQ(parse("{}", ", integrator: " + std::string(integrator_name(t))).integrator, t);
}

// ---------------------------------------------------------------------------------------------
// Files

TEST(CaseFile, LoadsFromFile) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("swell_case_" + std::to_string(::getpid()) + "_dam.yaml");
  {
    std::ofstream out(path);
    out << kMinimal2d;
  }
  const CaseSpec spec = load_case_file(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(spec.file, path.string());
  EXPECT_EQ(spec.text, kMinimal2d);
  EXPECT_EQ(spec.name, path.stem().string());
  EXPECT_EQ(spec.dim, 2);
  ASSERT_EQ(spec.bodies.size(), 1u);
  EXPECT_EQ(spec.bodies[0].line, 5);
}

// `swell run --set`: edits of a case file from the command line (case/reader.hpp).
TEST(CaseFileSets, EditsCreateReplaceAndAppendAndAreReadLikeTheFile) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("swell_case_" + std::to_string(::getpid()) + "_sets.yaml");
  {
    std::ofstream out(path);
    out << kMinimal2d << "gauges:\n  - {name: P1, kind: pressure, at: [0.5, 0.1]}\n";
  }
  const CaseSpec plain = load_case_file(path.string(), {});
  const CaseSpec spec = load_case_file(
      path.string(),
      {"physics.boundary.model=mdbc", "physics.shifting={model: fickian}", "time.end=0.25",
       "bodies.0.name=column", "gauges.1={name: H1, kind: height, at: [0.5, 0.0]}", "dp=0.02"});
  std::filesystem::remove(path);
  EXPECT_EQ(plain.text.find("boundary"), std::string::npos);
  EXPECT_EQ(spec.file, path.string());
  EXPECT_EQ(spec.boundary, BoundaryType::Mdbc);      // a map created on the way
  EXPECT_EQ(spec.shifting, ShiftingModel::Fickian);  // a map value
  EXPECT_DOUBLE_EQ(spec.t_end, 0.25);                // a key replaced in a flow map
  EXPECT_DOUBLE_EQ(spec.dp, 0.02);                   // a top-level scalar
  ASSERT_EQ(spec.bodies.size(), 1u);
  EXPECT_EQ(spec.bodies[0].name, "column");  // a list item by index
  ASSERT_EQ(spec.gauges.size(), 2u);         // appended after the last item
  EXPECT_EQ(spec.gauges[1].name, "H1");
  // The text holds the edits, so a checkpoint's case identity sees them.
  EXPECT_NE(spec.text.find("mdbc"), std::string::npos);
  EXPECT_EQ(spec.text.find("mdbc"), spec.text.rfind("mdbc"));
}

TEST(CaseFileSets, EditedValuesAreCheckedLikeHandWrittenKeys) {
  const std::string file = "cases/test.yaml";
  // A bad value or an unknown key goes through the ordinary reader: key named, exit-2 error.
  try {
    parse_case_text(edit_case_text(kMinimal2d, {"physics.boundary.model=mdcb"}, file), file);
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("physics.boundary.model"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mdcb"), std::string::npos) << e.what();
  }
  try {
    parse_case_text(edit_case_text(kMinimal2d, {"physics.shiftng.model=fickian"}, file), file);
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("shiftng"), std::string::npos) << e.what();
  }
}

TEST(CaseFileSets, MalformedEditsNameTheEdit) {
  const std::string file = "cases/test.yaml";
  const auto error_of = [&](const std::string& set) -> std::string {
    try {
      edit_case_text(kMinimal2d, {set}, file);
    } catch (const CaseError& e) {
      EXPECT_EQ(e.file(), file);
      return e.what();
    }
    return "no error";
  };
  const auto has = [](const std::string& what, const std::string& part) {
    return what.find(part) != std::string::npos;
  };
  std::string w = error_of("physics.boundary.model");
  EXPECT_TRUE(has(w, "--set physics.boundary.model") && has(w, "key.path=value")) << w;
  w = error_of("=mdbc");
  EXPECT_TRUE(has(w, "key.path=value")) << w;
  w = error_of("dp=");
  EXPECT_TRUE(has(w, "no value")) << w;
  w = error_of("physics..model=mdbc");
  EXPECT_TRUE(has(w, "empty key")) << w;
  w = error_of("bodies.3.name=x");
  EXPECT_TRUE(has(w, "'bodies' has 1 items, no item 3")) << w;
  w = error_of("bodies.first.name=x");
  EXPECT_TRUE(has(w, "'bodies' is a list") && has(w, "'first'")) << w;
  w = error_of("dp.value=0.01");
  EXPECT_TRUE(has(w, "'dp' holds a value, not a map")) << w;
  w = error_of("time.end=[1, 2");
  EXPECT_TRUE(has(w, "not valid YAML")) << w;
}

TEST(CaseFile, MissingFileNamesTheFile) {
  const std::string path = "/nonexistent/dir/no_such_case.yaml";
  try {
    load_case_file(path);
    FAIL() << "no CaseError thrown";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

TEST(CaseFile, DirectoryIsNotACaseFile) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_THROW(load_case_file(dir), CaseError);
}

// ---------------------------------------------------------------------------------------------
// YAML structure

TEST(CaseFileErrors, YamlSyntaxError) {
  EXPECT_TRUE(
      ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1\nbodies: []\n", 4, {"YAML syntax error"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\n  dp: 0.01\n", 2, {"YAML syntax error"}));
}

TEST(CaseFileErrors, EmptyOrNonMapFile) {
  EXPECT_TRUE(ThrowsCaseError("", 1, {"empty"}));
  EXPECT_TRUE(ThrowsCaseError("# nothing\n", 1, {"empty"}));
  EXPECT_TRUE(ThrowsCaseError("- dim\n- dp\n", 1, {"expected a map", "dim, dp"}));
}

TEST(CaseFileErrors, SecondDocument) {
  EXPECT_TRUE(ThrowsCaseError(std::string(kMinimal2d) + "---\ndim: 3\n", 7, {"---"}));
}

TEST(CaseFileErrors, DuplicateKey) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1, cfl: 0.2, cfl: 0.3}
)",
                              3, {"duplicate key 'time.cfl'"}));
}

// ---------------------------------------------------------------------------------------------
// Unknown keys

TEST(CaseFileErrors, UnknownTopLevelKey) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
gravity: [0, -9.81]
)",
                              3, {"unknown key 'gravity'", "allowed keys", "physics", "bodies"}));
}

TEST(CaseFileErrors, UnknownNestedKeys) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
physics:
  rho0: 1000
  viscocity: {alpha: 0.1}
)",
                              5, {"unknown key 'physics.viscocity'", "viscosity", "kernel"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
physics:
  viscosity: {model: artificial, nu: 1e-6}
)",
                              4, {"physics.viscosity.nu", "model artificial", "model, alpha"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
physics:
  density_diffusion: {model: none, delta: 0.1}
)",
                              4, {"physics.density_diffusion.delta", "allowed keys"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1, dt: 0.001}
)",
                              3, {"time.dt", "end, cfl, dt_fixed, integrator, verlet_steps"}));
  EXPECT_TRUE(
      ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - name: water
    kind: fluid
    colour: blue
)",
                      7, {"bodies[0].colour", "name, kind, shape, fill, walls, layers, open"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - name: water
    kind: fluid
    shape:
      box: {min: [0, 0], max: [1, 1], centre: [0.5, 0.5]}
)",
                              8, {"bodies[0].shape.box.centre", "min, max"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kMinimal2d) + "output: {every: 0.1, vtu: true}\n", 6,
      {"output.vtu", "every, vtk, vtk_split, hdf5, checkpoint_every, gauge_every"}));
}

// ---------------------------------------------------------------------------------------------
// Wrong types

TEST(CaseFileErrors, ExpectedANumber) {
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: small\n", 2, {"dp", "expected a number", "'small'"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
physics:
  rho0: '1000'
)",
                              4, {"physics.rho0", "expected a number"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
physics:
  viscosity:
    model: artificial
    alpha: [0.01]
)",
                              6, {"physics.viscosity.alpha", "expected a number"}));
}

TEST(CaseFileErrors, ExpectedAnIntegerOrBoolean) {
  EXPECT_TRUE(ThrowsCaseError("dim: 2.5\n", 1, {"dim", "expected an integer"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kMinimal2d) + "output:\n  vtk: maybe\n", 7,
                              {"output.vtk", "expected true or false"}));
}

TEST(CaseFileErrors, VectorLengthFollowsDim) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
physics:
  gravity: [0, 0, -9.81]
)",
                              4, {"physics.gravity", "expected a list of 2 numbers"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 3
dp: 0.01
time: {end: 1}
bodies:
  - name: water
    kind: fluid
    shape: {box: {min: [0, 0], max: [1, 1, 1]}}
)",
                              7, {"bodies[0].shape.box.min", "expected a list of 3 numbers"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
domain:
  min: [0, 0]
  max: [1, up]
)",
                              6, {"domain.max", "expected a list of 2 numbers", "'up'"}));
}

TEST(CaseFileErrors, WrongStructure) {
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\nphysics: 3\n", 3, {"physics", "expected a map"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies: {name: water}\n", 4,
                              {"bodies", "expected a non-empty list"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies: []\n", 4,
                              {"bodies", "expected a non-empty list"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}, open: ymax}
)",
                              5, {"bodies[0].open", "expected a list of faces"}));
}

// ---------------------------------------------------------------------------------------------
// Missing required keys

TEST(CaseFileErrors, MissingTopLevelKeys) {
  EXPECT_TRUE(ThrowsCaseError("dp: 0.01\ntime: {end: 1}\n", 1, {"missing required key 'dim'"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ntime: {end: 1}\n", 1, {"missing required key 'dp'"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\n", 1, {"missing required key 'time'"}));
  EXPECT_TRUE(
      ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1}\n", 1, {"missing required key 'bodies'"}));
}

TEST(CaseFileErrors, MissingTimeEnd) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time:
  cfl: 0.2
)",
                              4, {"missing required key 'time.end'"}));
}

TEST(CaseFileErrors, MissingBodyKeys) {
  const std::string head = "dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n";
  EXPECT_TRUE(
      ThrowsCaseError(head + "  - {kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}}}\n", 5,
                      {"missing required key 'bodies[0].name'"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: w, shape: {box: {min: [0, 0], max: [1, 1]}}}\n", 5,
                              {"missing required key 'bodies[0].kind'"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: w, kind: fluid}\n", 5,
                              {"missing required key 'bodies[0].shape'", "bodies[0].fill"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: t, kind: boundary}\n", 5,
                              {"missing required key 'bodies[0].shape'"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: w, kind: fluid, shape: {box: {min: [0, 0]}}}\n", 5,
                              {"missing required key 'bodies[0].shape.box.max'"}));
}

TEST(CaseFileErrors, DomainNeedsMinAndMax) {
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1}\ndomain: {min: [0, 0]}\n", 4,
                              {"missing required key 'domain.max'"}));
}

// ---------------------------------------------------------------------------------------------
// Invalid values

TEST(CaseFileErrors, InvalidDpAndDim) {
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0\n", 2, {"dp", "> 0", "'0'"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: -0.01\n", 2, {"dp", "> 0"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 4\ndp: 0.01\n", 1, {"dim", "2 or 3", "'4'"}));
}

TEST(CaseFileErrors, InvalidTimeValues) {
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 0}\n", 3, {"time.end", "> 0"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: -1}\n", 3, {"time.end", "> 0"}));
  EXPECT_TRUE(
      ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1, cfl: 0}\n", 3, {"time.cfl", "(0, 1]"}));
  EXPECT_TRUE(
      ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1, cfl: 1.5}\n", 3, {"time.cfl", "(0, 1]"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1, integrator: euler}\n", 3,
                              {"time.integrator", "'euler'", "symplectic, verlet"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1, verlet_steps: 0}\n", 3,
                              {"time.verlet_steps", ">= 1"}));
}

TEST(CaseFileErrors, InvalidPhysicsValues) {
  const std::string head = "dim: 2\ndp: 0.01\nphysics:\n";
  EXPECT_TRUE(ThrowsCaseError(head + "  rho0: 0\n", 4, {"physics.rho0", "> 0"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  rho0: -1000\n", 4, {"physics.rho0", "> 0"}));
  EXPECT_TRUE(
      ThrowsCaseError(head + "  kernel: wendlnd\n", 4,
                      {"physics.kernel", "'wendlnd'", "wendland, cubic, quintic, gaussian"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  viscosity: {model: sps}\n", 4,
                              {"physics.viscosity.model", "artificial, laminar"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  density_diffusion: {model: antuono}\n", 4,
                              {"physics.density_diffusion.model", "fourtakas, molteni, none"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  viscosity: {alpha: -0.1}\n", 4,
                              {"physics.viscosity.alpha", ">= 0"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  coefh: 0\n", 4, {"physics.coefh", "[0.5, 4]"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  coefh: 1000\n", 4, {"physics.coefh", "[0.5, 4]"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  gravity: [0, 0]\n", 4, {"physics.gravity", "non-zero"}));
  EXPECT_TRUE(
      ThrowsCaseError(head + "  density_bounds: [1.1, 1.3]\n", 4, {"physics.density_bounds"}));
}

TEST(CaseFileErrors, InvalidOutputValues) {
  const std::string head = std::string(kMinimal2d) + "output:\n  every: 0.1\n";
  EXPECT_TRUE(ThrowsCaseError(std::string(kMinimal2d) + "output: {every: -0.1}\n", 6,
                              {"output.every", ">= 0"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  checkpoint_every: -0.05\n", 8,
                              {"output.checkpoint_every", "expected a number >= 0", "'-0.05'"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  gauge_every: 0\n", 8,
                              {"output.gauge_every", "expected a number > 0", "'0'"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  gauge_every: -0.001\n", 8,
                              {"output.gauge_every", "expected a number > 0"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  vtk_split: yes please\n", 8,
                              {"output.vtk_split", "expected true or false"}));
  EXPECT_TRUE(
      ThrowsCaseError(head + "  hdf5: 1.5\n", 8, {"output.hdf5", "expected true or false"}));
}

TEST(CaseFileErrors, InvalidBoxAndDomainExtent) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - name: water
    kind: fluid
    shape:
      box:
        min: [0, 0.5]
        max: [1, 0.5]
)",
                              10, {"bodies[0].shape.box", "min < max", "on y"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 3
dp: 0.01
time: {end: 1}
domain: {min: [0, 0, 2], max: [1, 1, 1]}
)",
                              4, {"domain", "min < max", "on z"}));
}

TEST(CaseFileErrors, InvalidBodyValues) {
  const std::string head = "dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n";
  const std::string box = "shape: {box: {min: [0, 0], max: [1, 1]}}";
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: w, kind: solid, " + box + "}\n", 5,
                              {"bodies[0].kind", "'solid'", "fluid, boundary"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: '', kind: fluid, " + box + "}\n", 5,
                              {"bodies[0].name", "non-empty"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: t, kind: boundary, layers: 0, " + box + "}\n", 5,
                              {"bodies[0].layers", ">= 1"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: t, kind: boundary, walls: around, " + box + "}\n",
                              5, {"bodies[0].walls", "inside, outside"}));
}

TEST(CaseFileErrors, ShapeMustBeOneKnownKind) {
  const std::string head = "dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n";
  EXPECT_TRUE(
      ThrowsCaseError(head + "  - name: w\n    kind: fluid\n    shape:\n      cone: {r: 1}\n", 8,
                      {"unknown shape 'bodies[0].shape.cone'",
                       "known shapes: box, cylinder, sphere, polygon, mesh, stl, union, "
                       "difference"}));
  EXPECT_TRUE(ThrowsCaseError(
      head + "  - {name: w, kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}, stl: a.stl}}\n",
      5, {"bodies[0].shape", "exactly one shape key"}));
}

TEST(CaseFileErrors, BoundaryOnlyKeysOnFluid) {
  const std::string head = "dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n";
  const std::string box = "shape: {box: {min: [0, 0], max: [1, 1]}}";
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: water, kind: fluid, walls: inside, " + box + "}\n",
                              5, {"bodies[0].walls", "only boundary bodies", "'water'"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: water, kind: fluid, layers: 2, " + box + "}\n", 5,
                              {"bodies[0].layers", "only boundary bodies"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: water, kind: fluid, open: [ymax], " + box + "}\n",
                              5, {"bodies[0].open", "only boundary bodies"}));
}

TEST(CaseFileErrors, InvalidOpenFaces) {
  const std::string head = "dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n";
  const std::string box = "shape: {box: {min: [0, 0], max: [1, 1]}}";
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: t, kind: boundary, open: [zmax], " + box + "}\n",
                              5, {"bodies[0].open[0]", "'zmax'", "2D"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - {name: t, kind: boundary, open: [top], " + box + "}\n", 5,
                              {"bodies[0].open[0]", "'top'", "xmin, xmax, ymin, ymax"}));
  EXPECT_TRUE(
      ThrowsCaseError(head + "  - {name: t, kind: boundary, open: [ymax, ymax], " + box + "}\n", 5,
                      {"bodies[0].open[1]", "twice"}));
}

TEST(CaseFileErrors, DuplicateBodyNames) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}}}
  - name: water
    kind: fluid
    shape: {box: {min: [2, 0], max: [3, 1]}}
)",
                              6, {"bodies[1].name", "duplicate body name 'water'", "line 5"}));
}

TEST(CaseFileErrors, NoFluidBody) {
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}
)",
                              5, {"bodies", "no fluid body", "kind: fluid"}));
}

// ---------------------------------------------------------------------------------------------
// Shapes

const char* const kHead2d = "dim: 2\ndp: 0.01\ntime: {end: 1}\nbodies:\n";  // body 0 on line 5
const char* const kHead3d = "dim: 3\ndp: 0.02\ntime: {end: 1}\nbodies:\n";

// A fluid body to append after boundary bodies, so that the case is valid.
const char* const kWater2d =
    "  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}}}\n";
const char* const kWater3d =
    "  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [1, 1, 1]}}}\n";

TEST(CaseFileShapes, ParsesEveryKindIn2d) {
  const std::string text = std::string(kHead2d) + R"(  - name: disc
    kind: boundary
    shape: {cylinder: {center: [0.5, 0.25], radius: 0.1}}
  - {name: ball, kind: boundary, shape: {sphere: {center: [0.2, 0.3], radius: 0.05}}}
  - name: ramp
    kind: boundary
    shape:
      polygon:
        points: [[1, 0], [2, 0], [2, 0.2]]
  - name: beach
    kind: boundary
    shape: {mesh: {file: geometry/flume_beach.stl, slice_y: 0.15}}
    walls: outside
    layers: 2
  - name: caisson
    kind: boundary
    shape:
      stl: {file: caisson.STL, scale: 0.001, rotate: [0, 0, 90], translate: [2.6, 0, 0.1], repair: true, slice_y: -0.5}
    open: [ymax]
)" + kWater2d;
  const CaseSpec spec = parse_case_text(text, kLabel);
  ASSERT_EQ(spec.bodies.size(), 6u);

  const ShapeSpec& disc = spec.bodies[0].shape;
  EXPECT_EQ(disc.type, ShapeSpec::Type::Cylinder);
  EXPECT_EQ(disc.p1, Eigen::Vector3d(0.5, 0.25, 0.0));
  EXPECT_DOUBLE_EQ(disc.radius, 0.1);
  EXPECT_EQ(disc.line, 7);

  const ShapeSpec& ball = spec.bodies[1].shape;
  EXPECT_EQ(ball.type, ShapeSpec::Type::Sphere);
  EXPECT_EQ(ball.p1, Eigen::Vector3d(0.2, 0.3, 0.0));
  EXPECT_DOUBLE_EQ(ball.radius, 0.05);
  EXPECT_EQ(ball.line, 8);

  const ShapeSpec& ramp = spec.bodies[2].shape;
  EXPECT_EQ(ramp.type, ShapeSpec::Type::Polygon);
  ASSERT_EQ(ramp.points.size(), 3u);
  EXPECT_EQ(ramp.points[0], Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_EQ(ramp.points[1], Eigen::Vector3d(2.0, 0.0, 0.0));
  EXPECT_EQ(ramp.points[2], Eigen::Vector3d(2.0, 0.2, 0.0));
  EXPECT_EQ(ramp.line, 12);  // a block map starts at its first key

  const ShapeSpec& beach = spec.bodies[3].shape;
  EXPECT_EQ(beach.type, ShapeSpec::Type::Mesh);
  EXPECT_EQ(beach.file, "geometry/flume_beach.stl");
  EXPECT_EQ(beach.placement.scale, Eigen::Vector3d::Ones());  // defaults
  EXPECT_EQ(beach.placement.rotate_deg, Eigen::Vector3d::Zero());
  EXPECT_EQ(beach.placement.translate, Eigen::Vector3d::Zero());
  EXPECT_FALSE(beach.repair);
  ASSERT_TRUE(beach.slice_y.has_value());
  EXPECT_DOUBLE_EQ(*beach.slice_y, 0.15);
  EXPECT_EQ(beach.line, 16);
  EXPECT_EQ(spec.bodies[3].walls, BodySpec::Walls::Outside);
  EXPECT_EQ(spec.bodies[3].layers, 2);

  // `stl:` is a synonym of `mesh:`; rotate and translate are 3-vectors even in 2D.
  const BodySpec& caisson = spec.bodies[4];
  EXPECT_EQ(caisson.shape.type, ShapeSpec::Type::Mesh);
  EXPECT_EQ(caisson.shape.file, "caisson.STL");
  EXPECT_EQ(caisson.shape.placement.scale, Eigen::Vector3d::Constant(0.001));
  EXPECT_EQ(caisson.shape.placement.rotate_deg, Eigen::Vector3d(0.0, 0.0, 90.0));
  EXPECT_EQ(caisson.shape.placement.translate, Eigen::Vector3d(2.6, 0.0, 0.1));
  EXPECT_TRUE(caisson.shape.repair);
  EXPECT_DOUBLE_EQ(*caisson.shape.slice_y, -0.5);
  EXPECT_EQ(caisson.shape.line, 22);
  EXPECT_EQ(caisson.open, std::vector<std::string>{"ymax"});  // open faces on any shape

  EXPECT_EQ(spec.bodies[5].shape.type, ShapeSpec::Type::Box);
  EXPECT_EQ(spec.bodies[5].shape.line, 24);
  EXPECT_FALSE(spec.bodies[5].fill_below.has_value());
  EXPECT_TRUE(spec.bodies[5].fill_inside.empty());
}

TEST(CaseFileShapes, ParsesEveryKindIn3d) {
  const std::string text = std::string(kHead3d) + R"(  - name: pile
    kind: boundary
    shape: {cylinder: {p1: [1, 0.5, 0], p2: [1, 0.5, 0.8], radius: 0.05}}
    walls: outside
  - {name: ball, kind: boundary, shape: {sphere: {center: [0.2, 0.3, 0.4], radius: 0.05}}}
  - {name: box, kind: boundary, shape: {box: {min: [0, 0, 0], max: [1, 2, 3]}}}
  - name: beach
    kind: boundary
    shape:
      mesh:
        file: flume_beach.stl
        scale: [1, 2, 0.5]
        rotate: [90, 0, -45]
        translate: [0.5, -1, 2]
        repair: false
  - {name: a, kind: boundary, shape: {mesh: {file: part.obj}}}
  - {name: b, kind: boundary, shape: {stl: {file: dir.v2/part.Off}}}
  - {name: c, kind: boundary, shape: {mesh: {file: "with space.PLY"}}}
)" + kWater3d;
  const CaseSpec spec = parse_case_text(text, kLabel);
  ASSERT_EQ(spec.bodies.size(), 8u);

  const ShapeSpec& pile = spec.bodies[0].shape;
  EXPECT_EQ(pile.type, ShapeSpec::Type::Cylinder);
  EXPECT_EQ(pile.p1, Eigen::Vector3d(1.0, 0.5, 0.0));
  EXPECT_EQ(pile.p2, Eigen::Vector3d(1.0, 0.5, 0.8));
  EXPECT_DOUBLE_EQ(pile.radius, 0.05);
  EXPECT_EQ(pile.line, 7);

  const ShapeSpec& ball = spec.bodies[1].shape;
  EXPECT_EQ(ball.type, ShapeSpec::Type::Sphere);
  EXPECT_EQ(ball.p1, Eigen::Vector3d(0.2, 0.3, 0.4));
  EXPECT_EQ(ball.line, 9);

  const ShapeSpec& box = spec.bodies[2].shape;
  EXPECT_EQ(box.type, ShapeSpec::Type::Box);
  EXPECT_EQ(box.box.max, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(box.line, 10);

  const ShapeSpec& beach = spec.bodies[3].shape;
  EXPECT_EQ(beach.type, ShapeSpec::Type::Mesh);
  EXPECT_EQ(beach.file, "flume_beach.stl");
  EXPECT_EQ(beach.placement.scale, Eigen::Vector3d(1.0, 2.0, 0.5));
  EXPECT_EQ(beach.placement.rotate_deg, Eigen::Vector3d(90.0, 0.0, -45.0));
  EXPECT_EQ(beach.placement.translate, Eigen::Vector3d(0.5, -1.0, 2.0));
  EXPECT_FALSE(beach.repair);
  EXPECT_FALSE(beach.slice_y.has_value());
  EXPECT_EQ(beach.line, 14);

  EXPECT_EQ(spec.bodies[4].shape.file, "part.obj");
  EXPECT_EQ(spec.bodies[5].shape.type, ShapeSpec::Type::Mesh);
  EXPECT_EQ(spec.bodies[5].shape.file, "dir.v2/part.Off");
  EXPECT_EQ(spec.bodies[6].shape.file, "with space.PLY");
}

TEST(CaseFileShapes, ParsesNestedUnionAndDifference) {
  const std::string text = std::string(kHead2d) + R"(  - name: harbour
    kind: boundary
    walls: outside
    shape:
      difference:
        - union:
            - box: {min: [0, 0], max: [1, 0.5]}
            - {sphere: {center: [1, 0.25], radius: 0.25}}
        - cylinder:
            center: [0.5, 0.5]
            radius: 0.2
        - polygon: {points: [[0, 0], [0.2, 0], [0, 0.2]]}
)" + kWater2d;
  const CaseSpec spec = parse_case_text(text, kLabel);
  const ShapeSpec& diff = spec.bodies[0].shape;
  EXPECT_EQ(diff.type, ShapeSpec::Type::Difference);
  EXPECT_EQ(diff.line, 9);
  ASSERT_EQ(diff.children.size(), 3u);

  const ShapeSpec& uni = diff.children[0];
  EXPECT_EQ(uni.type, ShapeSpec::Type::Union);
  EXPECT_EQ(uni.line, 10);
  ASSERT_EQ(uni.children.size(), 2u);
  EXPECT_EQ(uni.children[0].type, ShapeSpec::Type::Box);
  EXPECT_EQ(uni.children[0].box.max, Eigen::Vector3d(1.0, 0.5, 0.0));
  EXPECT_EQ(uni.children[0].line, 11);
  EXPECT_EQ(uni.children[1].type, ShapeSpec::Type::Sphere);
  EXPECT_DOUBLE_EQ(uni.children[1].radius, 0.25);
  EXPECT_EQ(uni.children[1].line, 12);

  EXPECT_EQ(diff.children[1].type, ShapeSpec::Type::Cylinder);
  EXPECT_EQ(diff.children[1].p1, Eigen::Vector3d(0.5, 0.5, 0.0));
  EXPECT_EQ(diff.children[1].line, 13);
  EXPECT_EQ(diff.children[2].type, ShapeSpec::Type::Polygon);
  EXPECT_EQ(diff.children[2].points.size(), 3u);
  EXPECT_EQ(diff.children[2].line, 16);
}

TEST(CaseFileShapes, ParsesNestedCsgIn3d) {
  const std::string text = std::string(kHead3d) + R"(  - name: block
    kind: boundary
    shape: {union: [{mesh: {file: a.stl, scale: 2}}, {difference: [{box: {min: [0, 0, 0], max: [1, 1, 1]}}, {cylinder: {p1: [0.5, 0.5, 0], p2: [0.5, 0.5, 1], radius: 0.1}}]}]}
)" + kWater3d;
  const CaseSpec spec = parse_case_text(text, kLabel);
  const ShapeSpec& uni = spec.bodies[0].shape;
  ASSERT_EQ(uni.type, ShapeSpec::Type::Union);
  ASSERT_EQ(uni.children.size(), 2u);
  EXPECT_EQ(uni.children[0].type, ShapeSpec::Type::Mesh);
  EXPECT_EQ(uni.children[0].placement.scale, Eigen::Vector3d::Constant(2.0));
  const ShapeSpec& diff = uni.children[1];
  ASSERT_EQ(diff.type, ShapeSpec::Type::Difference);
  ASSERT_EQ(diff.children.size(), 2u);
  EXPECT_EQ(diff.children[1].type, ShapeSpec::Type::Cylinder);
  EXPECT_EQ(diff.children[1].p2, Eigen::Vector3d(0.5, 0.5, 1.0));
  for (const ShapeSpec* s : {&uni, &uni.children[0], &diff, &diff.children[0], &diff.children[1]}) {
    EXPECT_EQ(s->line, 7);
  }
}

TEST(CaseFileShapes, ParsesFillInsideATank) {
  const std::string text = std::string(kHead3d) + R"(  - name: water
    kind: fluid
    fill: {below: 0.3, inside: tank}
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0, 0], max: [4, 0.3, 0.5]}}, open: [zmax]}
)";
  const CaseSpec spec = parse_case_text(text, kLabel);
  ASSERT_EQ(spec.bodies.size(), 2u);
  const BodySpec& water = spec.bodies[0];
  EXPECT_EQ(water.kind, BodySpec::Kind::Fluid);
  ASSERT_TRUE(water.fill_below.has_value());
  EXPECT_DOUBLE_EQ(*water.fill_below, 0.3);
  EXPECT_EQ(water.fill_inside, "tank");
  EXPECT_EQ(water.fill_container, 1);  // resolved at parse time, though the tank comes later
  EXPECT_EQ(water.line, 5);
  EXPECT_FALSE(spec.bodies[1].fill_below.has_value());
  EXPECT_EQ(spec.bodies[1].fill_container, -1);
}

TEST(CaseFileShapeErrors, UnknownOrAmbiguousShape) {
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + "  - {name: w, kind: fluid, shape: {cube: {size: 1}}}\n", 5,
      {"unknown shape 'bodies[0].shape.cube'", "known shapes: box, cylinder, sphere"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      union:
        - {box: {min: [0, 0], max: [1, 1]}}
        - {circle: {center: [0, 0], radius: 1}}
)",
                              10, {"unknown shape 'bodies[0].shape.union[1].circle'"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      box: {min: [0, 0], max: [1, 1]}
      sphere: {center: [0, 0], radius: 1}
)",
                              8,
                              {"bodies[0].shape", "exactly one shape key", "a map with 2 keys"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + "  - {name: w, kind: fluid, shape: {}}\n", 5,
                              {"bodies[0].shape", "exactly one shape key"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + "  - {name: w, kind: fluid, shape: box}\n", 5,
                              {"bodies[0].shape", "exactly one shape key", "'box'"}));
}

TEST(CaseFileShapeErrors, PolygonOnlyIn2d) {
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead3d) + R"(  - name: w
    kind: fluid
    shape:
      polygon: {points: [[0, 0, 0], [1, 0, 0], [1, 1, 0]]}
)",
                              8, {"bodies[0].shape.polygon", "only in 2D", "mesh"}));
}

TEST(CaseFileShapeErrors, PolygonNeedsThreePoints) {
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points: [[0, 0], [1, 0]]
)",
      9, {"bodies[0].shape.polygon.points", "at least 3 points", "a list of 2 items"}));
  EXPECT_TRUE(
      ThrowsCaseError(std::string(kHead2d) + "  - {name: w, kind: fluid, shape: {polygon: {}}}\n",
                      5, {"missing required key 'bodies[0].shape.polygon.points'"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points:
          - [0, 0]
          - [1, 0, 0]
          - [1, 1]
)",
                              11, {"bodies[0].shape.polygon.points[1]", "a list of 2 numbers"}));
}

TEST(CaseFileShapeErrors, PolygonMustEncloseAnArea) {
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points: [[0, 0], [1, 1], [2, 2], [3, 3]]
)",
                              9, {"bodies[0].shape.polygon.points", "no area", "one line"}));
}

TEST(CaseFileShapeErrors, PolygonMustBeSimple) {
  // A bow tie: edges 0-1 and 2-3 cross.
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points: [[0, 0], [1, 1], [1, 0], [0, 1.5]]
)",
                              9,
                              {"bodies[0].shape.polygon.points",
                               "the edge from point 0 to point 1 meets the edge from point 2 to "
                               "point 3",
                               "simple polygon"}));
  // A spike folding back along an edge.
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points: [[0, 0], [2, 0], [1, 0], [1, 1]]
)",
                              9, {"bodies[0].shape.polygon.points", "simple polygon"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points:
          - [0, 0]
          - [1, 0]
          - [1, 0]
          - [0, 1]
)",
                              12, {"bodies[0].shape.polygon.points[2]", "repeats the previous"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      polygon:
        points:
          - [0, 0]
          - [1, 0]
          - [0, 1]
          - [0, 0]
)",
      13, {"bodies[0].shape.polygon.points[3]", "repeats the first", "closes itself"}));
}

TEST(CaseFileShapeErrors, RadiusMustBePositive) {
  EXPECT_TRUE(
      ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      sphere:
        center: [0, 0]
        radius: -0.1
)",
                      10, {"bodies[0].shape.sphere.radius", "expected a number > 0", "'-0.1'"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) +
          "  - {name: w, kind: fluid, shape: {cylinder: {center: [0, 0], radius: 0}}}\n",
      5, {"bodies[0].shape.cylinder.radius", "expected a number > 0"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead3d) +
          "  - {name: w, kind: fluid, shape: {cylinder: {p1: [0, 0, 0], p2: [0, 0, 1]}}}\n",
      5, {"missing required key 'bodies[0].shape.cylinder.radius'"}));
}

TEST(CaseFileShapeErrors, CylinderAxisAndDimension) {
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead3d) + R"(  - name: w
    kind: fluid
    shape:
      cylinder:
        p1: [1, 0.5, 0]
        p2: [1, 0.5, 0.0]
        radius: 0.1
)",
                              10, {"bodies[0].shape.cylinder.p2", "p1 and p2 are the same point"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      cylinder:
        p1: [0, 0]
        p2: [0, 1]
        radius: 0.1
)",
      9,
      {"bodies[0].shape.cylinder.p1", "in a 2D case a cylinder is a disc", "center and radius"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead3d) +
          "  - {name: w, kind: fluid, shape: {cylinder: {center: [0, 0, 0], radius: 1}}}\n",
      5, {"bodies[0].shape.cylinder.center", "p1 and p2", "2D discs"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) +
          "  - {name: w, kind: fluid, shape: {cylinder: {center: [0, 0], radius: 1, height: 2}}}\n",
      5,
      {"unknown key 'bodies[0].shape.cylinder.height'",
       "allowed keys in bodies[0].shape.cylinder in a 2D case: center, radius"}));
}

TEST(CaseFileShapeErrors, MeshFile) {
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead3d) + R"(  - name: beach
    kind: boundary
    shape:
      mesh: {scale: 0.001}
)" + kWater3d,
                              8, {"missing required key 'bodies[0].shape.mesh.file'"}));
  EXPECT_TRUE(
      ThrowsCaseError(std::string(kHead3d) + R"(  - name: beach
    kind: boundary
    shape:
      stl:
        file: beach.step
)" + kWater3d,
                      9, {"bodies[0].shape.stl.file", ".stl, .obj, .off or .ply", "'beach.step'"}));
  for (const char* bad : {"stl", ".stl", "beach.stl.bak", "beach_stl"}) {
    EXPECT_TRUE(ThrowsCaseError(std::string(kHead3d) +
                                    "  - {name: b, kind: boundary, shape: {mesh: {file: '" + bad +
                                    "'}}}\n" + kWater3d,
                                5, {"bodies[0].shape.mesh.file", ".stl, .obj, .off or .ply"}))
        << bad;
  }
}

TEST(CaseFileShapeErrors, MeshPlacement) {
  const std::string head = std::string(kHead3d) +
                           "  - name: b\n    kind: boundary\n    shape:\n"
                           "      mesh:\n        file: b.stl\n";
  EXPECT_TRUE(ThrowsCaseError(head + "        scale: 0\n" + kWater3d, 10,
                              {"bodies[0].shape.mesh.scale", "a number > 0 or a list of 3"}));
  EXPECT_TRUE(ThrowsCaseError(head + "        scale: [1, -1, 1]\n" + kWater3d, 10,
                              {"bodies[0].shape.mesh.scale", "a number > 0 or a list of 3"}));
  EXPECT_TRUE(ThrowsCaseError(head + "        scale: [1, 1]\n" + kWater3d, 10,
                              {"bodies[0].shape.mesh.scale", "[1, 1]"}));
  EXPECT_TRUE(ThrowsCaseError(head + "        translate: [1, 1]\n" + kWater3d, 10,
                              {"bodies[0].shape.mesh.translate", "a list of 3 numbers"}));
  EXPECT_TRUE(ThrowsCaseError(head + "        repair: maybe\n" + kWater3d, 10,
                              {"bodies[0].shape.mesh.repair", "true or false"}));
  EXPECT_TRUE(ThrowsCaseError(head + "        rotation: [0, 0, 90]\n" + kWater3d, 10,
                              {"unknown key 'bodies[0].shape.mesh.rotation'", "rotate"}));
  // Meshes are 3D: rotate takes 3 angles in a 2D case too.
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) +
                                  "  - {name: b, kind: boundary, shape: {mesh: {file: b.stl, "
                                  "rotate: [0, 90], slice_y: 0}}}\n" +
                                  kWater2d,
                              5, {"bodies[0].shape.mesh.rotate", "a list of 3 numbers"}));
}

TEST(CaseFileShapeErrors, MeshSliceDependsOnDimension) {
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + R"(  - name: beach
    kind: boundary
    shape:
      mesh:
        file: beach.stl
        scale: 1
)" + kWater2d,
      9, {"missing required key 'bodies[0].shape.mesh.slice_y'", "2D case cuts the placed mesh"}));
  EXPECT_TRUE(
      ThrowsCaseError(std::string(kHead3d) + R"(  - name: beach
    kind: boundary
    shape:
      mesh:
        file: beach.stl
        slice_y: 0.15
)" + kWater3d,
                      10, {"bodies[0].shape.mesh.slice_y", "only 2D cases", "leave slice_y out"}));
}

TEST(CaseFileShapeErrors, CsgNeedsTwoShapes) {
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      union:
        - {box: {min: [0, 0], max: [1, 1]}}
)",
                              9, {"bodies[0].shape.union", "a list of at least 2 shapes"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + "  - {name: w, kind: fluid, shape: {difference: {box: {}}}}\n", 5,
      {"bodies[0].shape.difference", "at least 2 shapes (the first minus all the others)"}));
  // Errors deep inside CSG name the full path.
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: w
    kind: fluid
    shape:
      difference:
        - {box: {min: [0, 0], max: [1, 1]}}
        - union:
            - {box: {min: [0, 0], max: [1, 1]}}
            - {sphere: {center: [0, 0], radius: -1}}
)",
                              12, {"bodies[0].shape.difference[1].union[1].sphere.radius", "> 0"}));
}

TEST(CaseFileFillErrors, ShapeAndFillAreExclusive) {
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) +
          R"(  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}
  - name: water
    kind: fluid
    shape: {box: {min: [0, 0], max: [1, 0.5]}}
    fill: {below: 0.5, inside: tank}
)",
      9, {"bodies[1].fill", "gives both 'shape' and 'fill'", "exactly one"}));
  EXPECT_TRUE(ThrowsCaseError(std::string(kHead2d) + R"(  - name: tank
    kind: boundary
    shape: {box: {min: [0, 0], max: [1, 1]}}
    fill: {below: 0.5, inside: tank}
)" + kWater2d,
                              8, {"bodies[0].fill", "only fluid bodies take 'fill'", "'tank'"}));
}

TEST(CaseFileFillErrors, FillKeys) {
  const std::string tank =
      "  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}\n";
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + tank + "  - {name: water, kind: fluid, fill: {inside: tank}}\n", 6,
      {"missing required key 'bodies[1].fill.below'"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + tank + "  - {name: water, kind: fluid, fill: {below: 0.5}}\n", 6,
      {"missing required key 'bodies[1].fill.inside'"}));
  EXPECT_TRUE(
      ThrowsCaseError(std::string(kHead2d) + tank +
                          "  - {name: water, kind: fluid, fill: {below: half, inside: tank}}\n",
                      6, {"bodies[1].fill.below", "expected a number", "'half'"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + tank +
          "  - {name: water, kind: fluid, fill: {below: 0.5, inside: tank, above: 0.1}}\n",
      6, {"unknown key 'bodies[1].fill.above'", "below, inside"}));
  EXPECT_TRUE(
      ThrowsCaseError(std::string(kHead2d) + tank + "  - {name: water, kind: fluid, fill: tank}\n",
                      6, {"bodies[1].fill", "a map such as {below: 0.3, inside: tank}"}));
}

TEST(CaseFileFillErrors, FillNeedsATank) {
  const std::string bodies =
      std::string(kHead2d) +
      R"(  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}
  - {name: block, kind: boundary, walls: outside, shape: {sphere: {center: [0.5, 0.5], radius: 0.1}}}
  - {name: other, kind: fluid, shape: {box: {min: [0, 0], max: [0.1, 0.1]}}}
  - name: water
    kind: fluid
    fill:
      below: 0.5
)";
  EXPECT_TRUE(ThrowsCaseError(
      bodies + "      inside: tnk\n", 12,
      {"bodies[3].fill.inside", "fluid body 'water'", "there is no body named 'tnk'",
       "boundary bodies with walls: inside: tank"}));
  EXPECT_TRUE(ThrowsCaseError(bodies + "      inside: other\n", 12,
                              {"bodies[3].fill.inside", "body 'other' (line 7) has kind fluid",
                               "boundary bodies with walls: inside: tank"}));
  EXPECT_TRUE(ThrowsCaseError(bodies + "      inside: water\n", 12,
                              {"bodies[3].fill.inside", "body 'water' (line 8) has kind fluid"}));
  EXPECT_TRUE(ThrowsCaseError(bodies + "      inside: block\n", 12,
                              {"bodies[3].fill.inside", "body 'block' (line 6) has walls: outside",
                               "boundary bodies with walls: inside: tank"}));
  EXPECT_TRUE(ThrowsCaseError(
      std::string(kHead2d) + "  - {name: water, kind: fluid, fill: {below: 1, inside: w}}\n", 5,
      {"bodies[0].fill.inside", "the case has no boundary body with walls: inside"}));
}

// The shipped cases parse; the wave flumes' meshes exist next to them (paths are relative to
// the case file's folder).
TEST(CaseFileShapes, ShippedCasesParse) {
#ifdef SWELL_SOURCE_DIR
  const std::filesystem::path cases = std::filesystem::path(SWELL_SOURCE_DIR) / "cases";
#else
  const std::filesystem::path cases = "cases";
#endif
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(cases)) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(load_case_file(entry.path().string())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 4);

  for (const int dim : {2, 3}) {
    const std::filesystem::path file = cases / ("wave_flume" + std::to_string(dim) + "d.yaml");
    const CaseSpec spec = load_case_file(file.string());
    EXPECT_EQ(spec.dim, dim);
    ASSERT_EQ(spec.bodies.size(), 4u);
    EXPECT_EQ(spec.bodies[0].shape.type, ShapeSpec::Type::Box);
    for (const int i : {1, 2}) {
      const BodySpec& body = spec.bodies[static_cast<std::size_t>(i)];
      EXPECT_EQ(body.shape.type, ShapeSpec::Type::Mesh) << body.name;
      EXPECT_EQ(body.walls, BodySpec::Walls::Outside) << body.name;
      EXPECT_EQ(body.layers, 2) << body.name;
      EXPECT_EQ(body.shape.slice_y.has_value(), dim == 2) << body.name;
      EXPECT_TRUE(std::filesystem::is_regular_file(file.parent_path() / body.shape.file))
          << body.shape.file;
    }
    EXPECT_EQ(spec.bodies[2].shape.placement.scale, Eigen::Vector3d::Constant(0.001));
    const BodySpec& water = spec.bodies[3];
    EXPECT_EQ(water.kind, BodySpec::Kind::Fluid);
    ASSERT_TRUE(water.fill_below.has_value());
    EXPECT_DOUBLE_EQ(*water.fill_below, 0.3);
    EXPECT_EQ(water.fill_inside, "tank");
    EXPECT_EQ(spec.gauges.size(), 3u);
  }
}

// ---------------------------------------------------------------------------------------------
// Gauges

// A valid 2D case up to `gauges:`, with a boundary body `tank` and a fluid body `water`; the first
// gauge appended to it is on line 8.
const char* const kGaugeHead = R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0], max: [1, 1]}}}
  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [0.5, 0.5]}}}
gauges:
)";

std::string with_gauges(const std::string& gauges) {
  return kGaugeHead + gauges;
}

TEST(CaseFileGauges, ParsesAllKindsIn2d) {
  const std::string text = with_gauges(
      R"(  - {name: P1, kind: pressure, at: [0.28575, 0.003], normal: [-3, 4], offset: 0.002}
  - {name: P2, kind: pressure, at: [0.1, 0.2]}
  - {name: H1, kind: height, at: [0.1, 0.0], every: 0.002}
  - {name: V1, kind: velocity, at: [0.1, 0.05]}
  - {name: F_wall, kind: force, body: tank, moment_about: [0, 0.5]}
  - {name: F2, kind: force, body: tank}
  - name: front
    kind: front
    band: 0.03
  - {name: front-2, kind: front}
output: {every: 0.01, vtk: true, vtk_split: false, hdf5: true, checkpoint_every: 0.05, gauge_every: 0.001}
)");
  const CaseSpec spec = parse_case_text(text, kLabel);
  EXPECT_DOUBLE_EQ(spec.output_every, 0.01);
  EXPECT_TRUE(spec.vtk);
  EXPECT_FALSE(spec.vtk_split);
  EXPECT_TRUE(spec.hdf5);
  EXPECT_DOUBLE_EQ(spec.checkpoint_every, 0.05);
  EXPECT_DOUBLE_EQ(spec.gauge_every, 0.001);
  ASSERT_EQ(spec.gauges.size(), 8u);

  const GaugeSpec& p1 = spec.gauges[0];
  EXPECT_EQ(p1.name, "P1");
  EXPECT_EQ(p1.kind, GaugeSpec::Kind::Pressure);
  EXPECT_EQ(p1.at, Eigen::Vector3d(0.28575, 0.003, 0.0));
  ASSERT_TRUE(p1.normal.has_value());  // stored normalised
  EXPECT_NEAR((*p1.normal - Eigen::Vector3d(-0.6, 0.8, 0.0)).norm(), 0.0, 1e-15);
  ASSERT_TRUE(p1.offset.has_value());
  EXPECT_DOUBLE_EQ(*p1.offset, 0.002);
  EXPECT_DOUBLE_EQ(p1.every, 0.0);
  EXPECT_EQ(p1.line, 8);

  const GaugeSpec& p2 = spec.gauges[1];
  EXPECT_EQ(p2.name, "P2");
  EXPECT_EQ(p2.at, Eigen::Vector3d(0.1, 0.2, 0.0));
  EXPECT_FALSE(p2.normal.has_value());
  EXPECT_FALSE(p2.offset.has_value());
  EXPECT_EQ(p2.line, 9);

  const GaugeSpec& h1 = spec.gauges[2];
  EXPECT_EQ(h1.name, "H1");
  EXPECT_EQ(h1.kind, GaugeSpec::Kind::Height);
  EXPECT_EQ(h1.at, Eigen::Vector3d(0.1, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(h1.every, 0.002);
  EXPECT_EQ(h1.line, 10);

  const GaugeSpec& v1 = spec.gauges[3];
  EXPECT_EQ(v1.kind, GaugeSpec::Kind::Velocity);
  EXPECT_EQ(v1.at, Eigen::Vector3d(0.1, 0.05, 0.0));
  EXPECT_DOUBLE_EQ(v1.every, 0.0);
  EXPECT_EQ(v1.line, 11);

  const GaugeSpec& f1 = spec.gauges[4];
  EXPECT_EQ(f1.name, "F_wall");
  EXPECT_EQ(f1.kind, GaugeSpec::Kind::Force);
  EXPECT_EQ(f1.body, "tank");
  ASSERT_TRUE(f1.moment_about.has_value());
  EXPECT_EQ(*f1.moment_about, Eigen::Vector3d(0.0, 0.5, 0.0));
  EXPECT_EQ(f1.line, 12);
  const GaugeSpec& f2 = spec.gauges[5];
  EXPECT_EQ(f2.body, "tank");
  EXPECT_FALSE(f2.moment_about.has_value());

  const GaugeSpec& front = spec.gauges[6];
  EXPECT_EQ(front.name, "front");
  EXPECT_EQ(front.kind, GaugeSpec::Kind::Front);
  ASSERT_TRUE(front.band.has_value());
  EXPECT_DOUBLE_EQ(*front.band, 0.03);
  EXPECT_EQ(front.line, 14);
  const GaugeSpec& front2 = spec.gauges[7];
  EXPECT_EQ(front2.name, "front-2");
  EXPECT_FALSE(front2.band.has_value());
  EXPECT_EQ(front2.line, 17);

  // Keys a kind does not take keep their defaults.
  for (const GaugeSpec& g : spec.gauges) {
    if (g.kind != GaugeSpec::Kind::Force) {
      EXPECT_TRUE(g.body.empty()) << g.name;
      EXPECT_FALSE(g.moment_about.has_value()) << g.name;
    }
    if (g.kind != GaugeSpec::Kind::Front) {
      EXPECT_FALSE(g.band.has_value()) << g.name;
    }
    if (g.kind == GaugeSpec::Kind::Force || g.kind == GaugeSpec::Kind::Front) {
      EXPECT_EQ(g.at, Eigen::Vector3d::Zero()) << g.name;
    }
  }
}

TEST(CaseFileGauges, ParsesGaugesIn3d) {
  const std::string text = R"(dim: 3
dp: 0.02
time: {end: 1}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0, 0], max: [1, 1, 1]}}}
  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [0.5, 1, 0.5]}}}
gauges:
  - {name: P1, kind: pressure, at: [1, 0.5, 0.1], normal: [0, 0, 2], offset: 0}
  - {name: H1, kind: height, at: [0.3, 0.5, 0]}
  - {name: F1, kind: force, body: tank, moment_about: [1, 0.5, 0]}
)";
  const CaseSpec spec = parse_case_text(text, kLabel);
  ASSERT_EQ(spec.gauges.size(), 3u);
  EXPECT_EQ(spec.gauges[0].at, Eigen::Vector3d(1.0, 0.5, 0.1));
  EXPECT_EQ(*spec.gauges[0].normal, Eigen::Vector3d(0.0, 0.0, 1.0));
  EXPECT_DOUBLE_EQ(*spec.gauges[0].offset, 0.0);
  EXPECT_EQ(spec.gauges[1].at, Eigen::Vector3d(0.3, 0.5, 0.0));
  EXPECT_EQ(*spec.gauges[2].moment_about, Eigen::Vector3d(1.0, 0.5, 0.0));
}

TEST(CaseFileGauges, EmptyListMeansNoGauges) {
  EXPECT_TRUE(parse_case_text(with_gauges("  []\n"), kLabel).gauges.empty());
}

TEST(CaseFileGaugeErrors, NotAListOrNotAMap) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  P1: {kind: pressure}\n"), 8,
                              {"gauges: expected a list of gauges"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - P1\n"), 8, {"gauges[0]: expected a map", "'P1'"}));
}

TEST(CaseFileGaugeErrors, MissingName) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {kind: pressure, at: [0.1, 0.1]}\n"), 8,
                              {"missing required key 'gauges[0].name'"}));
}

TEST(CaseFileGaugeErrors, InvalidName) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: 'P 1', kind: pressure, at: [0.1, 0.1]}\n"), 8,
                              {"gauges[0].name", "letters, digits, '_' and '-'", "'P 1'"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: p/1, kind: velocity, at: [0.1, 0.1]}\n"), 8,
                              {"gauges[0].name", "letters, digits"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: '', kind: front}\n"), 8,
                              {"gauges[0].name", "non-empty"}));
}

TEST(CaseFileGaugeErrors, DuplicateName) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges(R"(  - {name: P1, kind: pressure, at: [0.1, 0.1]}
  - {name: V1, kind: velocity, at: [0.1, 0.1]}
  - name: P1
    kind: height
    at: [0.2, 0]
)"),
                              10, {"gauges[2].name", "duplicate gauge name 'P1'", "line 8"}));
}

TEST(CaseFileGauges, HeightLevelDefinition) {
  const CaseSpec spec =
      parse_case_text(with_gauges("  - {name: H1, kind: height, at: [0.1, 0]}\n"
                                  "  - {name: H2, kind: height, at: [0.1, 0], level: integral}\n"
                                  "  - {name: H3, kind: height, at: [0.1, 0], level: surface}\n"),
                      kLabel);
  EXPECT_EQ(spec.gauges[0].level, GaugeSpec::Level::Surface);
  EXPECT_EQ(spec.gauges[1].level, GaugeSpec::Level::Integral);
  EXPECT_EQ(spec.gauges[2].level, GaugeSpec::Level::Surface);
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges("  - {name: H1, kind: height, at: [0.1, 0], level: mid}\n"), 8,
                      {"gauges[0].level", "surface (the first free surface"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: P1, kind: pressure, at: [0.1, 0.1], level: integral}\n"), 8,
      {"level"}));
}

TEST(CaseFileGauges, RunupLineSwlAndSampling) {
  const CaseSpec spec = parse_case_text(
      with_gauges("  - {name: R, kind: runup, from: [0.2, 0], to: [0.8, 0.3], swl: 0.1, "
                  "sampling: max, edge: connected}\n"
                  "  - {name: R2, kind: runup, from: [0.2, 0], to: [0.8, 0.3]}\n"),
      kLabel);
  ASSERT_EQ(spec.gauges.size(), 2u);
  const GaugeSpec& r = spec.gauges[0];
  EXPECT_EQ(r.kind, GaugeSpec::Kind::Runup);
  EXPECT_EQ(r.from, Eigen::Vector3d(0.2, 0.0, 0.0));
  EXPECT_EQ(r.to, Eigen::Vector3d(0.8, 0.3, 0.0));
  ASSERT_TRUE(r.swl.has_value());
  EXPECT_DOUBLE_EQ(*r.swl, 0.1);
  EXPECT_TRUE(r.max);
  EXPECT_FALSE(spec.gauges[1].swl.has_value());
  EXPECT_FALSE(spec.gauges[1].max);
  EXPECT_TRUE(r.connected);
  EXPECT_FALSE(spec.gauges[1].connected);  // default: edge: highest
  EXPECT_EQ(std::string(gauge_kind_name(r.kind)), "runup");
}

TEST(CaseFileGaugeErrors, RunupBadKeys) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: R, kind: runup, from: [0.2, 0]}\n"), 8,
                              {"missing required key 'gauges[0].to'"}));
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges("  - {name: R, kind: runup, from: [0.8, 0.3], to: [0.2, 0]}\n"),
                      8, {"gauges[0].to", "a point higher than 'from'"}));
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges("  - {name: R, kind: runup, from: [0.2, 0], to: [0.2, 0.3]}\n"),
                      8, {"gauges[0].to", "not straight above it"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: R, kind: runup, from: [0.2, 0], to: [0.8, 0.3], sampling: mean}\n"),
      8, {"gauges[0].sampling", "instant (the runup at each row's time) or max", "'mean'"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: R, kind: runup, from: [0.2, 0], to: [0.8, 0.3], edge: top}\n"), 8,
      {"gauges[0].edge", "highest", "connected", "'top'"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: H, kind: height, at: [0.1, 0], edge: "
                                          "connected}\n"),
                              8, {"gauges[0].edge", "runup"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: R, kind: runup, from: [0.2, 0], to: [0.8, 0.3], at: [0, 0]}\n"), 8,
      {"gauges[0].at", "runup gauges take no 'at'"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: R, kind: runup, from: [0.2, 0], to: [0.8, 0.3], swl: high}\n"), 8,
      {"gauges[0].swl", "'high'"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: H, kind: height, at: [0.1, 0], swl: 0.1}\n"),
                              8, {"gauges[0].swl", "height gauges take no 'swl'", "runup"}));
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges("  - {name: H, kind: height, at: [0.1, 0], sampling: max}\n"), 8,
                      {"gauges[0].sampling", "instant (the level at each row's time) or mean"}));
}

TEST(CaseFileGaugeErrors, MissingOrUnknownKind) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: P1, at: [0.1, 0.1]}\n"), 8,
                              {"missing required key 'gauges[0].kind'"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: P1, kind: pressure, at: [0.1, 0.1]}\n"
                  "  - name: P2\n    kind: presure\n    at: [0, 0]\n"),
      10, {"gauges[1].kind", "'presure'", "pressure, height, velocity, force, front"}));
}

TEST(CaseFileGaugeErrors, MissingAt) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: P1, kind: pressure, normal: [0, 1]}\n"), 8,
                              {"missing required key 'gauges[0].at'"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: H1, kind: height}\n"), 8,
                              {"missing required key 'gauges[0].at'"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: V1, kind: velocity}\n"), 8,
                              {"missing required key 'gauges[0].at'"}));
}

TEST(CaseFileGaugeErrors, WrongVectorLength) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: P1, kind: pressure, at: [0.1, 0.2, 0.3]}\n"),
                              8,
                              {"gauges[0].at", "expected a list of 2 numbers", "[0.1, 0.2, 0.3]"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges(R"(  - name: P1
    kind: pressure
    at: [0.1, 0.2]
    normal: [1]
)"),
                              11, {"gauges[0].normal", "expected a list of 2 numbers"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 3
dp: 0.02
time: {end: 1}
bodies:
  - {name: tank, kind: boundary, shape: {box: {min: [0, 0, 0], max: [1, 1, 1]}}}
  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [0.5, 1, 0.5]}}}
gauges:
  - {name: F1, kind: force, body: tank, moment_about: [0, 0]}
)",
                              8, {"gauges[0].moment_about", "expected a list of 3 numbers"}));
}

TEST(CaseFileGaugeErrors, OffsetNeedsNormal) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges(R"(  - name: P1
    kind: pressure
    at: [0.1, 0.2]
    offset: 0.01
)"),
                              11, {"gauges[0].offset", "only allowed together with 'normal'"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: P1, kind: pressure, at: [0, 0.2], normal: [1, 0], offset: -0.01}\n"),
      8, {"gauges[0].offset", "expected a number >= 0"}));
}

TEST(CaseFileGaugeErrors, ZeroNormal) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges(R"(  - name: P1
    kind: pressure
    at: [0.1, 0.2]
    normal: [0, 0.0]
)"),
                              11, {"gauges[0].normal", "expected a non-zero vector", "[0, 0.0]"}));
}

TEST(CaseFileGaugeErrors, ForceGaugeNeedsABoundaryBody) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: V1, kind: velocity, at: [0, 0]}\n"
                                          "  - {name: F1, kind: force, body: tnk}\n"),
                              9,
                              {"gauges[1].body", "force gauge 'F1' (line 9)", "no body named 'tnk'",
                               "boundary bodies: tank"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges(R"(  - name: F1
    kind: force
    body: water
)"),
                              10,
                              {"gauges[0].body", "force gauge 'F1' (line 8)",
                               "body 'water' (line 6)", "kind fluid", "boundary bodies: tank"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: F1, kind: force}\n"), 8,
                              {"missing required key 'gauges[0].body'"}));
  EXPECT_TRUE(ThrowsCaseError(R"(dim: 2
dp: 0.01
time: {end: 1}
bodies:
  - {name: water, kind: fluid, shape: {box: {min: [0, 0], max: [1, 1]}}}
gauges:
  - {name: F1, kind: force, body: water}
)",
                              7,
                              {"gauges[0].body", "kind fluid", "the case has no boundary bodies"}));
}

TEST(CaseFileGaugeErrors, KeyOfAnotherKind) {
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges(R"(  - name: P1
    kind: pressure
    at: [0.1, 0.2]
    body: tank
)"),
                      11,
                      {"gauges[0].body", "pressure gauges take no 'body'", "kind force",
                       "allowed keys in gauges[0] for kind pressure: name, kind, every, at, "
                       "normal, offset"}));
  EXPECT_TRUE(ThrowsCaseError(
      with_gauges("  - {name: F1, kind: force, body: tank, at: [0, 0]}\n"), 8,
      {"gauges[0].at", "force gauges take no 'at'", "kinds pressure, height, velocity"}));
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges("  - {name: V1, kind: velocity, at: [0, 0], normal: [1, 0]}\n"),
                      8, {"gauges[0].normal", "velocity gauges take no 'normal'"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: H1, kind: height, at: [0, 0], band: 0.1}\n"),
                              8, {"gauges[0].band", "height gauges take no 'band'", "kind front"}));
  EXPECT_TRUE(
      ThrowsCaseError(with_gauges("  - {name: H1, kind: height, at: [0, 0], colour: red}\n"), 8,
                      {"unknown key 'gauges[0].colour'",
                       "allowed keys in gauges[0] for kind height: name, kind, every, at"}));
}

TEST(CaseFileGaugeErrors, InvalidIntervalsAndBand) {
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: V1, kind: velocity, at: [0, 0], every: 0}\n"),
                              8, {"gauges[0].every", "expected a number > 0"}));
  EXPECT_TRUE(ThrowsCaseError(with_gauges("  - {name: fr, kind: front, band: -0.1}\n"), 8,
                              {"gauges[0].band", "expected a number > 0"}));
}

// ---------------------------------------------------------------------------------------------
// Damping zones and settling (bc/damping.hpp; more in tests/test_damping.cpp)

TEST(CaseFileDamping, ParsesZonesAndSettlingIn3d) {
  const CaseSpec spec = parse_case_text(R"(dim: 3
dp: 0.02
time: {end: 2, settling: {duration: 0.5, rate: 4}}
bodies:
  - {name: water, kind: fluid, shape: {box: {min: [0, 0, 0], max: [1, 1, 1]}}}
damping:
  - name: outlet
    plane: {at: [0.5, 0, 0], direction: [1, 0, 0]}
    length: 0.5
    components: [x, z]
  - {name: side, box: {min: [0, 0, 0], max: [1, 0.2, 1]}, direction: [0, -1, 0], ramp: cosine}
)",
                                        kLabel);
  ASSERT_TRUE(spec.settling);
  EXPECT_EQ(spec.settling->duration, 0.5);
  EXPECT_EQ(spec.settling->rate, 4.0);
  ASSERT_EQ(spec.damping.size(), 2u);
  EXPECT_EQ(spec.damping[0].line, 7);
  EXPECT_EQ(spec.damping[0].zone.at, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(spec.damping[0].zone.components, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(spec.damping[1].line, 11);
  EXPECT_EQ(spec.damping[1].zone.box_max, Eigen::Vector3d(1, 0.2, 1));
  EXPECT_EQ(spec.damping[1].zone.ramp, DampingRamp::Cosine);
}

TEST(CaseFileDampingErrors, LineKeyAndExpectation) {
  const std::string head = std::string(kMinimal2d) + "damping:\n";  // zones start on line 7
  EXPECT_TRUE(
      ThrowsCaseError(head + "  - {name: a, plane: {at: [1, 0], direction: [0, 0]}, length: 1}\n",
                      7, {"damping[0].plane.direction: expected a non-zero vector", "got [0, 0]"}));
  EXPECT_TRUE(ThrowsCaseError(head + "  - name: a\n    plane: {at: [1, 0], direction: [1, 0]}\n"
                                     "    length: -2\n",
                              9, {"damping[0].length: expected a number > 0", "got '-2'"}));
  EXPECT_TRUE(ThrowsCaseError(
      head + "  - {name: a, plane: {at: [1, 0], direction: [1, 0]}, length: 1, rate: 0}\n", 7,
      {"damping[0].rate: expected a number > 0"}));
  EXPECT_TRUE(ThrowsCaseError(
      head + "  - {name: a, plane: {at: [1, 0], direction: [1, 0, 0]}, length: 1}\n", 7,
      {"damping[0].plane.direction: expected a list of 2 numbers"}));
  EXPECT_TRUE(ThrowsCaseError(
      head + "  - {name: a, plane: {at: [1, 0], direction: [1, 0]}, length: 1, width: 1}\n", 7,
      {"unknown key 'damping[0].width'", "allowed keys in damping[0] for a plane zone"}));
  EXPECT_TRUE(ThrowsCaseError("dim: 2\ndp: 0.01\ntime: {end: 1, settling: {duration: -1}}\n", 3,
                              {"time.settling.duration: expected a number > 0"}));
}

}  // namespace
}  // namespace swell
