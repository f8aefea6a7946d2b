// The `swell` command line. Errors from every layer arrive here as exceptions and leave as
// one readable message and a non-zero exit code.
#include <omp.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "apps/bench_command.hpp"
#include "apps/fill_command.hpp"
#include "apps/foam_command.hpp"
#include "apps/goda_command.hpp"
#include "apps/probe_command.hpp"
#include "apps/validate_command.hpp"
#include "apps/verify_command.hpp"
#include "apps/wave_analysis_command.hpp"
#include "apps/wave_predict_command.hpp"
#include "apps/wave_target_command.hpp"
#include "apps/waves_command.hpp"
#include "case/reader.hpp"
#include "case/schema.hpp"
#include "io/hdf5_file.hpp"
#include "io/provenance.hpp"
#include "parallel/comm.hpp"
#include "run/run.hpp"
#include "run/stop_signals.hpp"
#include "solver/time/simulation.hpp"
#include "validation/validation_manifest.hpp"

namespace {

constexpr int kExitInput = 2;     // the case file or the command line is wrong
constexpr int kExitUnstable = 3;  // the run blew up
constexpr int kExitOther = 1;

// Option checks with short messages (CLI::PositiveNumber prints the whole double range).
const CLI::Validator kCount(
    [](std::string& s) -> std::string {
      char* end = nullptr;
      const long v = std::strtol(s.c_str(), &end, 10);
      if (s.empty() || *end != '\0' || v < 1)
        return "expected a whole number >= 1, got '" + s + "'";
      return {};
    },
    "N>=1");
const CLI::Validator kPositive(
    [](std::string& s) -> std::string {
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      if (s.empty() || *end != '\0' || !(v > 0.0) || !std::isfinite(v))
        return "expected a number > 0, got '" + s + "'";
      return {};
    },
    "X>0");

// `--set key.path=value`, repeatable, one edit per occurrence (case/reader.hpp).
void add_set_option(CLI::App* cmd, std::vector<std::string>& sets) {
  cmd->add_option("--set", sets,
                  "edit the case: key.path=value (YAML value; repeatable), e.g. "
                  "--set physics.boundary.model=mdbc --set bodies.2.boundary=dbc")
      ->allow_extra_args(false);
}

}  // namespace

