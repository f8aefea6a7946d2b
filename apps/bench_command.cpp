#include "apps/bench_command.hpp"

#include <omp.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "apps/validate_command.hpp"
#include "bench/bench_run.hpp"
#include "bench/bench_single.hpp"
#include "case/reader.hpp"
#include "io/resources.hpp"
#include "run/run.hpp"
#include "validation/validation_report.hpp"

namespace swell {
namespace {

namespace fs = std::filesystem;

// DualSPHysics 5.4 CPU on a 2-core machine of this kind, same cases and settings (issue #5):
// particle-steps per second with 1 and 2 threads (0: not measured), steps, particles, RSS.
struct Reference {
  double pss1 = 0.0, pss2 = 0.0;
  long steps = 0;
  long particles = 0;
  double rss_mb = 0.0;
};

struct BenchCase {
  std::string name, file;
  double dp = 0.0;
  Reference ref;
};

std::vector<BenchCase> builtin_cases() {
  return {
      {"b2d", "b2d.yaml", 0.01, {1.25e6, 2.10e6, 6320, 21001, 10.0}},
      {"b3d", "b3d.yaml", 0.02, {0.25e6, 0.47e6, 1503, 17446, 10.0}},
      {"b3d_fine", "b3d.yaml", 0.015, {0.0, 0.38e6, 0, 37896, 13.0}},
      // The same cases with mDBC walls (bc/mdbc): the cost of the ghost nodes (no reference).
      {"b2d_mdbc", "b2d_mdbc.yaml", 0.01, {}},
      {"b3d_mdbc", "b3d_mdbc.yaml", 0.02, {}},
      // And with particle shifting (solver/physics/shifting.hpp): the cost of its two passes.
      {"b2d_shift", "b2d_shift.yaml", 0.01, {}},
      {"b3d_shift", "b3d_shift.yaml", 0.02, {}},
  };
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

fs::path self_exe() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("bench: cannot find the swell executable (/proc/self/exe)");
  return exe;
}

// The folder holding the benchmark cases: given, else bench/ of Swell's data (io/resources:
// $SWELL_HOME, the install prefix's share/swell, the source tree).
fs::path find_bench_dir(const std::string& given) {
  if (!given.empty()) {
    if (!fs::exists(fs::path(given) / "cases" / "b2d.yaml"))
      throw std::invalid_argument("--bench-dir " + given + ": expected " + given +
                                  "/cases/b2d.yaml");
    return given;
  }
  std::vector<std::string> tried;
  if (const auto f = find_data_file("bench/cases/b2d.yaml", &tried))
    return f->parent_path().parent_path();
  throw std::invalid_argument("bench: cannot find the benchmark cases (tried " + tried_list(tried) +
                              "); pass --bench-dir, or " + data_roots_hint());
}

struct Measurement {
  std::map<std::string, double> v;  // the bench-result fields
  double get(const std::string& k) const {
    const auto it = v.find(k);
    return it == v.end() ? 0.0 : it->second;
  }
};

// The measuring program: swell_bench_run next to this executable (lean: only the solver's
// libraries loaded), else this executable's `bench --single`.
std::string runner_command(const fs::path& exe) {
  const fs::path lean = exe.parent_path() / "swell_bench_run";
  if (fs::exists(lean)) return shell_quote(lean.string());
  return shell_quote(exe.string()) + " bench --single";
}

// Runs one measurement in a child process and parses its bench-result line.
Measurement measure(const fs::path& exe, const std::string& file, double dp, int threads,
                    double end, long steps, long warmup) {
  std::ostringstream cmd;
  cmd << runner_command(exe) << " " << shell_quote(file) << " --dp " << std::setprecision(17) << dp
      << " -t " << threads;
  if (end > 0.0) cmd << " --end " << end;
  if (steps > 0) cmd << " --steps " << steps << " --warmup " << warmup;
  cmd << " 2>&1";
  std::FILE* pipe = ::popen(cmd.str().c_str(), "r");
  if (!pipe) throw std::runtime_error("bench: cannot start " + cmd.str());
  std::string output, line;
  char buf[4096];
  Measurement m;
  bool found = false;
  while (std::fgets(buf, sizeof buf, pipe)) {
    output += buf;
    line = buf;
    if (line.rfind("bench-result", 0) == 0) {
      std::istringstream in(line.substr(12));
      for (std::string kv; in >> kv;) {
        const auto eq = kv.find('=');
        if (eq != std::string::npos) m.v[kv.substr(0, eq)] = std::stod(kv.substr(eq + 1));
      }
      found = true;
    }
  }
  const int status = ::pclose(pipe);
  if (status != 0 || !found)
    throw std::runtime_error("bench: the run `" + cmd.str() + "` failed (status " +
                             std::to_string(status) + "):\n" + output);
  return m;
}

double median(std::vector<double> x) {
  if (x.empty()) return 0.0;
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

std::string mega(double pss) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << pss / 1e6 << " M";
  return o.str();
}

}  // namespace

int run_bench(const BenchOptions& opt, std::ostream& log) {
  const fs::path dir = find_bench_dir(opt.bench_dir);
  const fs::path exe = self_exe();
  const fs::path out(opt.out_dir);
  fs::create_directories(out);
  if (opt.repeats < 1) throw std::invalid_argument("--repeats: expected at least 1");

  std::vector<BenchCase> cases;
  const auto all = builtin_cases();
  if (opt.cases.empty() && !opt.sweep) cases.assign(all.begin(), all.begin() + 3);
  for (const auto& name : opt.cases) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const auto& c) { return c.name == name; });
    if (it == all.end())
      throw std::invalid_argument(
          "bench: unknown case '" + name +
          "' (expected b2d, b3d, b3d_fine, b2d_mdbc, b3d_mdbc, b2d_shift or "
          "b3d_shift)");
    cases.push_back(*it);
  }

  const Provenance prov = capture_provenance();
  {
    RunInfo info;
    info.header = "how the files in this folder were produced (written by swell bench)";
    info.kind = "bench";
    info.date = utc_minutes_now();
    info.provenance = {prov};
    write_run_info(out.string(), info);
  }
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::localtime(&now));
  log << "bench: " << prov.cpu << ", " << omp_get_num_procs() << " logical CPUs, " << date << "; "
      << opt.repeats << " run(s) per point, medians\n";

  std::ofstream runs_csv, sum_csv;
  if (!cases.empty()) {
    runs_csv.open(out / "bench_runs.csv");
    sum_csv.open(out / "bench_summary.csv");
  }
  runs_csv
      << "# every run of swell bench; pss = particles x steps / wall [1/s], times [s], RSS [kB]\n"
      << "case,dp,threads,repeat,particles,steps,wall,pss,neighbour,interaction,integration,"
         "other,rss_base_kb,rss_peak_kb\n";
  sum_csv << "# medians over repeats; dsph_pss: DualSPHysics 5.4 CPU, same case (issue #5)\n"
          << "case,dp,threads,particles,steps,wall,pss,dsph_pss,ratio,neighbour,interaction,"
             "integration,other,rss_peak_mb,bytes_per_particle\n";

  std::ostringstream table;
  table << "| case | particles | steps (DSPH) | threads | wall [s] | particle-steps/s | DSPH | "
           "ratio | neighbour / interaction / integration / other [%] | peak RSS [MB] | "
           "B/particle |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::map<std::string, double> pss_of;  // case/threads -> median pss, for the speed-up line
  for (const auto& c : cases) {
    const std::string file = (dir / "cases" / c.file).string();
    for (const int t : opt.threads) {
      std::vector<Measurement> ms;
      std::vector<double> pss, wall, rss;
      for (int r = 0; r < opt.repeats; ++r) {
        log << "bench: " << c.name << " dp " << c.dp << ", " << t << " thread(s), run " << r + 1
            << "/" << opt.repeats << " ... " << std::flush;
        const Measurement m = measure(exe, file, c.dp, t, 0.0, 0, 0);
        log << mega(m.get("pss")) << " particle-steps/s, " << m.get("steps") << " steps, "
            << std::setprecision(4) << m.get("wall") << " s\n";
        runs_csv << c.name << "," << c.dp << "," << t << "," << r << "," << m.get("particles")
                 << "," << m.get("steps") << "," << m.get("wall") << "," << m.get("pss") << ","
                 << m.get("neighbour") << "," << m.get("interaction") << "," << m.get("integration")
                 << "," << m.get("other") << "," << m.get("rss_base_kb") << ","
                 << m.get("rss_peak_kb") << "\n";
        ms.push_back(m);
        pss.push_back(m.get("pss"));
      }
      // The run with the median speed gives the phase split.
      std::vector<std::size_t> idx(ms.size());
      for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
      std::sort(idx.begin(), idx.end(),
                [&](auto a, auto b) { return ms[a].get("pss") < ms[b].get("pss"); });
      const Measurement& med = ms[idx[idx.size() / 2]];
      const double p = median(pss);
      pss_of[c.name + "/" + std::to_string(t)] = p;
      const double ref = t == 1 ? c.ref.pss1 : t == 2 ? c.ref.pss2 : 0.0;
      const double n = med.get("particles");
      const double rss_mb = med.get("rss_peak_kb") / 1024.0;
      const double bpp = (med.get("rss_peak_kb") - med.get("rss_base_kb")) * 1024.0 / n;
      const double w = med.get("wall");
      auto pct = [&](const char* k) {
        std::ostringstream o;
        o << std::fixed << std::setprecision(0) << 100.0 * med.get(k) / w;
        return o.str();
      };
      sum_csv << c.name << "," << c.dp << "," << t << "," << n << "," << med.get("steps") << ","
              << w << "," << p << "," << ref << "," << (ref > 0 ? p / ref : 0.0) << ","
              << med.get("neighbour") << "," << med.get("interaction") << ","
              << med.get("integration") << "," << med.get("other") << "," << rss_mb << "," << bpp
              << "\n";
      std::ostringstream ratio;
      ratio << std::fixed << std::setprecision(2) << (ref > 0 ? p / ref : 0.0) << "x";
      table << "| " << c.name << " (dp " << c.dp << ") | " << static_cast<long>(n) << " | "
            << static_cast<long>(med.get("steps")) << " ("
            << (c.ref.steps ? std::to_string(c.ref.steps) : "-") << ") | " << t << " | "
            << std::fixed << std::setprecision(1) << w << " | " << mega(p) << " | "
            << (ref > 0 ? mega(ref) : "-") << " | " << (ref > 0 ? ratio.str() : "-") << " | "
            << pct("neighbour") << " / " << pct("interaction") << " / " << pct("integration")
            << " / " << pct("other") << " | " << std::setprecision(1) << rss_mb << " ("
            << c.ref.rss_mb << ") | " << std::setprecision(0) << bpp << " |\n";
      table.unsetf(std::ios::fixed);
      table << std::setprecision(6);
    }
  }
  if (!cases.empty()) {
    log << "\n" << table.str();
    for (const auto& c : cases) {
      const auto a = pss_of.find(c.name + "/1"), b = pss_of.find(c.name + "/2");
      if (a != pss_of.end() && b != pss_of.end() && a->second > 0)
        log << c.name << ": speed-up 1 -> 2 threads " << std::setprecision(3)
            << b->second / a->second << "x\n";
    }
    std::ofstream(out / "bench_table.md") << table.str();
    log << "bench: wrote " << (out / "bench_summary.csv").string() << ", "
        << (out / "bench_runs.csv").string() << ", " << (out / "bench_table.md").string() << "\n";
  }

  if (opt.sweep) {
    std::vector<double> dps = opt.sweep_dp;
    if (dps.empty()) dps = {0.025, 0.02, 0.015, 0.01, 0.0075, 0.006, 0.005, 0.0045};
    const int t = *std::max_element(opt.threads.begin(), opt.threads.end());
    const fs::path sweep_csv = out / "scaling.csv";
    std::ofstream sw(sweep_csv);
    sw << "# swell bench --sweep: B3D (bench/cases/b3d.yaml) over dp, " << t << " thread(s), "
       << opt.sweep_steps << " timed steps after " << opt.sweep_warmup
       << " warm-up steps, median of " << opt.repeats << " run(s); " << prov.cpu << ", " << date
       << "\n"
       << "dp,particles,fluid,steps,wall,pss,ns_per_particle_step,ns_per_fluid_particle_step,"
          "neighbour,interaction,integration,rss_peak_mb,bytes_per_particle\n";
    const std::string file = (dir / "cases" / "b3d.yaml").string();
    for (const double dp : dps) {
      std::vector<Measurement> ms;
      for (int r = 0; r < opt.repeats; ++r) {
        log << "bench: sweep dp " << dp << ", run " << r + 1 << "/" << opt.repeats << " ... "
            << std::flush;
        ms.push_back(measure(exe, file, dp, t, 0.0, opt.sweep_steps, opt.sweep_warmup));
        log << static_cast<long>(ms.back().get("particles")) << " particles, "
            << mega(ms.back().get("pss")) << " particle-steps/s\n";
      }
      std::sort(ms.begin(), ms.end(),
                [](const auto& a, const auto& b) { return a.get("pss") < b.get("pss"); });
      const Measurement& m = ms[ms.size() / 2];
      const double n = m.get("particles");
      sw << dp << "," << n << "," << m.get("fluid") << "," << m.get("steps") << "," << m.get("wall")
         << "," << m.get("pss") << "," << 1e9 / m.get("pss") << ","
         << 1e9 * m.get("wall") / (m.get("fluid") * m.get("steps")) << "," << m.get("neighbour")
         << "," << m.get("interaction") << "," << m.get("integration") << ","
         << m.get("rss_peak_kb") / 1024.0 << ","
         << (m.get("rss_peak_kb") - m.get("rss_base_kb")) * 1024.0 / n << "\n";
      sw.flush();
    }
    log << "bench: wrote " << sweep_csv.string() << "\n";
    const std::string python = find_plot_python();
    const fs::path script = dir / "plot_scaling.py";
    if (python.empty() || !fs::exists(script)) {
      log << "bench: no plot (needs python3 with matplotlib and " << script.string() << ")\n";
    } else {
      const std::string png = (out / "scaling.png").string();
      const std::string cmd = shell_quote(python) + " " + shell_quote(script.string()) + " " +
                              shell_quote(sweep_csv.string()) + " " + shell_quote(png);
      if (std::system(cmd.c_str()) == 0)
        log << "bench: wrote " << png << "\n";
      else
        log << "bench: the plot failed (" << cmd << ")\n";
    }
  }
  return 0;
}

