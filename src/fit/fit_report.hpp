#pragma once
// What bapd-fit writes (into its output directory, and a summary on stdout):
//   parameters_<law>.csv   name, value, standard error, unit
//   residuals_<law>.csv    file, mode, stretch, data, fit, fit - data [Pa]
//   material_<law>.yaml    the scene's material: section (include it in a scene), and
//                          with a notched curve its failure: section (toughness.hpp)
//   toughness.csv          (a notched curve) lambda_c and each law's Gamma +- uncertainty
//   data.csv, curves.csv   the data and every law's response on a fine stretch grid,
//                          for scripts/plot_fit.py, which draws fit_<mode>.png
//   comparison.csv         (several laws) RMS error and AIC per law, best first
#include <ostream>
#include <string>
#include <vector>

#include "fit_run.hpp"
#include "toughness.hpp"

namespace bapd::fit {

void print_fit(std::ostream &out, const LawFit &fit);
void print_comparison(std::ostream &out, const std::vector<LawFit> &fits);
// Writes every file above (the PNGs excepted); throws FitError if a file cannot be written.
// curves: the fitted ones; toughness: the notched test, or nullptr.
void write_outputs(const std::string &dir, const std::vector<Curve> &curves, const std::vector<LawFit> &fits,
                   const ToughnessTest *toughness = nullptr);

} // namespace bapd::fit
