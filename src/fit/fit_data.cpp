// Reading and checking one test curve (fit_data.hpp).
#include "fit_data.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "export_table.hpp"
#include "fit_error.hpp"
#include "number_text.hpp"

namespace bapd::fit {
namespace {

struct Line {
  int         number;
  std::string text;
};

// The first column of the first quantity in `order` that the header has; -1 if none.
int pick(const std::vector<ColumnName> &columns, std::initializer_list<Quantity> order)
{
  for (Quantity q : order)
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i].quantity == q) return static_cast<int>(i);
  return -1;
}

bool all_numbers(const std::vector<std::string> &cells)
{
  double v     = 0.0;
  bool   any   = false;
  for (const std::string &c : cells) {
    if (c.empty()) continue;
    if (!parse_number(c, v)) return false;
    any = true;
  }
  return any;
}

// How a column's values become SI: the factor of its unit; throws naming the column.
double column_factor(const std::string &path, const ColumnName &c)
{
  const std::string n = c.name;
  if ((c.quantity == Quantity::stress || c.quantity == Quantity::strain) &&
      (n.find("true") != std::string::npos || n.find("cauchy") != std::string::npos || n.find("hencky") != std::string::npos ||
       n.find("logarithmic") != std::string::npos))
    throw FitError(path + ": column '" + c.label + "': bapd-fit fits the nominal (engineering) stress against the stretch; "
                          "export the nominal stress or the force, and the engineering strain or the extension");
  const double factor = si_factor(c.quantity, c.unit);
  if (factor > 0.0) return factor;
  const char *example = c.quantity == Quantity::extension ? "'Extension (mm)'"
                        : c.quantity == Quantity::force   ? "'Load (N)'"
                        : c.quantity == Quantity::strain  ? "'Strain (%)'"
                                                          : "'nominal_stress_kPa' or 'Stress (kPa)'";
  if (c.quantity == Quantity::stretch)
    throw FitError(path + ": column '" + c.label + "': a stretch has no unit (" + c.unit + "?); name the column stretch");
  if (c.unit.empty())
    throw FitError(path + ": column '" + c.label + "' (" + to_string(c.quantity) + ") needs its unit in the header, e.g. " +
                   example + " (" + known_units(c.quantity) + ")");
  throw FitError(path + ": column '" + c.label + "': '" + c.unit + "' is not a unit of " + to_string(c.quantity) +
                 " bapd-fit reads (" + known_units(c.quantity) + ")");
}


// The lines that are not blank or comments; the "# mode:" line's value into file_mode.
std::vector<Line> read_lines(const std::string &path, std::string &file_mode)
{
  std::ifstream in(path);
  if (!in) throw FitError(path + ": cannot open the data file; give CSV files of stretch and nominal stress, or exports of extension and force");
  std::string       text;
  std::vector<Line> lines;
  for (int number = 1; std::getline(in, text); ++number) {
    if (number == 1 && text.rfind("\xef\xbb\xbf", 0) == 0) text.erase(0, 3); // a UTF-8 byte-order mark
    if (text.find('\0') != std::string::npos)
      throw FitError(path + ": the file is UTF-16 text (it holds zero bytes); save the export as UTF-8 or ANSI CSV");
    const std::string t = trim(text);
    if (t.empty()) continue;
    if (t[0] == '#') {
      const std::string body = lower(trim(t.substr(1)));
      if (body.rfind("mode:", 0) == 0) file_mode = trim(t.substr(t.find(':') + 1));
      continue;
    }
    lines.push_back({number, t});
  }
  return lines;
}

// The header's columns and where the data starts.
struct Header {
  std::size_t             first_row = 0; // index into the lines of the first data row
  char                    separator = ',';
  std::vector<ColumnName> columns;
  int                     deformation = -1, load = -1;
};