int main(int argc, char** argv) {
  // No HDF5 clean-up at exit (it can crash after a failed write), and a file size limit
  // (ulimit -f) makes writes fail with EFBIG, reported like a full disk, instead of killing.
  swell::hdf5_no_atexit();
  std::signal(SIGXFSZ, SIG_IGN);
  // MPI for the process's lifetime when started by mpirun (else nothing). Ranks other than 0
  // print nothing: rank 0 reports for the whole run (its errors, progress and summary).
  swell::parallel::Environment mpi(argc, argv);
  const bool rank0 = swell::parallel::Comm::world().rank() == 0;
  static std::ofstream silent;  // never opened: what is written to it goes nowhere
  if (!rank0) {
    std::cout.rdbuf(silent.rdbuf());
    std::cerr.rdbuf(silent.rdbuf());
  }

  CLI::App app{"Swell: weakly-compressible SPH for coastal and hydraulic engineering"};
  app.require_subcommand(1);
  app.set_version_flag("--version", swell::version_text());

  std::string case_path, out_dir;
  int threads = 0;
  bool quiet = false;
  auto* run = app.add_subcommand("run", "run a case file to its end time");
  run->add_option("case", case_path, "case file (YAML)")->required();
  run->add_option("-o,--out", out_dir, "output folder (default: out/<case name>)");
  run->add_option("-t,--threads", threads, "OpenMP threads (default: all cores)")->check(kCount);
  run->add_flag("-q,--quiet", quiet, "no progress line");
  std::vector<std::string> run_sets;
  add_set_option(run, run_sets);
  std::string restart_dir;
  bool overwrite = false;
  auto* restart_opt = run->add_option(
      "--restart", restart_dir, "continue the run in this output folder from its last checkpoint");
  long rebalance_every = 100;
  run->add_option("--rebalance", rebalance_every,
                  "under mpirun: balance the slabs by the pair loop's estimated work every N steps "
                  "(0: never)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--overwrite", overwrite,
                "replace the run the output folder already holds (else such a folder is refused)")
      ->excludes(restart_opt);

  std::string fill_case, fill_out;
  int fill_threads = 0;
  auto* fill = app.add_subcommand(
      "fill", "build a case's particles as `run` would, write <name>_fill.vtp and report");
  fill->add_option("case", fill_case, "case file (YAML)")->required();
  std::vector<std::string> fill_sets;
  add_set_option(fill, fill_sets);
  fill->add_option("-o,--out", fill_out, "output folder (default: out/<case name>)");
  fill->add_option("-t,--threads", fill_threads, "OpenMP threads (default: all cores)")
      ->check(kCount);

  std::string probe_dir, probe_at, probe_normal, probe_kind = "pressure", probe_out, probe_to;
  double probe_offset = -1.0;
  std::optional<double> probe_swl;
  auto* probe = app.add_subcommand("probe", "evaluate a gauge on the snapshots of a finished run");
  probe->add_option("outdir", probe_dir, "output folder of a run (holding <case>.h5)")->required();
  probe
      ->add_option("--at", probe_at,
                   "point x,y[,z] (height: horizontal position and line start; runup: the "
                   "line's lower end on the slope)")
      ->required();
  probe->add_option("--kind", probe_kind, "pressure | velocity | height | runup")
      ->check(CLI::IsMember({"pressure", "velocity", "height", "runup"}));
  probe->add_option("--to", probe_to, "runup: the line's upper end on the slope x,y[,z]");
  probe->add_option("--swl", probe_swl, "runup: still-water level (the value is relative to it)");
  probe->add_option("--normal", probe_normal,
                    "pressure: wall normal nx,ny[,nz]; sample at at + offset*normal");
  probe->add_option("--offset", probe_offset, "distance along the normal (default h)");
  std::optional<double> probe_size;
  probe->add_option("--size", probe_size,
                    "pressure: a sensor face of this diameter (3D) / length (2D) [m] on the wall "
                    "at --at, needs --normal (the face average, as a case gauge's size)");
  probe->add_option("-o,--out", probe_out, "CSV file (default: standard output)");

  swell::CompareOptions cmp;
  std::string cmp_labels, cmp_window, cmp_peak_window;
  double cmp_arrival = 0.0;
  auto* compare = app.add_subcommand(
      "compare", "metrics, plots and a report of runs' gauges against a reference CSV or run");
  compare->add_option("runs", cmp.runs, "run folders holding gauges_*.csv")->required();
  compare->add_option("--reference", cmp.reference, "reference CSV table, or a run folder")
      ->required();
  compare->add_option("--labels", cmp_labels, "comma-separated labels, one per run");
  compare->add_option("--reference-label", cmp.reference_label,
                      "legend text of the reference (e.g. \"experiment (Lobovsky 2014)\")");
  compare->add_option("-o,--out", cmp.out_dir, "output folder")->required();
  compare->add_option("--map", cmp.map, "GAUGE=COLUMN: reference column of a gauge (repeatable)");
  compare->add_option("--time-scale", cmp.time_scale, "normalise run times: t * scale")
      ->check(kPositive);
  compare->add_option("--value-scale", cmp.value_scale, "normalise run values: v * scale")
      ->check(kPositive);
  compare->add_option("--window", cmp_window, "metric window t0,t1 (scaled time)");
  compare->add_option("--peak-window", cmp_peak_window, "peak window t0,t1 (default: --window)");
  auto* cmp_arrival_opt =
      compare->add_option("--arrival", cmp_arrival, "arrival threshold (scaled value)");

  swell::ValidateOptions val;
  std::string val_res, val_cells;
  auto* validate = app.add_subcommand(
      "validate", "run/compare a validation case (validation/NAME/validation.yaml) and report");
  validate->add_option("name", val.name, "validation case name, folder or manifest file")
      ->required();
  add_set_option(validate, val.sets);
  validate->add_flag("--run-sph", val.run_sph, "run the SPH case (else: committed results)");
  validate->add_flag("--run-foam", val.run_foam, "run interFoam (else: committed results)");
  validate->add_option("--resolution", val_res, "SPH dp list d1,d2 [m] (default: manifest's)");
  validate->add_option("--cell-size", val_cells, "OpenFOAM cell sizes c1,c2 [m]");
  validate->add_option("-o,--out", val.out_dir, "output folder (default: out/validate/NAME)");
  validate->add_option("-t,--threads", val.threads, "OpenMP threads for SPH runs")->check(kCount);
  validate->add_option("--np", val.np, "OpenFOAM processes")->check(kCount);
  validate->add_option("--end", val.end_time, "end time of fresh runs [s] (shortened runs)")
      ->check(kPositive);
  validate->add_flag("--save-results", val.save_results,
                     "copy fresh results into validation/NAME/results/ (to commit them)");

  std::string foam_case;
  swell::FoamOptions foam_opt;
  swell::VerifyOptions ver;
  auto* verify = app.add_subcommand(
      "verify", "the method checked piece by piece: consistency, convergence, conservation");
  verify->add_option("names", ver.names, "verifications to run (default: all; --list)");
  verify->add_option("-o,--out", ver.out_dir, "output folder (default: out/verify)");
  verify->add_flag("--full", ver.full, "the full convergence studies (longer)");
  verify->add_flag("--list", ver.list, "list the verifications and stop");
  verify->add_option("-t,--threads", ver.threads, "OpenMP threads")->check(kCount);

  auto* foam = app.add_subcommand(
      "foam", "write an OpenFOAM interFoam case of a case file; --run runs it and converts gauges");
  foam->add_option("case", foam_case, "case file (YAML)")->required();
  std::vector<std::string> foam_sets;
  add_set_option(foam, foam_sets);
  foam->add_option("-o,--out", foam_opt.out_dir, "case folder (default: out/<case name>_foam)");
  auto* foam_cell =
      foam->add_option("--cell", foam_opt.cell_size, "cell size [m]")->check(kPositive);
  foam->add_option("--cells-per-dp", foam_opt.cells_per_dp, "cell = dp / K (default 1)")
      ->check(kPositive)
      ->excludes(foam_cell);
  foam->add_option("--end", foam_opt.end_time, "end time [s] (default: the case's)")
      ->check(kPositive);
  foam->add_flag("--run", foam_opt.run, "run it (blockMesh ... interFoam) and convert the gauges");
  foam->add_option("--np", foam_opt.np, "processes (decomposePar + mpirun)")->check(kCount);

  swell::BenchOptions bench_opt;
  swell::BenchSingleOptions bench_single;
  std::string bench_threads, bench_sweep_dp;
  auto* bench = app.add_subcommand(
      "bench", "performance benchmark: B2D, B3D (DualSPHysics' cases), 1 and 2 threads, scaling");
  bench
      ->add_option("cases", bench_opt.cases,
                   "b2d, b3d, b3d_fine (default: these three); b2d_mdbc, b3d_mdbc (mDBC walls); "
                   "b2d_shift, b3d_shift (particle shifting)")
      ->check(CLI::IsMember(
          {"b2d", "b3d", "b3d_fine", "b2d_mdbc", "b3d_mdbc", "b2d_shift", "b3d_shift"}));
  bench->add_option("--threads", bench_threads, "thread counts t1,t2 (default 1,2)");
  bench->add_option("--repeats", bench_opt.repeats, "runs per point; medians are reported")
      ->check(kCount);
  bench->add_flag("--sweep", bench_opt.sweep, "B3D over dp (N ~1e4..1e6): cost per particle-step");
  bench->add_option("--sweep-dp", bench_sweep_dp, "sweep dp list d1,d2,... [m]");
  bench->add_option("--sweep-steps", bench_opt.sweep_steps, "timed steps per sweep point")
      ->check(kCount);
  bench->add_option("-o,--out", bench_opt.out_dir, "output folder (default out/bench)");
  bench->add_option("--bench-dir", bench_opt.bench_dir, "folder holding cases/b2d.yaml");
  auto* single = bench->add_option("--single", bench_single.case_file,
                                   "one measurement of this case file (used by the driver)");
  bench->add_option("--dp", bench_single.dp, "with --single: dp [m]")->needs(single);
  bench->add_option("--end", bench_single.end, "with --single: end time [s]")->needs(single);
  bench->add_option("--steps", bench_single.steps, "with --single: timed steps")->needs(single);
  bench->add_option("--warmup", bench_single.warmup, "with --single: untimed steps first")
      ->needs(single);
  bench->add_option("-t", bench_single.threads, "with --single: threads")->needs(single);

  swell::WavesOptions waves_opt;
  // `swell waves H T d`: regular-wave theory and paddle stroke (apps/waves_command); its
  // subcommand `analyse` (apps/wave_analysis_command) runs in the dispatch below.
  auto* waves = app.add_subcommand(
      "waves",
      "wave theory (swell waves H T d [--paddle flap --hinge l]), analysis (analyse), Goda's wall "
      "pressures (goda), a case's target wave (target)");
  waves->require_subcommand(0, 1);
  // `swell waves analyse | predict | goda | target`: each file registers its own.
  const std::vector<swell::Subcommand> waves_subcommands{
      swell::add_waves_analyse_command(*waves), swell::add_waves_predict_command(*waves),
      swell::add_waves_goda_command(*waves), swell::add_waves_target_command(*waves)};
  const auto chosen_waves = [&]() -> const swell::Subcommand* {
    for (const auto& c : waves_subcommands)
      if (c.chosen()) return &c;
    return nullptr;
  };
  auto* waves_h = waves->add_option("H", waves_opt.height, "wave height [m]")->check(kPositive);
  waves->add_option("T", waves_opt.period, "wave period [s]")->check(kPositive);
  waves->add_option("d", waves_opt.depth, "still-water depth [m]")->check(kPositive);
  waves->add_option("--paddle", waves_opt.paddle, "piston (default) | flap")
      ->check(CLI::IsMember({"piston", "flap"}));
  waves->add_option("--hinge", waves_opt.hinge,
                    "flap: hinge height above the bed [m] (< 0: below)");
  waves->add_option("--order", waves_opt.order, "generation order 1 | 2 (default 1)")
      ->check(CLI::IsMember({1, 2}));
  waves->add_option("--dp", waves_opt.dp, "particle spacing [m]: resolution checks")
      ->check(kPositive);
  waves->add_option("-g", waves_opt.g, "gravity [m/s^2] (default 9.81)")->check(kPositive);

  std::string help_topic, help_key;
  auto* help = app.add_subcommand(
      "help",
      "reference documentation: `swell help case` (every case-file key, Markdown) or "
      "`swell help case KEY.PATH` (one key or section)");
  help->add_option("topic", help_topic, "case")->required()->check(CLI::IsMember({"case"}));
  help->add_option("key", help_key, "a key path such as physics.coefh or gauges.band");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    if (app.get_subcommands().empty()) {
      // No command chosen: say what was wrong, then list the commands.
      const std::string first = argc > 1 ? argv[1] : "";
      if (!first.empty() && first[0] != '-')
        std::cerr << "error: unknown command '" << first << "'\n\n";
      else if (argc > 1)
        std::cerr << "error: " << e.what() << "\n\n";
      else
        std::cerr << "error: a command is required\n\n";
      std::cerr << app.help();
    } else {
      app.exit(e);
    }
    return kExitInput;  // every option error is bad input (exit 2)
  }

  try {
    // Only `swell run` is decomposed; any other command on several ranks would run N times
    // into the same files.
    if (swell::parallel::Comm::world().size() > 1 && !*run)
      throw std::invalid_argument(
          "only `swell run` runs on several MPI ranks; start this command without mpirun");
    if (*run) {
      // Under mpirun every rank runs the case on its slab; a build without MPI cannot.
      if (const int ranks = swell::parallel::launcher_world_size();
          ranks > 1 && swell::parallel::Comm::world().size() != ranks)
        throw std::invalid_argument(
            "swell run: started on " + std::to_string(ranks) +
            " MPI ranks, but this swell was built without MPI (install libopenmpi-dev and "
            "rebuild; scripts/setup does); run one rank, with OpenMP threads (-t N)");
      const swell::CaseSpec spec = swell::load_case_file(case_path, run_sets);
      swell::RunOptions opt;
      if (!restart_dir.empty()) {
        if (!out_dir.empty() && out_dir != restart_dir)
          throw std::invalid_argument("--restart " + restart_dir + " and -o " + out_dir +
                                      " differ: a restart continues in its own folder");
        out_dir = restart_dir;
        opt.restart = true;
      }
      opt.out_dir = out_dir;
      opt.overwrite = overwrite;
      opt.threads = threads;
      opt.progress = !quiet && rank0;
      opt.rebalance_every = rebalance_every;
      swell::install_stop_handlers();
      swell::run_case(spec, opt);
    } else if (*fill) {
      const swell::CaseSpec spec = swell::load_case_file(fill_case, fill_sets);
      swell::FillCommandOptions opt;
      opt.out_dir = fill_out;
      opt.threads = fill_threads;
      swell::run_fill(spec, opt, std::cout);
    } else if (*probe) {
      swell::ProbeOptions opt;
      opt.out_dir = probe_dir;
      opt.kind = probe_kind;
      opt.at = swell::parse_vector_option(probe_at, "--at");
      if (!probe_normal.empty()) opt.normal = swell::parse_vector_option(probe_normal, "--normal");
      if (probe_offset >= 0.0) {
        if (!opt.normal) throw std::invalid_argument("--offset needs --normal");
        opt.offset = probe_offset;
      }
      if (!probe_to.empty()) opt.to = swell::parse_vector_option(probe_to, "--to");
      opt.swl = probe_swl;
      opt.size = probe_size;
      opt.output = probe_out;
      const int rows = swell::run_probe(opt, std::cout);
      if (!probe_out.empty())
        std::cerr << "probe: " << rows << " snapshots -> " << probe_out << "\n";
    } else if (*compare) {
      auto window = [](const std::string& text, const std::string& option) {
        const auto v = swell::parse_vector_option(text, option);
        if (!(v[1] > v[0]) || v[2] != 0.0)
          throw std::invalid_argument(option + ": expected t0,t1 with t1 > t0");
        return swell::Window{v[0], v[1]};
      };
      if (!cmp_labels.empty()) {
        std::stringstream in(cmp_labels);
        for (std::string l; std::getline(in, l, ',');) cmp.labels.push_back(l);
      }
      if (!cmp_window.empty()) cmp.window = window(cmp_window, "--window");
      if (!cmp_peak_window.empty()) cmp.peak_window = window(cmp_peak_window, "--peak-window");
      if (*cmp_arrival_opt) cmp.arrival_threshold = cmp_arrival;
      swell::run_compare(cmp, std::cerr);
    } else if (*waves && waves->get_subcommands().empty()) {
      if (waves_h->count() == 0 || waves_opt.period <= 0.0 || waves_opt.depth <= 0.0)
        throw std::invalid_argument("waves: expected H T d (height [m], period [s], depth [m])");
      swell::run_waves(waves_opt, std::cout);
    } else if (*validate) {
      if (!val_res.empty()) val.resolutions = swell::parse_number_list(val_res, "--resolution");
      if (!val_cells.empty()) val.cell_sizes = swell::parse_number_list(val_cells, "--cell-size");
      swell::run_validate(val, std::cerr);
    } else if (*verify) {
      return swell::run_verify(ver, std::cout);
    } else if (*bench) {
      if (!bench_single.case_file.empty()) return swell::run_bench_single(bench_single, std::cout);
      if (!bench_threads.empty()) {
        bench_opt.threads.clear();
        for (const double t : swell::parse_number_list(bench_threads, "--threads")) {
          if (!(t >= 1.0) || t != std::floor(t))
            throw std::invalid_argument("--threads: expected positive integers, got " +
                                        bench_threads);
          bench_opt.threads.push_back(static_cast<int>(t));
        }
      }
      if (!bench_sweep_dp.empty())
        bench_opt.sweep_dp = swell::parse_number_list(bench_sweep_dp, "--sweep-dp");
      return swell::run_bench(bench_opt, std::cout);
    } else if (*foam) {
      const swell::CaseSpec spec = swell::load_case_file(foam_case, foam_sets);
      swell::run_foam_command(spec, foam_opt, std::cout);
    } else if (const swell::Subcommand* w = chosen_waves()) {  // swell waves analyse, ...
      w->run(std::cout);
    } else if (*help) {
      if (help_key.empty()) {
        std::cout << swell::case_schema::reference_markdown();
      } else if (const auto entry = swell::case_schema::reference_entry(help_key)) {
        std::cout << *entry;
      } else {
        std::string sections;
        for (const auto& s : swell::case_schema::sections())
          if (!s.path.empty()) sections += (sections.empty() ? "" : ", ") + std::string(s.path);
        throw std::invalid_argument("help case: no key or section '" + help_key +
                                    "' in the case-file schema; sections: " + sections +
                                    " (and the top-level keys); `swell help case` lists them all");
      }
    }
  } catch (const swell::PeerFailed& e) {
    return e.exit_code();  // rank 0 said why
  } catch (const swell::Interrupted& e) {
    std::cerr << "swell: " << e.what() << "\n";
    return e.exit_code();
  } catch (const swell::CaseError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const swell::ManifestError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const swell::FoamError& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (e.kind() == swell::FoamError::Kind::Missing) return swell::kExitFoamMissing;
    return e.kind() == swell::FoamError::Kind::Diverged ? kExitUnstable : kExitOther;
  } catch (const swell::InstabilityError& e) {
    std::cerr << "error: the run went unstable: " << e.what() << "\n";
    return kExitUnstable;
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitOther;
  }
  return 0;
}
