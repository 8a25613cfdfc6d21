// bapd-fit's outputs (fit_report.hpp).
#include "fit_report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fit_error.hpp"
#include "number_text.hpp"

namespace bapd::fit {
namespace {

std::ofstream open(const std::string &path)
{
  std::ofstream f(path);
  if (!f) throw FitError(path + ": cannot write; give a writable -output_dir");
  return f;
}

std::vector<const LawFit *> by_aic(const std::vector<LawFit> &fits)
{
  std::vector<const LawFit *> order;
  for (const LawFit &f : fits)
    if (f.problem.empty()) order.push_back(&f);
  std::stable_sort(order.begin(), order.end(), [](const LawFit *a, const LawFit *b) { return a->aic < b->aic; });
  for (const LawFit &f : fits)
    if (!f.problem.empty()) order.push_back(&f);
  return order;
}

} // namespace

void print_fit(std::ostream &out, const LawFit &fit)
{
  out << "law " << fit.law.name << ": " << fit.points << " points, " << fit.law.parameters.size() << " parameters";
  if (!fit.problem.empty()) {
    out << ": no fit (" << fit.problem << ")\n";
    return;
  }
  out << ", " << fit.ls.iterations << " iterations\n";
  for (std::size_t j = 0; j < fit.law.parameters.size(); ++j)
    out << "  " << fit.law.parameters[j] << " = " << number_text(fit.ls.p[j], 6) << " +- " << number_text(fit.ls.standard_error[j], 2) << " "
        << fit.law.units[j] << "\n";
  out << "  RMS error " << number_text(fit.rms_Pa, 4) << " Pa, weighted RMS " << number_text(fit.rms_weighted, 4) << ", AIC " << number_text(fit.aic, 6) << "\n";
}

void print_comparison(std::ostream &out, const std::vector<LawFit> &fits)
{
  char line[256];
  out << "comparison (best AIC first; AIC = m ln(weighted SSR / m) + 2 k, lower is better):\n";
  std::snprintf(line, sizeof line, "  %-14s %3s %12s %12s %10s %9s\n", "law", "k", "RMS_Pa", "weighted_RMS", "AIC", "dAIC");
  out << line;
  const std::vector<const LawFit *> order = by_aic(fits);
  const double best = order.empty() || !order[0]->problem.empty() ? 0.0 : order[0]->aic;
  for (const LawFit *f : order) {
    if (f->problem.empty())
      std::snprintf(line, sizeof line, "  %-14s %3zu %12.4g %12.4g %10.2f %9.2f\n", f->law.name.c_str(), f->law.parameters.size(),
                    f->rms_Pa, f->rms_weighted, f->aic, f->aic - best);
    else std::snprintf(line, sizeof line, "  %-14s %3zu  no fit: see above\n", f->law.name.c_str(), f->law.parameters.size());
    out << line;
  }
}

void write_outputs(const std::string &dir, const std::vector<Curve> &curves, const std::vector<LawFit> &fits,
                   const ToughnessTest *toughness)
{
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw FitError("-output_dir " + dir + ": cannot create it (" + ec.message() + ")");
  {
    std::ofstream f = open(dir + "/data.csv");
    f << "file,mode,stretch,nominal_stress_Pa\n";
    for (const Curve &c : curves)
      for (std::size_t k = 0; k < c.stretch.size(); ++k)
        f << c.file << "," << to_string(c.mode) << "," << number_text(c.stretch[k], 12) << "," << number_text(c.stress_Pa[k], 12) << "\n";
    if (toughness)
      for (std::size_t k = 0; k < toughness->notched.stretch.size(); ++k)
        f << toughness->notched.file << ",notched_pure_shear," << number_text(toughness->notched.stretch[k], 12) << ","
          << number_text(toughness->notched.stress_Pa[k], 12) << "\n";
  }
  if (toughness) {
    std::ofstream f = open(dir + "/toughness.csv");
    f << "law,onset_stretch,onset_stretch_uncertainty,gauge_length_m,energy_density_J_m3,fracture_energy_J_m2,"
         "fracture_energy_uncertainty_J_m2\n";
    for (std::size_t k = 0; k < fits.size(); ++k) {
      const Toughness &t = toughness->per_law[k];
      if (!t.problem.empty()) continue;
      f << fits[k].law.name << "," << number_text(toughness->onset.stretch, 12) << "," << number_text(toughness->onset.uncertainty, 6)
        << "," << number_text(toughness->H0, 12) << "," << number_text(t.energy_J_m3, 12) << "," << number_text(t.gamma_J_m2, 12) << ","
        << number_text(t.uncertainty_J_m2, 6) << "\n";
    }
  }
  std::ofstream curves_csv = open(dir + "/curves.csv");
  curves_csv << "law,mode,stretch,nominal_stress_Pa\n";
  for (const LawFit &fit : fits) {
    if (!fit.problem.empty()) continue;
    const std::string &name = fit.law.name;
    {
      std::ofstream f = open(dir + "/parameters_" + name + ".csv");
      f << "parameter,value,standard_error,unit\n";
      for (std::size_t j = 0; j < fit.law.parameters.size(); ++j)
        f << fit.law.parameters[j] << "," << number_text(fit.ls.p[j], 12) << "," << number_text(fit.ls.standard_error[j], 6) << "," << fit.law.units[j] << "\n";
    }
    {
      std::ofstream f = open(dir + "/residuals_" + name + ".csv");
      f << "file,mode,stretch,data_stress_Pa,fit_stress_Pa,residual_Pa\n";
      std::size_t i = 0;
      for (const Curve &c : curves)
        for (std::size_t k = 0; k < c.stretch.size(); ++k, ++i)
          f << c.file << "," << to_string(c.mode) << "," << number_text(c.stretch[k], 12) << "," << number_text(c.stress_Pa[k], 12) << ","
            << number_text(fit.fitted[i], 12) << "," << number_text(fit.fitted[i] - c.stress_Pa[k], 6) << "\n";
    }
    {
      std::ofstream f = open(dir + "/material_" + name + ".yaml");
      f << "# bapd-fit: " << name << " fitted to";
      for (const Curve &c : curves) f << " " << c.file << " (" << to_string(c.mode) << ")";
      f << "\n# RMS error " << number_text(fit.rms_Pa, 4) << " Pa. Include it after the scene: -options_file_yaml scene.yaml "
        << "-options_file_yaml material_" << name << ".yaml\n"
        << fit.law.yaml(fit.ls.p);
      const std::size_t k = static_cast<std::size_t>(&fit - fits.data());
      if (toughness && toughness->per_law[k].problem.empty() && fit.law.in_bapd) f << failure_yaml(*toughness, toughness->per_law[k]);
    }
    for (const Curve &c : curves) {
      const double top = c.stretch.back();
      for (int s = 0; s <= 200; ++s) {
        const double lambda = 1.0 + (top - 1.0) * s / 200.0;
        double       P      = 0.0;
        if (fit.law.stress(fit.ls.p, c.mode, lambda, P))
          curves_csv << name << "," << to_string(c.mode) << "," << number_text(lambda, 8) << "," << number_text(P, 10) << "\n";
      }
    }
  }
  if (fits.size() > 1) {
    std::ofstream f = open(dir + "/comparison.csv");
    f << "law,parameters,rms_Pa,weighted_rms,aic,status\n";
    for (const LawFit *fit : by_aic(fits))
      f << fit->law.name << "," << fit->law.parameters.size() << "," << number_text(fit->rms_Pa, 6) << "," << number_text(fit->rms_weighted, 6) << ","
        << number_text(fit->aic, 8) << "," << (fit->problem.empty() ? "ok" : "no fit") << "\n";
  }
}

} // namespace bapd::fit