// A row of units under the header ("(s),(mm),(N)") gives the columns that have none
// their unit; returns whether the row was one.
bool read_unit_row(const std::vector<std::string> &cells, std::vector<ColumnName> &columns)
{
  bool units = !all_numbers(cells), any = false;
  for (const std::string &cell : cells) {
    if (cell.empty()) continue;
    any = true;
    if (unit_cell(cell).empty()) units = false;
  }
  if (!units || !any) return false;
  for (std::size_t i = 0; i < columns.size() && i < cells.size(); ++i)
    if (columns[i].unit.empty() && !cells[i].empty()) {
      columns[i].unit  = unit_cell(cells[i]);
      columns[i].label = columns[i].label + " (" + columns[i].unit + ")";
    }
  return true;
}

// The header: the first line with a deformation and a load column (the lines before it
// skipped with a note), and the row of units under it if there is one.
Header find_header(const std::string &path, const std::vector<Line> &lines, std::vector<std::string> &notes)
{
  Header            h;
  std::size_t      &at = h.first_row;
  const std::string no_header =
      path + ": no header line names a deformation column (stretch, strain or extension, e.g. 'Extension (mm)') and a load "
             "column (a stress named with its unit, e.g. nominal_stress_kPa, or a force, e.g. 'Load (N)')";
  for (; at < lines.size(); ++at) {
    h.separator                          = detect_separator(lines[at].text);
    const std::vector<std::string> cells = split_cells(lines[at].text, h.separator);
    if (all_numbers(cells) && at > 0) throw FitError(no_header + "; its first line is '" + lines[0].text + "'");
    if (all_numbers(cells))
      throw FitError(path + ":" + std::to_string(lines[at].number) + ": '" + lines[at].text +
                     "' is data before any header; the first line must name the columns, e.g. stretch,nominal_stress_kPa "
                     "or Time (s),Extension (mm),Load (N)");
    h.columns.clear();
    for (const std::string &cell : cells) h.columns.push_back(parse_column(cell));
    h.deformation = pick(h.columns, {Quantity::stretch, Quantity::strain, Quantity::extension});
    h.load        = pick(h.columns, {Quantity::stress, Quantity::force});
    if (h.deformation >= 0 && h.load >= 0) break;
  }
  if (at == lines.size())
    throw FitError(no_header + (lines.empty() ? std::string("; the file holds no line") : "; its first line is '" + lines[0].text + "'"));
  if (at > 0)
    notes.push_back("skipped " + std::to_string(at) + " line(s) before the header (line " + std::to_string(lines[at].number) + ")");
  ++at;
  if (at < lines.size() && read_unit_row(split_cells(lines[at].text, h.separator), h.columns)) ++at;
  return h;
}

// An extension needs the gauge length, a force the cross-section.
void check_specimen(const std::string &path, const ColumnName &dcol, const ColumnName &lcol, const Specimen &specimen)
{
  const std::string option_place = " (before the file on the command line)";
  if (dcol.quantity == Quantity::extension && !(specimen.gauge_length_m > 0.0))
    throw FitError(path + ": column '" + dcol.label + "' is the extension: give the specimen's gauge length at rest (the "
                          "clamps' separation) with -fit_gauge_length L in m, e.g. -fit_gauge_length 0.02 for 20 mm" + option_place);
  if (lcol.quantity == Quantity::force && !(specimen.cross_section_m2 > 0.0))
    throw FitError(path + ": column '" + lcol.label + "' is the force: give the specimen's cross-section at rest with "
                          "-fit_cross_section A in m^2 (e.g. 1e-5 for 10 mm^2) or -fit_width W -fit_thickness T in m" + option_place);
}

