// bapd-fit: fits hyperelastic laws to stress-stretch test data (docs/laws.md).
//
//   bapd-fit -law gent,mooney_rivlin data/pure_shear.csv uniaxial:data/uni.csv
//
// Reads the curves (fit_data.hpp: bapd-fit's stretch-stress CSV or a test machine's
// export, converted with the specimen options before it; what was converted or
// dropped is noted), fits each law (fit_run.hpp), prints the parameters with their
// standard errors and a comparison table, writes the files of fit_report.hpp
// and, unless -no_plot, draws fit_<mode>.png with scripts/plot_fit.py. A notched
// pure-shear curve is not fitted: it gives the crack onset, and each law the toughness
// Gamma = W(lambda_c) H0 (toughness.hpp), printed and written as the scene's failure:
// section. Bad input stops
// it with one "bapd-fit: error: ..." line and exit status 1; so does any law that
// cannot fit the data (after the others are written).
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fit_error.hpp"
#include "fit_laws.hpp"
#include "fit_report.hpp"
#include "fit_run.hpp"
#include "toughness.hpp"
#include "bapd/version.hpp"

#ifndef BAPD_SOURCE_DIR
#define BAPD_SOURCE_DIR "."
#endif

namespace {

using namespace bapd::fit;

const char *usage_head =
    "usage: bapd-fit [options] [specimen options] [MODE:]FILE ...\n"
    "  FILE              one test: nominal stress against stretch (a 'stretch' column and one named\n"
    "                    ..._stress_Pa or ..._stress_kPa), or a test machine's export of extension and\n"
    "                    force ('Extension (mm)', 'Load (N)', 'Force [kN]', 'Strain (%)', 'Stress (MPa)'...;\n"
    "                    ',' ';' or tab separated, decimal commas read); the test from a\n"
    "                    '# mode: uniaxial|pure_shear|equibiaxial' line or the MODE: tag; notched_pure_shear:\n"
    "                    a notched sheet's curve, not fitted: its peak is the crack onset lambda_c, and\n"
    "                    Gamma = W(lambda_c) H0 is printed and written as each law's failure: section\n"; // then -law's (LawUsage)
const char *usage_tail =
    "  -ogden_terms N    terms of the Ogden law, 1 to 4 (default 2)\n"
    "  -weight W         relative (default: residual / max(|P|, 5 % of the curve's top)) or absolute (Pa)\n"
    "  -output_dir DIR   where the files go (default bapd_fit_output)\n"
    "  -no_plot          skip the PNGs (scripts/plot_fit.py; needs /usr/bin/python3 with matplotlib)\n"
    "  -plot_script PATH the plotting script (default " BAPD_SOURCE_DIR "/scripts/plot_fit.py)\n"
    "  -version          the version of bapd-fit (bapd's)\n"
    "  -fit_onset_stretch L  the notched test's crack onset stretch as measured (e.g. by video), instead of\n"
    "                    the stretch of its peak stress; -fit_onset_stretch_uncertainty U its uncertainty (default 0)\n"
    "specimen options, at rest, in SI, for the files after them (an export of extension or force needs them):\n"
    "  -fit_gauge_length L    the clamps' separation [m]: stretch = 1 + extension / L (and a notched\n"
    "                         sheet's height H0: the pure-shear and notched files need the same)\n"
    "  -fit_cross_section A   width x thickness [m^2]: nominal stress = force / A\n"
    "  -fit_width W -fit_thickness T   the same section as two lengths [m]\n";

// -law's lines of the usage: the laws bapd-fit knows (fit_law_names, the law registry's),
// wrapped at 104 columns as the other lines are.
std::string LawUsage()
{
  std::vector<std::string> words;
  for (const std::string &name : fit_law_names()) words.push_back(name + ",");
  for (const char *w : {"or", "all", "(default", "gent)"}) words.push_back(w);
  std::string text, line = "  -law LIST         laws to fit, comma-separated:";
  for (const std::string &w : words) {
    if (line.size() + 1 + w.size() > 104) {
      text += line + "\n";
      line = std::string(20, ' ') + w;
    } else line += " " + w;
  }
  return text + line + "\n";
}

std::vector<std::string> split_commas(const std::string &s)
{
  std::vector<std::string> out;
  std::stringstream        ss(s);
  std::string              item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// The specimen options given so far: every file takes those before it.
struct SpecimenOptions {
  double      gauge_length = 0.0, cross_section = 0.0, width = 0.0, thickness = 0.0;
  std::string pending; // the last one given if no file has followed it yet

  Specimen resolve() const
  {
    if ((width > 0.0) != (thickness > 0.0))
      throw FitError(std::string(width > 0.0 ? "-fit_width" : "-fit_thickness") + " needs " +
                     (width > 0.0 ? "-fit_thickness" : "-fit_width") + " too (the section is their product), or give -fit_cross_section A");
    return {gauge_length, width > 0.0 ? width * thickness : cross_section};
  }
};

// A length or an area > 0 for a specimen option, with a note when it is implausible in SI.
double specimen_value(const std::string &option, const std::string &v, bool area)
{
  char        *end   = nullptr;
  const double value = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(value) || !(value > 0.0))
    throw FitError(option + " " + v + ": give " + (area ? "the area in m^2, a number > 0 (e.g. 1e-5 for 10 mm^2)" : "the length in m, a number > 0 (e.g. 0.02 for 20 mm)"));
  if (area ? value > 0.01 : value > 1.0)
    std::cout << "note: " << option << " " << v << (area ? " m^2: areas are in m^2 (" + v + " mm^2 would be " : " m: lengths are in m (" + v + " mm would be ")
              << value * (area ? 1e-6 : 1e-3) << ")\n";
  return value;
}

// -fit_onset_stretch (> 1) or -fit_onset_stretch_uncertainty (>= 0).
double onset_value(const std::string &option, const std::string &v)
{
  char        *end   = nullptr;
  const double x     = std::strtod(v.c_str(), &end);
  const bool   onset = option == "-fit_onset_stretch";
  if (v.empty() || *end != '\0' || !std::isfinite(x) || (onset ? !(x > 1.0) : !(x >= 0.0)))
    throw FitError(option + " " + v + (onset ? ": give the crack onset's stretch, a number > 1 (e.g. 3.02)" : ": give a number >= 0 (e.g. 0.02)"));
  return x;
}

// The notched test's onset as given on the command line (0: not given).
struct OnsetOptions {
  double      stretch = 0.0, uncertainty = 0.0;
  std::string option; // the last one given, for the message without a notched curve
};

// Reads every file (their notes printed); the fitted curves into curves, and the
// notched one, if any, as the toughness test it gives (toughness.hpp).
std::unique_ptr<ToughnessTest> read_data(const std::vector<std::pair<std::string, Specimen>> &files, const OnsetOptions &onset,
                                         std::vector<Curve> &curves)
{
  std::vector<Curve> all;
  for (const auto &[f, geometry] : files) {
    std::string mode, path = f;
    const auto  colon = f.find(':');
    bapd::LoadMode m;
    bool           notched = false;
    if (colon != std::string::npos && parse_test(f.substr(0, colon), m, notched)) mode = f.substr(0, colon), path = f.substr(colon + 1);
    all.push_back(read_curve(path, mode, geometry));
  }
  for (const Curve &c : all) {
    if (c.notes.empty()) continue;
    std::cout << c.file << ": " << (c.notched ? "notched_pure_shear" : to_string(c.mode)) << ", " << c.stretch.size()
              << " points, stretch " << c.stretch.front() << " to " << c.stretch.back() << "\n";
    for (const std::string &note : c.notes) std::cout << "  note: " << note << "\n";
  }
  const Curve *notched = nullptr; // not fitted: it gives the toughness
  for (const Curve &c : all) {
    if (!c.notched) curves.push_back(c);
    else if (notched)
      throw FitError(c.file + ": a second notched curve (the first: " + notched->file + "); give one notched test a run (run bapd-fit once for each)");
    else notched = &c;
  }
  if (!onset.option.empty() && !notched)
    throw FitError(onset.option + " is for the crack onset of a notched pure-shear test: give that test's curve too, notched_pure_shear:FILE");
  if (onset.uncertainty > 0.0 && !(onset.stretch > 0.0))
    throw FitError("-fit_onset_stretch_uncertainty is the uncertainty of -fit_onset_stretch: give the onset stretch too");
  if (!notched) return nullptr;
  return std::make_unique<ToughnessTest>(prepare_toughness(*notched, curves, onset.stretch, onset.uncertainty));
}

int run(int argc, char **argv)
{
  std::vector<std::string> laws = {"gent"};
  std::vector<std::pair<std::string, Specimen>> files;
  SpecimenOptions          specimen;
  int                      ogden_terms = 2;
  Weighting                weighting   = Weighting::relative;
  std::string              output_dir = "bapd_fit_output", plot_script = BAPD_SOURCE_DIR "/scripts/plot_fit.py";
  bool                     plot = true;
  OnsetOptions             onset;
  for (int i = 1; i < argc; ++i) {
    const std::string a     = argv[i];
    auto              value = [&]() -> std::string {
      if (i + 1 >= argc) throw FitError(a + " needs a value (bapd-fit -help lists the options)");
      return argv[++i];
    };
    if (a == "-help" || a == "--help" || a == "-h") {
      std::cout << usage_head << LawUsage() << usage_tail;
      return 0;
    } else if (a == "-version" || a == "--version") {
      std::cout << "bapd-fit " << bapd::VersionText() << "\n";
      return 0;
    } else if (a == "-law") {
      laws = split_commas(value());
      if (laws.size() == 1 && laws[0] == "all") laws = fit_law_names();
    } else if (a == "-ogden_terms") {
      const std::string v = value();
      char             *end = nullptr;
      ogden_terms           = static_cast<int>(std::strtol(v.c_str(), &end, 10));
      if (v.empty() || *end != '\0') throw FitError("-ogden_terms " + v + ": give a whole number of terms, 1 to 4");
    } else if (a == "-weight") {
      const std::string v = value();
      if (v == "relative") weighting = Weighting::relative;
      else if (v == "absolute") weighting = Weighting::absolute;
      else throw FitError("-weight " + v + ": choose relative or absolute");
    } else if (a == "-output_dir") output_dir = value();
    else if (a == "-no_plot") plot = false;
    else if (a == "-plot_script") plot_script = value();
    else if (a == "-fit_onset_stretch" || a == "-fit_onset_stretch_uncertainty")
      (a == "-fit_onset_stretch" ? onset.stretch : onset.uncertainty) = onset_value(a, value()), onset.option = a;
    else if (a == "-fit_gauge_length") specimen.gauge_length = specimen_value(a, value(), false), specimen.pending = a;
    else if (a == "-fit_cross_section") {
      specimen.cross_section = specimen_value(a, value(), true), specimen.pending = a;
      specimen.width = specimen.thickness = 0.0; // the latest way of giving the section counts
    } else if (a == "-fit_width" || a == "-fit_thickness") {
      (a == "-fit_width" ? specimen.width : specimen.thickness) = specimen_value(a, value(), false), specimen.pending = a;
      specimen.cross_section = 0.0;
    } else if (!a.empty() && a[0] == '-') throw FitError(a + " is not an option of bapd-fit (bapd-fit -help lists them)");
    else {
      files.emplace_back(a, specimen.resolve());
      specimen.pending.clear();
    }
  }
  if (files.empty()) throw FitError("no data: give one or more CSV files of stretch and nominal stress, or exports of extension and force (bapd-fit -help)");
  if (!specimen.pending.empty())
    throw FitError(specimen.pending + " comes after the last file and describes none: give the specimen options before the file(s) they "
                   "describe, e.g. bapd-fit -fit_gauge_length 0.02 -fit_cross_section 1e-5 uniaxial:export.csv");
  if (laws.empty()) throw FitError("-law: give at least one law");

  std::vector<Curve>             curves; // the fitted ones
  std::unique_ptr<ToughnessTest> toughness = read_data(files, onset, curves);
  std::vector<FitLaw> chosen;
  for (const std::string &name : laws) chosen.push_back(fit_law(name, ogden_terms)); // unknown names first
  std::vector<LawFit> fits;
  for (const FitLaw &law : chosen) fits.push_back(fit_law_to_data(law, curves, weighting));
  for (const LawFit &f : fits) print_fit(std::cout, f);
  if (fits.size() > 1) print_comparison(std::cout, fits);
  if (toughness) {
    compute_toughness(*toughness, fits);
    print_toughness(std::cout, *toughness, fits);
  }
  write_outputs(output_dir, curves, fits, toughness.get());
  std::cout << "wrote " << output_dir << "/ (parameters_*.csv, residuals_*.csv, material_*.yaml, curves.csv"
            << (fits.size() > 1 ? ", comparison.csv" : "") << (toughness ? ", toughness.csv" : "") << ")\n";
  if (plot) {
    std::cout.flush(); // (the script's lines after ours)
    const std::string cmd = "/usr/bin/python3 '" + plot_script + "' '" + output_dir + "'";
    if (std::system(cmd.c_str()) != 0)
      throw FitError("the plot failed (" + cmd + "); the fit's files are written; rerun with -no_plot to skip the PNGs");
  }
  int status = 0;
  for (std::size_t k = 0; k < fits.size(); ++k) {
    const std::string problem = !fits[k].problem.empty() ? fits[k].problem
                                : toughness             ? toughness->per_law[k].problem // (its material is written, without failure:)
                                                        : "";
    if (!problem.empty()) {
      std::cerr << "bapd-fit: error: -law " << fits[k].law.name << ": " << problem << "\n";
      status = 1;
    }
  }
  return status;
}

} // namespace

int main(int argc, char **argv)
{
  try {
    return run(argc, argv);
  } catch (const FitError &e) {
    std::cerr << "bapd-fit: error: " << e.what() << "\n";
    return 1;
  }
}