Subcommand add_bench_command(CLI::App& app) {
  struct Options {
    BenchOptions bench;
    BenchSingleOptions single;
    std::string threads, sweep_dp;
  };
  auto o = std::make_shared<Options>();
  BenchOptions& bench_opt = o->bench;
  BenchSingleOptions& bench_single = o->single;
  auto* bench = app.add_subcommand(
      "bench", "performance benchmark: B2D, B3D (DualSPHysics' cases), 1 and 2 threads, scaling");
  bench
      ->add_option("cases", bench_opt.cases,
                   "b2d, b3d, b3d_fine (default: these three); b2d_mdbc, b3d_mdbc (mDBC walls); "
                   "b2d_shift, b3d_shift (particle shifting)")
      ->check(CLI::IsMember(
          {"b2d", "b3d", "b3d_fine", "b2d_mdbc", "b3d_mdbc", "b2d_shift", "b3d_shift"}));
  bench->add_option("--threads", o->threads, "thread counts t1,t2 (default 1,2)");
  bench->add_option("--repeats", bench_opt.repeats, "runs per point; medians are reported")
      ->check(count_check());
  bench->add_flag("--sweep", bench_opt.sweep, "B3D over dp (N ~1e4..1e6): cost per particle-step");
  bench->add_option("--sweep-dp", o->sweep_dp, "sweep dp list d1,d2,... [m]");
  bench->add_option("--sweep-steps", bench_opt.sweep_steps, "timed steps per sweep point")
      ->check(count_check());
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
  return Subcommand(bench, [o] {
    if (!o->single.case_file.empty()) return run_bench_single(o->single, std::cout);
    BenchOptions opt = o->bench;
    if (!o->threads.empty()) {
      opt.threads.clear();
      for (const double t : parse_number_list(o->threads, "--threads")) {
        if (!(t >= 1.0) || t != std::floor(t))
          throw std::invalid_argument("--threads: expected positive integers, got " + o->threads);
        opt.threads.push_back(static_cast<int>(t));
      }
    }
    if (!o->sweep_dp.empty()) opt.sweep_dp = parse_number_list(o->sweep_dp, "--sweep-dp");
    return run_bench(opt, std::cout);
  });
}

}  // namespace swell
