#include "apps/verify_command.hpp"

#include <omp.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/provenance.hpp"
#include "io/resources.hpp"
#include "validation/validation_report.hpp"
#include "verify/verify.hpp"

namespace swell {
namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream o;
  o << std::setprecision(4) << v;
  return o.str();
}

std::string bound_text(const verify::Figure& f) {
  switch (f.rel) {
    case verify::Figure::Rel::AtMost:
      return "<= " + number(f.bound);
    case verify::Figure::Rel::AtLeast:
      return ">= " + number(f.bound);
    case verify::Figure::Rel::Report:
      return "(reported)";
  }
  return "";
}

void write_table(const fs::path& dir, const verify::Table& t) {
  for (const auto& c : t.columns)  // the header is split at commas (plot_verify.py, users)
    if (c.find(',') != std::string::npos)
      throw std::logic_error("verify: table " + t.file + ": column name '" + c + "' holds a comma");
  std::ofstream out(dir / (t.file + ".csv"));
  for (std::size_t c = 0; c < t.columns.size(); ++c) out << (c ? "," : "") << t.columns[c];
  out << "\n" << std::setprecision(12);
  for (const auto& row : t.rows) {
    if (row.size() != t.columns.size())
      throw std::logic_error("verify: table " + t.file + " has a row of " +
                             std::to_string(row.size()) + " values for " +
                             std::to_string(t.columns.size()) + " columns");
    for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << row[c];
    out << "\n";
  }
  if (!out) throw std::runtime_error("verify: cannot write " + (dir / (t.file + ".csv")).string());
}

// plots.tsv: one line per plot: file, title, table, x, y columns (separated by ';'), log_x,
// log_y, style - read by verify/plot_verify.py.
void write_plot_list(const fs::path& dir, const std::vector<verify::Plot>& plots) {
  std::ofstream out(dir / "plots.tsv");
  for (const auto& p : plots) {
    std::string ys;
    for (const auto& y : p.y) ys += (ys.empty() ? "" : ";") + y;
    out << p.file << "\t" << p.title << "\t" << p.table << "\t" << p.x << "\t" << ys << "\t"
        << (p.log_x ? 1 : 0) << "\t" << (p.log_y ? 1 : 0) << "\t" << p.style << "\n";
  }
}

}  // namespace

int run_verify(const VerifyOptions& opt, std::ostream& log) {
  const auto& all = verify::all();
  if (opt.list) {
    for (const auto& v : all) log << std::left << std::setw(20) << v.name << " " << v.title << "\n";
    return 0;
  }
  std::vector<const verify::Verification*> chosen;
  if (opt.names.empty()) {
    for (const auto& v : all) chosen.push_back(&v);
  } else {
    for (const auto& n : opt.names) {
      const verify::Verification* found = nullptr;
      for (const auto& v : all)
        if (n == v.name) found = &v;
      if (!found) {
        std::string names;
        for (const auto& v : all) names += (names.empty() ? "" : ", ") + std::string(v.name);
        throw std::invalid_argument("verify: no verification named '" + n + "' (known: " + names +
                                    "; `swell verify --list`)");
      }
      chosen.push_back(found);
    }
  }
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const fs::path out = opt.out_dir;
  fs::create_directories(out);
  const std::string python = find_plot_python();
  const auto script = find_data_file("verify/plot_verify.py");
  if (python.empty() || !script)
    log << "verify: no plots (needs python3 with matplotlib and verify/plot_verify.py)\n";

  std::ostringstream report;
  report << "# swell verify\n\n```\n"
         << provenance_text(capture_provenance(), "") << "```\n\n"
         << "Form: " << (opt.full ? "full (--full)" : "fast (the ctest form)") << ", "
         << opt.threads << " thread(s).\n\n| verification | verdict | figures | run time [s] |\n"
         << "|---|---|---|---|\n";
  std::ostringstream body;
  int failed = 0;
  for (const auto* v : chosen) {
    const fs::path dir = out / v->name;
    fs::create_directories(dir);
    verify::Options vo;
    vo.outdir = dir;
    vo.full = opt.full;
    vo.threads = opt.threads;
    log << "verify: " << v->name << " (" << v->title << ") ..." << std::flush;
    const auto t0 = std::chrono::steady_clock::now();
    verify::Result r;
    std::string error;
    try {
      r = v->run(vo);
    } catch (const std::exception& e) {
      error = e.what();
    }
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool pass = error.empty() && r.passed() && !r.figures.empty();
    if (!pass) ++failed;
    log << (pass ? " pass" : " FAIL") << " (" << number(secs) << " s)\n";
    for (const auto& t : r.tables) write_table(dir, t);
    write_plot_list(dir, r.plots);
    if (!python.empty() && script && !r.plots.empty()) {
      const std::string cmd = quoted(python) + " " + quoted(script->string()) + " " +
                              quoted(dir.string()) + " > " + quoted((dir / "plots.log").string()) +
                              " 2>&1";
      if (std::system(cmd.c_str()) != 0)
        log << "verify: the plots of " << v->name << " failed, see " << (dir / "plots.log") << "\n";
    }
    int n_pass = 0;
    for (const auto& f : r.figures) n_pass += f.pass() ? 1 : 0;
    report << "| [" << v->name << "](#" << v->name << ") | " << (pass ? "pass" : "**FAIL**")
           << " | " << n_pass << "/" << r.figures.size() << " | " << number(secs) << " |\n";
    body << "\n## " << v->name << "\n\n"
         << v->title << ". " << (pass ? "Pass" : "**FAIL**") << ", " << number(secs) << " s.\n\n";
    if (!error.empty()) body << "Error: " << error << "\n\n";
    if (!r.notes.empty()) body << r.notes << "\n\n";
    body << "| figure | value | unit | bound | verdict |\n|---|---|---|---|---|\n";
    for (const auto& f : r.figures)
      body << "| " << f.name << " | " << number(f.value) << " | " << f.unit << " | "
           << bound_text(f) << " | "
           << (f.rel == verify::Figure::Rel::Report ? "-" : (f.pass() ? "pass" : "**FAIL**"))
           << " |\n";
    for (const auto& p : r.plots)
      if (fs::exists(dir / (p.file + ".png")))
        body << "\n![" << p.title << "](" << v->name << "/" << p.file << ".png)\n";
    for (const auto& t : r.tables)
      body << "\nTable: [" << t.file << ".csv](" << v->name << "/" << t.file << ".csv)\n";
  }
  std::ofstream rep(out / "report.md");
  rep << report.str() << body.str();
  if (!rep) throw std::runtime_error("verify: cannot write " + (out / "report.md").string());
  log << "verify: " << (chosen.size() - static_cast<std::size_t>(failed)) << "/" << chosen.size()
      << " passed; report " << (out / "report.md").string() << "\n";
  return failed == 0 ? 0 : 1;
}

Subcommand add_verify_command(CLI::App& app) {
  auto ver = std::make_shared<VerifyOptions>();
  auto* verify = app.add_subcommand(
      "verify", "the method checked piece by piece: consistency, convergence, conservation");
  verify->add_option("names", ver->names, "verifications to run (default: all; --list)");
  verify->add_option("-o,--out", ver->out_dir, "output folder (default: out/verify)");
  verify->add_flag("--full", ver->full, "the full convergence studies (longer)");
  verify->add_flag("--list", ver->list, "list the verifications and stop");
  verify->add_option("-t,--threads", ver->threads, "OpenMP threads")->check(count_check());
  return Subcommand(verify, [ver] { return run_verify(*ver, std::cout); });
}

}  // namespace swell
