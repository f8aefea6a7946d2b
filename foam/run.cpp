// `swell foam`, part 3: writing the case (write_foam_case), running the OpenFOAM programs with
// failure and divergence detection (run_foam_case), and finding them (openfoam_available).
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <regex>
#include <sstream>
#include <thread>

#include "foam/foam.hpp"
#include "foam/plan.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

const char* const kDefaultProjectDir = "/usr/share/openfoam";  // Debian's openfoam package

bool find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path p = fs::path(dir) / name;
    if (::access(p.c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The last `n` lines of a file, plus (first) any line that names a fatal error.
std::string log_tail(const fs::path& log, std::size_t n = 15) {
  std::ifstream in(log);
  std::deque<std::string> last;
  std::vector<std::string> fatal;
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("FOAM FATAL") != std::string::npos && fatal.size() < 3) fatal.push_back(line);
    last.push_back(line);
    if (last.size() > n) last.pop_front();
  }
  std::string s;
  for (const auto& f : fatal) s += "    " + f + "\n";
  if (!fatal.empty()) s += "    ...\n";
  for (const auto& l : last) s += "    " + l + "\n";
  return s;
}

// Runs `command` in `dir` with its output in `log`. While it runs, `watch` (if set) is called
// every second and may ask to stop it (returns a reason). Returns the exit status (128 + signal
// when killed) and the watch reason, if any.
struct StepResult {
  int status = 0;
  std::string stopped;
};

template <class Watch>
StepResult run_step(const fs::path& dir, const std::string& command, const fs::path& log,
                    Watch&& watch) {
  std::string env;
  if (!std::getenv("WM_PROJECT_DIR"))
    env = std::string("WM_PROJECT_DIR=") + kDefaultProjectDir + " ";
  const std::string full = "cd " + shell_quote(dir.string()) + " && " + env + "exec " + command +
                           " > " + shell_quote(log.filename().string()) + " 2>&1 < /dev/null";
  const pid_t pid = ::fork();
  if (pid < 0) throw FoamError(FoamError::Kind::Failed, "cannot start " + command);
  // The child stays in our process group, so Ctrl-C stops it with us; `exec` makes the
  // command (interFoam, or mpirun which forwards signals to its ranks) the process itself.
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", full.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  StepResult r;
  int wstatus = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &wstatus, WNOHANG);
    if (w == pid) break;
    if (w < 0) throw FoamError(FoamError::Kind::Failed, "lost track of " + command);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (r.stopped.empty()) {
      r.stopped = watch();
      if (!r.stopped.empty()) ::kill(pid, SIGTERM);
    }
  }
  r.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
  return r;
}

StepResult run_step(const fs::path& dir, const std::string& command, const fs::path& log) {
  return run_step(dir, command, log, [] { return std::string(); });
}

void check_step(const std::string& step, const StepResult& r, const fs::path& log) {
  if (r.status == 0) return;
  throw FoamError(FoamError::Kind::Failed, step + " failed (exit status " +
                                               std::to_string(r.status) + "), log " + log.string() +
                                               ":\n" + log_tail(log));
}

// Cells of the mesh as the last mesh utility reported them: subsetMesh's "Subset N of M
// cells", else blockMesh's "nCells: N" (the mesh files themselves are compressed).
long count_cells(const fs::path& log, const std::string& key) {
  std::ifstream in(log);
  std::string line;
  long n = -1;
  while (std::getline(in, line)) {
    const auto k = line.find(key);
    if (k != std::string::npos) n = std::atol(line.c_str() + k + key.size());
  }
  return n;
}

// Removes what an earlier generation or run left in the case folder (never anything else).
void clean_case(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    char* end = nullptr;
    std::strtod(n.c_str(), &end);
    const bool time_dir = e.is_directory() && !n.empty() && end && *end == '\0';
    if (time_dir || n == "postProcessing" || n == "gauges" || n.rfind("processor", 0) == 0 ||
        n.rfind("log.", 0) == 0 || n == "0.orig")
      fs::remove_all(e.path());
  }
  fs::remove_all(dir / "constant/polyMesh");
}

}  // namespace