// The data rows as stretch and nominal stress [Pa] into c, each row's line number into
// line_of; returns whether a value had a decimal comma.
bool read_rows(const std::string &path, const std::vector<Line> &lines, const Header &h, const Specimen &specimen, Curve &c,
               std::vector<int> &line_of)
{
  const ColumnName &dcol = h.columns[h.deformation], &lcol = h.columns[h.load];
  const double      dfactor = column_factor(path, dcol), lfactor = column_factor(path, lcol);
  check_specimen(path, dcol, lcol, specimen);
  const int need          = std::max(h.deformation, h.load);
  bool      decimal_comma = false;
  for (std::size_t at = h.first_row; at < lines.size(); ++at) {
    const std::vector<std::string> cells = split_cells(lines[at].text, h.separator);
    const std::string              where = path + ":" + std::to_string(lines[at].number);
    if (static_cast<int>(cells.size()) <= need)
      throw FitError(where + ": '" + lines[at].text + "' has too few columns for the header");
    double v[2];
    int    cols[2] = {h.deformation, h.load};
    for (int k = 0; k < 2; ++k)
      if (!parse_number(cells[cols[k]], v[k]))
        throw FitError(where + ": column '" + h.columns[cols[k]].label + "': '" + cells[cols[k]] + "' is not a number" +
                       (cells[cols[k]].find(',') != std::string::npos && cells[cols[k]].find('.') != std::string::npos
                            ? " (thousands separators are not read: export without them)"
                            : ""));
    decimal_comma = decimal_comma || cells[h.deformation].find(',') != std::string::npos || cells[h.load].find(',') != std::string::npos;
    double lambda = v[0] * dfactor; // a stretch, or a strain
    if (dcol.quantity == Quantity::strain) lambda = 1.0 + lambda;
    else if (dcol.quantity == Quantity::extension) lambda = 1.0 + lambda / specimen.gauge_length_m;
    double P = v[1] * lfactor;
    if (lcol.quantity == Quantity::force) P /= specimen.cross_section_m2;
    c.stretch.push_back(lambda);
    c.stress_Pa.push_back(P);
    line_of.push_back(lines[at].number);
  }
  return decimal_comma;
}

// The note that says how the columns became stretch and nominal stress ("" when they
// were already).
std::string conversion_note(const Header &h, const Specimen &specimen, bool decimal_comma)
{
  const ColumnName &dcol = h.columns[h.deformation], &lcol = h.columns[h.load];
  if (dcol.quantity == Quantity::stretch && lcol.quantity == Quantity::stress) return "";
  std::string how = "stretch = ";
  how += dcol.quantity == Quantity::stretch  ? "'" + dcol.label + "'"
         : dcol.quantity == Quantity::strain ? "1 + '" + dcol.label + "'"
                                             : "1 + '" + dcol.label + "' / gauge length " + number_text(specimen.gauge_length_m, 6) + " m";
  how += ", nominal stress = ";
  how += lcol.quantity == Quantity::stress ? "'" + lcol.label + "'"
                                           : "'" + lcol.label + "' / cross-section " + number_text(specimen.cross_section_m2, 6) + " m^2";
  const char separator = h.separator;
  if (separator != ',' || decimal_comma)
    how += std::string(" (") + (separator == ';' ? "';'-separated" : separator == '\t' ? "tab-separated" : "comma-separated") +
           (decimal_comma ? ", decimal commas)" : ")");
  return how;
}

// Loading starts at the first row in tension that carries stress; the rows before it
// (the rest point, a slack or a preload) are not part of the curve: dropped with a note.
std::size_t drop_before_loading(Curve &c, std::vector<int> &line_of)
{
  std::size_t start = 0;
  while (start < c.stretch.size() && !(c.stretch[start] > 1.0 && c.stress_Pa[start] > 0.0)) ++start;
  if (start > 0) {
    c.notes.push_back("dropped " + std::to_string(start) + " row(s) before loading starts (line" +
                      (start > 1 ? "s " + std::to_string(line_of[0]) + "-" : " ") + std::to_string(line_of[start - 1]) +
                      ": stretch <= 1 or stress <= 0, as at rest)");
    c.stretch.erase(c.stretch.begin(), c.stretch.begin() + start);
    c.stress_Pa.erase(c.stress_Pa.begin(), c.stress_Pa.begin() + start);
    line_of.erase(line_of.begin(), line_of.begin() + start);
  }
  return start;
}