foam::SolverLog foam::check_solver_log(const std::string& log, double end_time, int status,
                                       const std::string& stopped) {
  SolverLog s;
  std::ifstream in(log);
  std::string line;
  static const std::regex nan_re("(^|[^A-Za-z])(nan|-nan|NaN|inf)([^A-Za-z]|$)");
  while (std::getline(in, line)) {
    if (line.rfind("Time = ", 0) == 0) {
      ++s.steps;
      s.last_time = std::atof(line.c_str() + 7);
    } else if (line.rfind("deltaT = ", 0) == 0) {
      s.last_dt = std::atof(line.c_str() + 9);
      s.min_dt = std::min(s.min_dt, s.last_dt);
      s.max_dt = std::max(s.max_dt, s.last_dt);
    }
    // "Courant Number mean: 0.01 max: 0.23" and "Interface Courant Number mean: ... max: ...",
    // once per step.
    if (line.find("Courant Number mean:") != std::string::npos) {
      const auto m = line.find("max:");
      if (m != std::string::npos) {
        const double c = std::atof(line.c_str() + m + 4);
        (line.rfind("Interface", 0) == 0 ? s.interface_courant_max : s.courant_max) = c;
      }
    }
    if (line.find("FOAM FATAL") != std::string::npos) s.fatal = true;
    // (The banner's "sigFpe : Enabling floating point exception trapping" is no error.)
    if (line.find("sigHandler") != std::string::npos ||
        line.find("Floating point exception (core") != std::string::npos)
      s.fpe = true;
    if (line.find("Courant") != std::string::npos ||
        line.find("Solving for") != std::string::npos || line.find("deltaT") != std::string::npos)
      if (std::regex_search(line, nan_re)) s.nan = true;
  }
  s.finished = s.last_time >= end_time * (1.0 - 1e-6) - 1e-12;
  if (!stopped.empty()) {
    s.problem = "stopped: " + stopped;
  } else if (s.nan || s.fpe) {
    s.problem = "diverged (" + std::string(s.fpe ? "floating point exception" : "nan") + ")";
  } else if (status != 0) {
    s.problem = "failed (exit status " + std::to_string(status) + ")";
    s.kind = FoamError::Kind::Failed;
  } else if (!s.finished) {
    s.problem = "stopped at t = " + std::to_string(s.last_time) + " s before the end time";
  }
  return s;
}

std::string foam::progress_line(const SolverLog& s, double end_time, double elapsed) {
  std::ostringstream o;
  o << std::setprecision(4) << "t = " << s.last_time << " of " << end_time << " s";
  if (end_time > 0)
    o << std::fixed << std::setprecision(0) << " (" << 100.0 * s.last_time / end_time << " %)";
  o << std::defaultfloat << std::setprecision(3) << ", " << s.steps << " steps";
  if (s.last_dt > 0) o << ", dt " << s.last_dt << " s";
  if (s.steps > 0)
    o << ", Courant max " << s.courant_max << " (interface " << s.interface_courant_max << ")";
  o << std::fixed << std::setprecision(0) << ", " << elapsed << " s elapsed";
  if (s.last_time > 0 && end_time > s.last_time)
    o << ", about " << elapsed * (end_time - s.last_time) / s.last_time << " s left";
  return o.str();
}

bool openfoam_available(std::string* why) {
  std::vector<std::string> missing;
  for (const char* p : {"blockMesh", "topoSet", "subsetMesh", "setFields", "interFoam"})
    if (!find_program(p)) missing.push_back(p);
  if (missing.empty() && !std::getenv("WM_PROJECT_DIR") && !fs::exists(kDefaultProjectDir))
    missing.push_back(std::string("WM_PROJECT_DIR (not set, and no ") + kDefaultProjectDir + ")");
  if (missing.empty()) return true;
  if (why) {
    *why = "OpenFOAM not found: missing";
    for (const auto& m : missing) *why += " " + m;
    *why +=
        " (install it with `apt-get install openfoam` on Debian/Ubuntu, or source an "
        "OpenFOAM environment)";
  }
  return false;
}

FoamResult write_foam_case(const CaseSpec& spec, const FoamOptions& opt, std::ostream& log) {
  if (opt.out_dir.empty()) throw std::invalid_argument("swell foam: no output folder (-o)");
  const foam::Plan plan = foam::make_plan(spec, opt);
  const fs::path dir(opt.out_dir);
  clean_case(dir);
  foam::write_case_files(plan, dir.string());

  FoamResult r;
  r.case_dir = dir.string();
  r.gauge_dir = (dir / "gauges").string();
  r.cells = plan.kept_cells;
  r.cell_size = plan.cell_size;
  r.end_time = plan.end_time;
  r.notes = plan.notes;
  const auto& g = plan.grid;
  long wet = 0;
  for (auto w : plan.wet) wet += w;
  log << "foam: case " << spec.name << " -> " << r.case_dir << "\n"
      << "  mesh: " << g.n[0] << " x " << g.n[1] << " x " << g.n[2] << " cells of " << g.cell[0]
      << " x " << g.cell[1];
  if (spec.dim == 3) log << " x " << g.cell[2];
  log << " m; " << plan.kept_cells << " cells after cutting " << plan.obstacles.size()
      << " obstacle(s); " << wet << " water cells\n"
      << "  end time " << plan.end_time << " s, fields every " << plan.write_interval
      << " s; gauges:";
  int sampled = 0;
  for (const auto& p : plan.probes) sampled += p.skipped ? 0 : 1;
  log << " " << sampled << " of " << plan.probes.size() << " sampled\n";
  for (const auto& n : plan.notes) log << "  note: " << n << "\n";
  return r;
}