// At least 2 points once loading starts, stretches > 1 that increase strictly, no
// negative stress (a notched curve's past its largest stress: the cut sheet, read as is).
void check_loading_branch(const std::string &path, const Curve &c, const std::vector<int> &line_of, std::size_t dropped)
{
  const std::size_t peak = static_cast<std::size_t>(std::max_element(c.stress_Pa.begin(), c.stress_Pa.end()) - c.stress_Pa.begin());
  if (c.stretch.size() < 2)
    throw FitError(path + ": " + std::to_string(c.stretch.size()) + " data point(s)" +
                   (dropped > 0 ? " once the " + std::to_string(dropped) + " row(s) before loading starts are dropped" : "") +
                   "; a curve needs at least 2");
  for (std::size_t i = 0; i < c.stretch.size(); ++i) {
    std::ostringstream at_line;
    at_line << path << ":" << line_of[i] << ": stretch " << c.stretch[i];
    if (!(c.stretch[i] > 1.0))
      throw FitError(at_line.str() + ": a " + to_string(c.mode) +
                     " test in tension has stretches > 1 once loading starts; drop the compression or unloading rows");
    if (i > 0 && !(c.stretch[i] > c.stretch[i - 1]))
      throw FitError(at_line.str() + ": the stretch must increase strictly down the file (loading branch only; sort it, "
                                     "drop repeated or unloading points)");
    if (c.stress_Pa[i] < 0.0 && !(c.notched && i > peak))
      throw FitError(at_line.str() + ": negative nominal stress " + number_text(c.stress_Pa[i], 6) +
                     " Pa in tension; check the sign and the offset of the load cell");
  }
}
} // namespace

namespace {
std::string mode_word(const std::string &text)
{
  std::string t = lower(trim(text));
  std::replace(t.begin(), t.end(), '-', '_');
  std::replace(t.begin(), t.end(), ' ', '_');
  return t;
}
} // namespace

bool parse_mode(const std::string &text, LoadMode &mode) { return load_mode_words.parse(mode_word(text), mode); }

bool parse_test(const std::string &text, LoadMode &mode, bool &notched)
{
  notched = mode_word(text) == "notched_pure_shear";
  if (notched) mode = LoadMode::pure_shear;
  return notched || parse_mode(text, mode);
}

Curve read_curve(const std::string &path, const std::string &mode_tag, const Specimen &specimen)
{
  Curve c;
  c.file           = path;
  c.gauge_length_m = specimen.gauge_length_m;
  std::string             file_mode;
  const std::vector<Line> lines = read_lines(path, file_mode);
  const Header            header = find_header(path, lines, c.notes);
  std::vector<int>        line_of;
  const bool              decimal_comma = read_rows(path, lines, header, specimen, c, line_of);
  const std::string       how           = conversion_note(header, specimen, decimal_comma);
  if (!how.empty()) c.notes.push_back(how);

  const std::string mode_text = mode_tag.empty() ? file_mode : mode_tag;
  if (mode_text.empty())
    throw FitError(path + ": which test is it? add a line '# mode: uniaxial' (or pure_shear, equibiaxial, notched_pure_shear) or tag the "
                          "file on the command line, e.g. pure_shear:" + path);
  if (!parse_test(mode_text, c.mode, c.notched))
    throw FitError(path + ": mode '" + mode_text + "' is not a test: choose uniaxial, pure_shear or equibiaxial (or "
                          "notched_pure_shear: a notched sheet's curve, for the toughness)");

  const std::size_t dropped = drop_before_loading(c, line_of);
  check_loading_branch(path, c, line_of, dropped);
  return c;
}

} // namespace bapd::fit