FoamResult run_foam_case(const CaseSpec& spec, const FoamOptions& opt, std::ostream& log) {
  FoamResult r = write_foam_case(spec, opt, log);
  std::string why;
  if (!openfoam_available(&why))
    throw FoamError(FoamError::Kind::Missing,
                    why + ". The case was written to " + r.case_dir +
                        " (run it there with ./Allrun once OpenFOAM is installed)");
  if (opt.np > 1 && !(find_program("mpirun") && find_program("decomposePar")))
    throw FoamError(FoamError::Kind::Missing, "--np " + std::to_string(opt.np) +
                                                  " needs mpirun and decomposePar; the case "
                                                  "was written to " +
                                                  r.case_dir);
  const foam::Plan plan = foam::make_plan(spec, opt);
  const fs::path dir(r.case_dir);

  auto step = [&](const std::string& name, const std::string& command, const std::string& logname) {
    log << "  " << name << " ..." << std::flush;
    const auto t0 = std::chrono::steady_clock::now();
    const fs::path lp = dir / logname;
    const StepResult s = run_step(dir, command, lp);
    check_step(name, s, lp);
    log << " done (" << std::fixed << std::setprecision(1)
        << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s)\n"
        << std::defaultfloat;
  };
  step("blockMesh", "blockMesh", "log.blockMesh");
  for (const auto& ob : plan.obstacles) {
    step("topoSet (" + ob.name + ")", "topoSet -dict system/topoSetDict." + ob.name,
         "log.topoSet." + ob.name);
    step("subsetMesh (" + ob.name + ")",
         "subsetMesh keep_" + ob.name + " -patch " + ob.name + " -overwrite",
         "log.subsetMesh." + ob.name);
  }
  const long cells =
      plan.obstacles.empty()
          ? count_cells(dir / "log.blockMesh", "nCells:")
          : count_cells(dir / ("log.subsetMesh." + plan.obstacles.back().name), "Subset ");
  if (cells != plan.kept_cells)
    throw FoamError(FoamError::Kind::Failed,
                    "the mesh has " + std::to_string(cells) + " cells, " +
                        std::to_string(plan.kept_cells) +
                        " expected after cutting the obstacles (see log.subsetMesh.*)");
  r.cells = cells;
  fs::remove_all(dir / "0");
  fs::copy(dir / "0.orig", dir / "0", fs::copy_options::recursive);
  step("setFields", "setFields", "log.setFields");

  std::string solver = "interFoam";
  if (opt.np > 1) {
    std::ofstream(dir / "system/decomposeParDict")
        << "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
        << "    object decomposeParDict;\n}\n\nnumberOfSubdomains " << opt.np
        << ";\n\nmethod simple;\n\ncoeffs\n{\n    n (" << opt.np << " 1 1);\n}\n";
    step("decomposePar", "decomposePar -force", "log.decomposePar");
    solver = std::string("mpirun ") + (::geteuid() == 0 ? "--allow-run-as-root " : "") +
             "--oversubscribe -np " + std::to_string(opt.np) + " interFoam -parallel";
  }

  // interFoam, watched (the log, every 5 s): nan in the residuals, or a time step fallen below
  // 1e-5 of the largest one so far (after 50 steps), means the run has blown up or would crawl
  // for hours; stop it. Every 30 s (the first after 10 s) a progress line: simulated time,
  // Courant numbers, time step and the remaining wall time at the mean rate so far.
  const fs::path lp = dir / "log.interFoam";
  log << "  interFoam (" << (opt.np > 1 ? std::to_string(opt.np) + " processes" : "serial")
      << ", to t = " << std::defaultfloat << std::setprecision(6) << plan.end_time << " s, log "
      << lp.string() << ")\n"
      << std::flush;
  const auto t0 = std::chrono::steady_clock::now();
  auto last_check = t0;
  auto next_report = t0 + std::chrono::seconds(10);
  const StepResult s = run_step(dir, solver, lp, [&]() -> std::string {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_check < std::chrono::seconds(5)) return {};
    last_check = now;
    const foam::SolverLog sc = foam::check_solver_log(lp.string(), plan.end_time, 0, "");
    if (sc.nan) return "nan in the solution";
    if (sc.steps > 50 && sc.last_dt > 0 && sc.last_dt < 1e-5 * sc.max_dt)
      return "time step collapsed to " + std::to_string(sc.last_dt) + " s";
    if (now >= next_report) {
      next_report = now + std::chrono::seconds(30);
      log << "    "
          << foam::progress_line(sc, plan.end_time, std::chrono::duration<double>(now - t0).count())
          << "\n"
          << std::flush;
    }
    return {};
  });
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const foam::SolverLog sc =
      foam::check_solver_log(lp.string(), plan.end_time, s.status, s.stopped);
  r.steps = sc.steps;
  log << "  interFoam: " << sc.steps << " steps, " << std::fixed << std::setprecision(1)
      << r.wall_seconds << " s\n"
      << std::defaultfloat;
  const std::string& problem = sc.problem;
  const FoamError::Kind kind = sc.kind;
  if (!problem.empty()) {
    // Convert what was sampled, so the partial series can still be looked at.
    try {
      convert_foam_gauges(spec, opt, r.gauge_dir, log);
    } catch (const std::exception&) {
    }
    throw FoamError(kind, "interFoam " + problem + " after " + std::to_string(sc.steps) +
                              " steps at t = " + std::to_string(sc.last_time) + " s, log " +
                              lp.string() + ":\n" + log_tail(lp));
  }
  r.ran = true;
  convert_foam_gauges(spec, opt, r.gauge_dir, log);
  return r;
}

}  // namespace swell
