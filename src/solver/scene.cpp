// Scene configuration: every option of a run, read in one PetscOptionsBegin block
// per component (so -help lists them with units and defaults), then checked as a
// whole before any work is done. Each rejected value gets one message that names
// the option and the fix. Every name read is remembered, so that an option nobody
// read (a typo) can be answered with the nearest real one (CheckUnusedOptions).
//
// Reading and checking are separate passes: with -help every block is listed even
// when the scene is incomplete, and the checks, which need the whole scene (a probe
// must lie in the body, a stretch grip needs a schedule), see it all at once.
#include "bapd/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "bapd/option_suggest.hpp"

namespace bapd {

namespace {

// ---------------------------------------------------------------------------------
// Small text helpers

std::string Lower(std::string s)
{
  for (char &c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string Format(const char *format, ...) __attribute__((format(printf, 1, 2)));
std::string Format(const char *format, ...)
{
  va_list args, copy;
  va_start(args, format);
  va_copy(copy, args);
  const int   length = std::vsnprintf(nullptr, 0, format, copy);
  std::string text(length > 0 ? static_cast<std::size_t>(length) : 0, '\0');
  if (length > 0) std::vsnprintf(text.data(), text.size() + 1, format, args);
  va_end(copy);
  va_end(args);
  return text;
}

std::vector<std::string> SplitList(const std::string &text)
{
  std::vector<std::string> items;
  if (text.empty()) return items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

// strtod/strtoll over the whole text, finite values only: what PETSc's own parsers
// accept for a plain number, so a text that passes here never trips them.
bool ParseReal(const std::string &text, double *value)
{
  if (text.empty()) return false;
  char        *end = nullptr;
  const double v   = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

bool ParseInt(const std::string &text, PetscInt *value)
{
  if (text.empty()) return false;
  char           *end = nullptr;
  const long long v   = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0') return false;
  if (v < std::numeric_limits<PetscInt>::min() || v > std::numeric_limits<PetscInt>::max()) return false;
  *value = static_cast<PetscInt>(v);
  return true;
}

// Load set and probe names become parts of option names (-load_NAME_region).
bool IsName(const std::string &name)
{
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// ---------------------------------------------------------------------------------
// Registry of every option name bapd reads (lower case -> spelling as documented),
// warnings of the last SceneFromOptions.

std::map<std::string, std::string> &Registry()
{
  static std::map<std::string, std::string> names;
  return names;
}

std::vector<std::string> &Warnings()
{
  static std::vector<std::string> warnings;
  return warnings;
}

PetscErrorCode Warn(MPI_Comm comm, const std::string &message, bool loud = false)
{
  PetscFunctionBeginUser;
  Warnings().push_back(message);
  if (loud) PetscCall(PetscFPrintf(comm, PETSC_STDERR, "\nbapd: WARNING: %s\n\n", message.c_str()));
  else PetscCall(PetscFPrintf(comm, PETSC_STDERR, "bapd: warning: %s\n", message.c_str()));
  PetscFunctionReturn(0);
}

// ---------------------------------------------------------------------------------
// Reading: one OptionReader per PetscOptionsBegin block. Each call registers the
// name, checks that the text is well formed (so a malformed number is reported
// naming its option, not as PETSc's "Input string has no numeric value"), and then
// reads it through PETSc so that -help lists it. The first malformed value is kept
// and reported after the block.

class OptionReader {
public:
  explicit OptionReader(PetscOptionItems *items) : items_(items) {}
  const std::string &problem() const { return problem_; }

  PetscErrorCode Real(const char *name, const char *help, double *value, bool *set = nullptr)
  {
    PetscOptionItems *PetscOptionsObject = items_;
    std::string       text;
    bool              present = false;
    PetscFunctionBeginUser;
    PetscCall(Raw(name, &text, &present));
    double parsed = 0;
    if (present && text.empty()) {
      Fail(Format("%s needs a value: give a number in SI units, e.g. %s 0.01", Full(name).c_str(), Full(name).c_str()));
      PetscFunctionReturn(0);
    }
    if (present && !ParseReal(text, &parsed)) {
      Fail(Format("%s '%s' is not a number: give one value in SI units, e.g. %s 0.01", Full(name).c_str(), text.c_str(),
                  Full(name).c_str()));
      PetscFunctionReturn(0);
    }
    PetscReal v = *value;
    PetscBool flg = PETSC_FALSE;
    PetscCall(PetscOptionsReal(name, help, "docs/options.md", *value, &v, &flg));
    *value = v;
    if (set) *set = flg;
    PetscFunctionReturn(0);
  }

  PetscErrorCode Int(const char *name, const char *help, PetscInt *value, bool *set = nullptr)
  {
    PetscOptionItems *PetscOptionsObject = items_;
    std::string       text;
    bool              present = false;
    PetscFunctionBeginUser;
    PetscCall(Raw(name, &text, &present));
    PetscInt parsed = 0;
    if (present && text.empty()) {
      Fail(Format("%s needs a value: give a whole number, e.g. %s 10", Full(name).c_str(), Full(name).c_str()));
      PetscFunctionReturn(0);
    }
    if (present && !ParseInt(text, &parsed)) {
      Fail(Format("%s '%s' is not a whole number: give an integer, e.g. %s 10", Full(name).c_str(), text.c_str(), Full(name).c_str()));
      PetscFunctionReturn(0);
    }
    PetscBool flg = PETSC_FALSE;
    PetscCall(PetscOptionsInt(name, help, "docs/options.md", *value, value, &flg));
    if (set) *set = flg;
    PetscFunctionReturn(0);
  }

  PetscErrorCode String(const char *name, const char *help, std::string *value, bool *set = nullptr)
  {
    PetscOptionItems *PetscOptionsObject = items_;
    std::string       text;
    bool              present = false;
    PetscFunctionBeginUser;
    PetscCall(Raw(name, &text, &present));
    char      buffer[PETSC_MAX_PATH_LEN];
    PetscBool flg = PETSC_FALSE;
    PetscCall(PetscStrncpy(buffer, value->c_str(), sizeof(buffer)));
    PetscCall(PetscOptionsString(name, help, "docs/options.md", value->c_str(), buffer, sizeof(buffer), &flg));
    if (flg) *value = buffer;
    if (set) *set = flg;
    PetscFunctionReturn(0);
  }

  PetscErrorCode RealArray(const char *name, const char *help, std::vector<double> *values, bool *set = nullptr)
  {
    PetscOptionItems *PetscOptionsObject = items_;
    std::string       text;
    bool              present = false;
    PetscFunctionBeginUser;
    PetscCall(Raw(name, &text, &present));
    const std::vector<std::string> items = SplitList(text);
    for (const std::string &item : items) {
      double parsed = 0;
      if (!ParseReal(item, &parsed)) {
        Fail(Format("%s '%s': '%s' is not a number: give comma-separated numbers in SI units (YAML: a list [a, b, ...])",
                    Full(name).c_str(), text.c_str(), item.c_str()));
        PetscFunctionReturn(0);
      }
    }
    // PETSc reads at most n values: size the buffer from the text. Absent, it holds
    // the current values, which -help shows.
    std::vector<PetscReal> buffer(present ? items.size() : values->size());
    if (!present) std::copy(values->begin(), values->end(), buffer.begin());
    PetscInt n = static_cast<PetscInt>(buffer.size());
    buffer.push_back(0.0); // never empty: -help prints the first entry
    PetscBool flg = PETSC_FALSE;
    PetscCall(PetscOptionsRealArray(name, help, "docs/options.md", buffer.data(), &n, &flg));
    if (flg) values->assign(buffer.begin(), buffer.begin() + n);
    if (set) *set = flg;
    PetscFunctionReturn(0);
  }

  PetscErrorCode StringArray(const char *name, const char *help, std::vector<std::string> *values, bool *set = nullptr)
  {
    PetscOptionItems *PetscOptionsObject = items_;
    std::string       text;
    bool              present = false;
    PetscFunctionBeginUser;
    PetscCall(Raw(name, &text, &present));
    const std::vector<std::string> items = SplitList(text);
    std::vector<char *>            buffer(items.size() + 1, nullptr);
    PetscInt                       n   = static_cast<PetscInt>(items.size());
    PetscBool                      flg = PETSC_FALSE;
    PetscCall(PetscOptionsStringArray(name, help, "docs/options.md", buffer.data(), &n, &flg));
    if (flg) {
      values->clear();
      for (PetscInt i = 0; i < n; ++i) {
        values->push_back(buffer[i] ? buffer[i] : "");
        PetscCall(PetscFree(buffer[i]));
      }
    }
    if (set) *set = flg;
    PetscFunctionReturn(0);
  }

private:
  std::string Full(const char *name) const
  {
    return std::string("-") + (items_->prefix ? items_->prefix : "") + (name + 1);
  }
  void Fail(const std::string &message)
  {
    if (problem_.empty()) problem_ = message;
  }
  // Registers the name; returns the text the database holds for it.
  PetscErrorCode Raw(const char *name, std::string *text, bool *present)
  {
    PetscFunctionBeginUser;
    RegisterOptionName(Full(name));
    const char *value = nullptr;
    PetscBool   flg   = PETSC_FALSE;
    PetscCall(PetscOptionsFindPair(items_->options, items_->prefix, name, &value, &flg));
    *present = flg;
    *text    = value ? value : "";
    PetscFunctionReturn(0);
  }

  PetscOptionItems *items_;
  std::string       problem_;
};

// What the options said, beyond the values that go straight into the Scene: which
// were given, and the raw text of lists and choices, for the checks.
struct LoadInput {
  std::string         name, region, x = "free", y = "free";
  bool                region_set = false, box_set = false, layers_set = false, x_scale_set = false, y_scale_set = false;
  std::vector<double> box;
  PetscInt            layers  = 1;
  double              x_scale = 1.0, y_scale = 1.0;
};

struct ProbeInput {
  std::string         name;
  std::vector<double> at;
  bool                at_set = false;
};

struct SceneInput {
  bool                     width_set = false, height_set = false, thickness_set = false, dx_set = false;
  std::vector<double>      holes, notches;
  std::string              model = "gent", formulation = "plane_stress", force_form = "bond_only";
  bool                     D_set = false, bulk_ratio_set = false;
  double                   bulk_ratio = 1000.0;
  bool                     critical_stretch_set = false;
  std::vector<std::string> load_names;
  std::vector<LoadInput>   loads;
  std::vector<double>      schedule;
  bool                     schedule_set = false, reference_length_set = false;
  std::vector<std::string> probe_names;
  std::vector<ProbeInput>  probes;
  bool                     end_time_set = false;
};

// PetscCheck with the message formatted by the C library: PETSc's printf writes
// 4550 as "4550.", which reads oddly in a message about an option value.
#define SceneCheck(cond, comm, ...) PetscCheck(cond, comm, PETSC_ERR_USER, "%s", Format(__VA_ARGS__).c_str())

#define BAPD_CHECK_READ(reader_problem, comm) \
  PetscCheck((reader_problem).empty(), comm, PETSC_ERR_USER, "%s", (reader_problem).c_str())

PetscErrorCode ReadBody(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  Body2D     &b = scene->body;
  std::string problem;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Body: a plane sheet [0, width] x [0, height] cut by holes and notches", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.Real("-body_width", "Sheet width along x [m] (required)", &b.width, &in->width_set));
    PetscCall(r.Real("-body_height", "Sheet height along y [m] (required)", &b.height, &in->height_set));
    PetscCall(r.Real("-body_thickness", "Sheet thickness [m] (required)", &b.thickness, &in->thickness_set));
    PetscCall(r.Real("-body_dx", "Lattice spacing of the material points [m] (required)", &b.dx, &in->dx_set));
    PetscCall(r.RealArray("-body_holes", "Circular holes cx,cy,r,cx,cy,r,... [m] (default: none)", &in->holes));
    PetscCall(r.RealArray("-body_notches", "Pre-notch segments x0,y0,x1,y1,... [m]; bonds crossing one are never created (default: none)", &in->notches));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);

  PetscOptionsBegin(comm, nullptr, "Horizon", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.Real("-horizon_factor", "Horizon over lattice spacing, delta/dx [-] (paper: 3.015; 2.515 and 3.515 also studied)",
                     &scene->horizon_factor));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);
  PetscFunctionReturn(0);
}

PetscErrorCode ReadMaterial(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  MaterialParameters &m = scene->material;
  std::string         problem;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Material", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.String("-material_model", "Constitutive model: gent | neo_hookean (neo-hookean also accepted)", &in->model));
    PetscCall(r.String("-material_formulation", "2D reduction: plane_stress | plane_strain", &in->formulation));
    PetscCall(r.String("-force_form",
                       "Bond force: bond_only (the paper's eq 23) | energy_consistent (minus the gradient of the strain "
                       "energy: conserves energy undamped)",
                       &in->force_form));
    PetscCall(r.Real("-material_mu", "Shear modulus mu [Pa] (paper: 4.55e3)", &m.mu));
    PetscCall(r.Real("-material_Jm", "Gent chain-extension limit Jm [-] (paper: 162.6; unused by neo_hookean)", &m.Jm));
    // Default compressibility: bulk modulus K = 2/D = 1000 mu (METHOD.md section 4:
    // the paper gives no D). K = 100 mu already softens the pure-shear curve by 7 %
    // at stretch 5.125 (the sheet thins less); 1000 mu keeps it within 1 %, and in
    // plane stress a stiffer K does not shrink the stable step at rest.
    m.D = 2.0 / (in->bulk_ratio * m.mu);
    PetscCall(r.Real("-material_D", "Compressibility D [1/Pa]; bulk modulus K = 2/D (default 2/(1000 mu), i.e. K = 1000 mu)", &m.D, &in->D_set));
    PetscCall(r.Real("-material_bulk_ratio", "Bulk to shear modulus ratio K/mu [-]; sets D = 2/(ratio mu) (give this or -material_D)",
                     &in->bulk_ratio, &in->bulk_ratio_set));
    PetscCall(r.Real("-material_density", "Mass density [kg/m^3]", &scene->density));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);

  PetscOptionsBegin(comm, nullptr, "Failure (no option: bonds never break)", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.Real("-failure_critical_stretch", "Critical bond stretch s_c [-], > 1 (paper: 7.2); absent: no failure",
                     &scene->critical_stretch, &in->critical_stretch_set));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckNames(MPI_Comm comm, const std::vector<std::string> &names, const char *option, const char *what)
{
  PetscFunctionBeginUser;
  for (std::size_t i = 0; i < names.size(); ++i) {
    SceneCheck(IsName(names[i]), comm,
               "%s: %s name '%s' must start with a letter and hold only letters, digits and '_' (it becomes part of option names)",
               option, what, names[i].c_str());
    for (std::size_t j = 0; j < i; ++j)
      SceneCheck(Lower(names[i]) != Lower(names[j]), comm, "%s lists %s '%s' twice: give each %s a different name", option,
                 what, names[i].c_str(), what);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ReadLoading(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  std::string problem;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Loading: grips (load sets) following a stretch schedule", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.StringArray("-load_sets", "Names of the load sets name1,name2,... (each set S is configured by -load_S_...)", &in->load_names));
    PetscCall(r.RealArray("-load_schedule", "Stretch schedule t0,lambda0,t1,lambda1,... [s, -], piecewise linear (default: none)", &in->schedule,
                          &in->schedule_set));
    PetscCall(r.Real("-load_reference_length", "Length L in u = scale (lambda - 1) L [m] (default: body height)", &scene->reference_length,
                     &in->reference_length_set));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);
  PetscCall(CheckNames(comm, in->load_names, "-load_sets", "load set"));

  for (const std::string &name : in->load_names) {
    LoadInput         set;
    const std::string prefix = "load_" + name + "_";
    const std::string title  = "Load set " + name;
    set.name                 = name;
    PetscOptionsBegin(comm, prefix.c_str(), title.c_str(), "bapd");
    {
      OptionReader r(PetscOptionsObject);
      PetscCall(r.String("-region", "Points held: top | bottom | left | right (edge layers) | box (required)", &set.region, &set.region_set));
      PetscCall(r.RealArray("-box", "Region box xmin,ymin,xmax,ymax [m] (region box)", &set.box, &set.box_set));
      PetscCall(r.Int("-layers", "Point layers taken from the edge, each dx thick [-]", &set.layers, &set.layers_set));
      PetscCall(r.String("-x", "x component: free | fixed (u = 0) | stretch (follows the schedule)", &set.x));
      PetscCall(r.String("-y", "y component: free | fixed (u = 0) | stretch (follows the schedule)", &set.y));
      PetscCall(r.Real("-x_scale", "Scale of a stretch x component: u = scale (lambda - 1) L [-]", &set.x_scale, &set.x_scale_set));
      PetscCall(r.Real("-y_scale", "Scale of a stretch y component: u = scale (lambda - 1) L [-]", &set.y_scale, &set.y_scale_set));
      problem = r.problem();
    }
    PetscOptionsEnd();
    BAPD_CHECK_READ(problem, comm);
    in->loads.push_back(set);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ReadProbesOutputTime(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  std::string problem;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Probes: points whose displacement is recorded", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.StringArray("-probes", "Names of the probes name1,name2,... (each probe P is placed by -probe_P_at)", &in->probe_names));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);
  PetscCall(CheckNames(comm, in->probe_names, "-probes", "probe"));
  for (const std::string &name : in->probe_names) {
    ProbeInput        probe;
    const std::string prefix = "probe_" + name + "_";
    const std::string title  = "Probe " + name;
    probe.name               = name;
    PetscOptionsBegin(comm, prefix.c_str(), title.c_str(), "bapd");
    {
      OptionReader r(PetscOptionsObject);
      PetscCall(r.RealArray("-at", "Position x,y [m]; the nearest material point is recorded (required)", &probe.at, &probe.at_set));
      problem = r.problem();
    }
    PetscOptionsEnd();
    BAPD_CHECK_READ(problem, comm);
    in->probes.push_back(probe);
  }

  PetscOptionsBegin(comm, nullptr, "Output", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.String("-output_dir", "Directory for history and fields", &scene->output_dir));
    PetscCall(r.Int("-output_interval", "Time steps between history rows [-], >= 1", &scene->output_interval));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);

  PetscOptionsBegin(comm, nullptr, "Time stepping (explicit dynamics)", "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(r.Real("-time_step", "Time step [s]; 0: time_step_safety x the estimated stable step", &scene->time_step));
    PetscCall(r.Real("-time_step_safety", "Fraction of the estimated stable step [-], in (0, 1]", &scene->time_step_safety));
    PetscCall(r.Real("-time_step_travel", "Largest distance a point with bonds may move in one step [dx]; the step shrinks while points move fast (snapping bonds), 0: never", &scene->time_step_travel));
    PetscCall(r.Real("-damping", "Mass-proportional damping coefficient [1/s], >= 0", &scene->damping));
    PetscCall(r.Real("-static_tolerance", "A hold of the load schedule ends once kinetic/internal energy < this [-] (0: holds run their full length)", &scene->static_tolerance));
    PetscCall(r.Real("-end_time", "End of the run [s] (default: the schedule's last time)", &scene->end_time, &in->end_time_set));
    PetscCall(r.Int("-progress_interval", "Time steps between progress lines [-] (0: about 20 lines a run)", &scene->progress_interval));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);
  PetscFunctionReturn(0);
}

// ---------------------------------------------------------------------------------
// Geometry for the body checks

double PointSegmentDistance(double px, double py, const Segment &s)
{
  const double ex = s.x1 - s.x0, ey = s.y1 - s.y0, len2 = ex * ex + ey * ey;
  double       t = len2 > 0 ? ((px - s.x0) * ex + (py - s.y0) * ey) / len2 : 0.0;
  t              = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (s.x0 + t * ex), py - (s.y0 + t * ey));
}

double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

double SegmentDistance(const Segment &a, const Segment &b)
{
  // Proper crossing: the end points of each lie strictly on both sides of the other.
  const double d1 = Cross(b.x1 - b.x0, b.y1 - b.y0, a.x0 - b.x0, a.y0 - b.y0);
  const double d2 = Cross(b.x1 - b.x0, b.y1 - b.y0, a.x1 - b.x0, a.y1 - b.y0);
  const double d3 = Cross(a.x1 - a.x0, a.y1 - a.y0, b.x0 - a.x0, b.y0 - a.y0);
  const double d4 = Cross(a.x1 - a.x0, a.y1 - a.y0, b.x1 - a.x0, b.y1 - a.y0);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({PointSegmentDistance(a.x0, a.y0, b), PointSegmentDistance(a.x1, a.y1, b), PointSegmentDistance(b.x0, b.y0, a),
                   PointSegmentDistance(b.x1, b.y1, a)});
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int i) { return parent[i] == i ? i : parent[i] = Find(parent[i]); }
  void Join(int a, int b) { parent[Find(a)] = Find(b); }
};

// The notches and holes, with the four edges, as a graph whose links are contacts
// closer than half a spacing (a gap that narrow holds no column of lattice points, so
// every bond across it is cut). Two edges in one connected group mean the body falls
// apart. Returns "" or the message for the first such pair.
std::string FindCut(const Body2D &b)
{
  const int   n_holes = static_cast<int>(b.holes.size()), n_notches = static_cast<int>(b.notches.size());
  const int   first_hole = 4, first_notch = 4 + n_holes;
  const double tol       = 0.5 * b.dx;
  UnionFind    groups(4 + n_holes + n_notches);
  enum { left = 0, right = 1, bottom = 2, top = 3 };
  for (int h = 0; h < n_holes; ++h) {
    const Circle &c = b.holes[h];
    if (c.cx - c.radius <= tol) groups.Join(first_hole + h, left);
    if (b.width - (c.cx + c.radius) <= tol) groups.Join(first_hole + h, right);
    if (c.cy - c.radius <= tol) groups.Join(first_hole + h, bottom);
    if (b.height - (c.cy + c.radius) <= tol) groups.Join(first_hole + h, top);
    for (int k = 0; k < h; ++k)
      if (std::hypot(c.cx - b.holes[k].cx, c.cy - b.holes[k].cy) - c.radius - b.holes[k].radius <= tol) groups.Join(first_hole + h, first_hole + k);
  }
  for (int s = 0; s < n_notches; ++s) {
    const Segment &g = b.notches[s];
    if (std::min(g.x0, g.x1) <= tol) groups.Join(first_notch + s, left);
    if (b.width - std::max(g.x0, g.x1) <= tol) groups.Join(first_notch + s, right);
    if (std::min(g.y0, g.y1) <= tol) groups.Join(first_notch + s, bottom);
    if (b.height - std::max(g.y0, g.y1) <= tol) groups.Join(first_notch + s, top);
    for (int h = 0; h < n_holes; ++h)
      if (PointSegmentDistance(b.holes[h].cx, b.holes[h].cy, g) - b.holes[h].radius <= tol) groups.Join(first_notch + s, first_hole + h);
    for (int k = 0; k < s; ++k)
      if (SegmentDistance(g, b.notches[k]) <= tol) groups.Join(first_notch + s, first_notch + k);
  }
  struct Pair {
    int         a, b;
    const char *edges, *result;
  };
  const Pair pairs[] = {
    {left, right, "the left and right edges", "cutting the body into a top and a bottom piece"},
    {bottom, top, "the bottom and top edges", "cutting the body into a left and a right piece"},
    {left, bottom, "the left and bottom edges", "cutting off the bottom-left corner"},
    {left, top, "the left and top edges", "cutting off the top-left corner"},
    {right, bottom, "the right and bottom edges", "cutting off the bottom-right corner"},
    {right, top, "the right and top edges", "cutting off the top-right corner"},
  };
  for (const Pair &p : pairs) {
    if (groups.Find(p.a) != groups.Find(p.b)) continue;
    std::string culprits;
    int         count = 0, notches = 0;
    for (int s = 0; s < n_notches; ++s)
      if (groups.Find(first_notch + s) == groups.Find(p.a)) {
        const Segment &g = b.notches[s];
        culprits += Format("%snotch %d (%g, %g)-(%g, %g)", count++ ? ", " : "", s + 1, g.x0, g.y0, g.x1, g.y1);
        ++notches;
      }
    for (int h = 0; h < n_holes; ++h)
      if (groups.Find(first_hole + h) == groups.Find(p.a)) culprits += Format("%shole %d", count++ ? ", " : "", h + 1);
    const char *options = notches == 0 ? "-body_holes" : notches == count ? "-body_notches" : "-body_notches and -body_holes";
    const char *fix     = notches == 0 ? "shrink or move a hole" : "shorten a notch so that it ends inside the body (an edge crack starts on one edge only)";
    return Format("%s: %s %s %s, %s (gaps under dx/2 = %g m count as closed): %s", options, culprits.c_str(), count > 1 ? "together join" : "joins",
                  p.edges, p.result, tol, fix);
  }
  return "";
}

bool InsideHole(const Body2D &b, double x, double y, int *which)
{
  for (std::size_t h = 0; h < b.holes.size(); ++h)
    if (std::hypot(x - b.holes[h].cx, y - b.holes[h].cy) < b.holes[h].radius) {
      *which = static_cast<int>(h);
      return true;
    }
  return false;
}

// " (-body_widht was given: is it a misspelling of -body_width?)" when an option that
// nothing has read lies within typo distance of `option`, which is missing: a misspelt
// required option otherwise reads as a forgotten one. "" when there is none.
std::string MisspeltHint(const std::string &option)
{
  PetscInt    n      = 0;
  char      **names  = nullptr;
  char      **values = nullptr;
  std::string hint;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values)) return "";
  for (PetscInt i = 0; i < n && hint.empty(); ++i) {
    const std::string given = std::string("-") + names[i];
    if (Lower(given) != Lower(option) && !SuggestOption(given, {option}).empty())
      hint = " (" + given + " was given: is it a misspelling of " + option + "?)";
  }
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return hint;
}

// Why rank 0 could not create files in `dir`, or "": the nearest existing ancestor
// (dir itself when it exists) must be a directory this process may write into.
// Nothing is created here; the history file is opened after the setup.
std::string OutputDirProblem(const std::string &dir)
{
  std::filesystem::path path = dir;
  while (true) {
    struct stat info;
    if (::stat(path.c_str(), &info) == 0) {
      if (!S_ISDIR(info.st_mode)) return "'" + path.string() + "' is a file, not a directory";
      if (::access(path.c_str(), W_OK | X_OK) != 0)
        return "'" + path.string() + "' is not writable (" + std::strerror(errno) + ")";
      return "";
    }
    if (!path.has_relative_path() || path.parent_path() == path) return "";
    path = path.parent_path();
    if (path.empty()) path = ".";
  }
}

// ---------------------------------------------------------------------------------
// Checks: the whole scene, component by component, first problem reported.

PetscErrorCode CheckBody(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  Body2D &b = scene->body;
  PetscFunctionBeginUser;
  const struct {
    bool        set;
    double      value;
    const char *name, *what, *yaml;
  } sizes[] = {
    {in.width_set, b.width, "-body_width", "the sheet width along x", "width: 0.08"},
    {in.height_set, b.height, "-body_height", "the sheet height along y", "height: 0.16"},
    {in.thickness_set, b.thickness, "-body_thickness", "the sheet thickness", "thickness: 0.001"},
    {in.dx_set, b.dx, "-body_dx", "the lattice spacing", "dx: 0.001"},
  };
  for (const auto &s : sizes) {
    SceneCheck(s.set, comm, "%s is required: give %s in metres (YAML: body: {%s})%s", s.name, s.what, s.yaml, MisspeltHint(s.name).c_str());
    SceneCheck(s.value > 0, comm, "%s %g: %s must be > 0 m", s.name, s.value, s.what);
  }
  SceneCheck(b.dx <= b.width && b.dx <= b.height, comm,
             "-body_dx %g m is larger than the body (%g m x %g m): choose a spacing well below the smaller side, e.g. -body_dx %g", b.dx,
             b.width, b.height, std::min(b.width, b.height) / 20);
  const double tol = 1e-12 * std::max(b.width, b.height); // round-off in the input numbers

  SceneCheck(in.holes.size() % 3 == 0, comm,
             "-body_holes holds %zu numbers, not a multiple of 3: give each hole as cx,cy,r (e.g. -body_holes 0.04,0.08,0.01)", in.holes.size());
  b.holes.clear();
  for (std::size_t h = 0; 3 * h < in.holes.size(); ++h) {
    const Circle c = {in.holes[3 * h], in.holes[3 * h + 1], in.holes[3 * h + 2]};
    SceneCheck(c.radius > 0, comm, "-body_holes: hole %zu has radius %g m: a radius must be > 0", h + 1, c.radius);
    double far = 0; // distance from the centre to the farthest corner
    for (double x : {0.0, b.width})
      for (double y : {0.0, b.height}) far = std::max(far, std::hypot(x - c.cx, y - c.cy));
    SceneCheck(c.radius < far, comm,
               "-body_holes: hole %zu (centre (%g, %g) m, radius %g m) covers the whole body and leaves no material: reduce its radius",
               h + 1, c.cx, c.cy, c.radius);
    SceneCheck(c.cx - c.radius >= -tol && c.cx + c.radius <= b.width + tol && c.cy - c.radius >= -tol && c.cy + c.radius <= b.height + tol,
               comm,
               "-body_holes: hole %zu (centre (%g, %g) m, radius %g m) is not entirely inside the body [0, %g] x [0, %g] m: move its "
               "centre or reduce its radius",
               h + 1, c.cx, c.cy, c.radius, b.width, b.height);
    b.holes.push_back(c);
  }

  SceneCheck(in.notches.size() % 4 == 0, comm,
             "-body_notches holds %zu numbers, not a multiple of 4: give each notch as x0,y0,x1,y1 (e.g. -body_notches 0.05,0.005,0.07,0.005)",
             in.notches.size());
  b.notches.clear();
  for (std::size_t s = 0; 4 * s < in.notches.size(); ++s) {
    const Segment g = {in.notches[4 * s], in.notches[4 * s + 1], in.notches[4 * s + 2], in.notches[4 * s + 3]};
    for (int end = 0; end < 2; ++end) {
      const double x = end ? g.x1 : g.x0, y = end ? g.y1 : g.y0;
      SceneCheck(x >= -tol && x <= b.width + tol && y >= -tol && y <= b.height + tol, comm,
                 "-body_notches: notch %zu ends at (%g, %g) m, outside the body [0, %g] x [0, %g] m: move that end inside (an edge crack "
                 "ends on the edge)",
                 s + 1, x, y, b.width, b.height);
    }
    SceneCheck(std::hypot(g.x1 - g.x0, g.y1 - g.y0) > tol, comm,
               "-body_notches: notch %zu has zero length (both ends at (%g, %g) m): give two different end points", s + 1, g.x0, g.y0);
    b.notches.push_back(g);
  }
  const std::string cut = FindCut(b);
  PetscCheck(cut.empty(), comm, PETSC_ERR_USER, "%s", cut.c_str());
  SceneCheck(ScenePointEstimate(*scene) > 0, comm,
             "-body_holes: the holes leave no material point on the lattice of spacing -body_dx %g m: reduce their radii or dx", b.dx);

  SceneCheck(scene->horizon_factor >= 1, comm,
             "-horizon_factor %g is below 1: the horizon delta = factor x dx must reach the nearest neighbours; use 3.015 (the paper's "
             "value), or a value in [2, 5]",
             scene->horizon_factor);
  if (scene->horizon_factor < 2 || scene->horizon_factor > 5)
    PetscCall(Warn(comm, Format("-horizon_factor %g is outside [2, 5]: too few neighbours make the shape tensor fragile, too many "
                                "smooth the solution and cost time; the paper uses 3.015",
                                scene->horizon_factor)));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckMaterial(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  MaterialParameters &m = scene->material;
  PetscFunctionBeginUser;
  std::string model = Lower(in.model);
  std::replace(model.begin(), model.end(), '-', '_'); // "neo-hookean" as the paper writes it
  if (!parse(model, scene->model))
    SETERRQ(comm, PETSC_ERR_USER, "%s", Format("-material_model '%s' is not a model: choose gent or neo_hookean", in.model.c_str()).c_str());
  if (!parse(Lower(in.formulation), scene->formulation))
    SETERRQ(comm, PETSC_ERR_USER, "%s",
            Format("-material_formulation '%s' is not a formulation: choose plane_stress or plane_strain", in.formulation.c_str()).c_str());
  std::string form = Lower(in.force_form);
  std::replace(form.begin(), form.end(), '-', '_');
  if (form == "bond_only") scene->force_form = ForceForm::bond_only;
  else if (form == "energy_consistent") scene->force_form = ForceForm::energy_consistent;
  else
    SETERRQ(comm, PETSC_ERR_USER, "%s",
            Format("-force_form '%s' is not a force form: choose bond_only (the paper's) or energy_consistent", in.force_form.c_str()).c_str());

  SceneCheck(!(in.D_set && in.bulk_ratio_set), comm,
             "-material_D and -material_bulk_ratio both set the compressibility (D = 2/(bulk_ratio mu)): give only one of them");
  if (in.bulk_ratio_set) {
    SceneCheck(in.bulk_ratio > 0, comm,
               "-material_bulk_ratio %g: the ratio K/mu must be > 0; a nearly incompressible gel has K/mu >= 100 (the default)", in.bulk_ratio);
    m.D = 2.0 / (in.bulk_ratio * m.mu);
  } else if (!in.D_set) m.D = 2.0 / (1000.0 * m.mu); // K = 1000 mu, see ReadMaterial
  std::string problems = check_parameters(scene->model, m); // -material_mu, -material_Jm, -material_D
  if (!problems.empty() && problems.back() == '\n') problems.pop_back();
  PetscCheck(problems.empty(), comm, PETSC_ERR_USER, "%s", problems.c_str());
  SceneCheck(scene->density > 0, comm, "-material_density %g: the density must be > 0 kg/m^3 (a hydrogel: about 1000)",
             scene->density);

  scene->failure = in.critical_stretch_set;
  if (scene->failure)
    SceneCheck(scene->critical_stretch > 1, comm,
               "-failure_critical_stretch %g: a bond breaks once stretched past s_c, so s_c must be > 1 (paper: 7.2); leave the option "
               "out for no failure",
               scene->critical_stretch);
  else scene->critical_stretch = 0.0;
  PetscFunctionReturn(0);
}

bool ParseComponent(const std::string &text, ComponentLoad *load)
{
  const std::string t = Lower(text);
  if (t == "free") *load = ComponentLoad::free;
  else if (t == "fixed") *load = ComponentLoad::fixed;
  else if (t == "stretch") *load = ComponentLoad::stretch;
  else return false;
  return true;
}

PetscErrorCode CheckLoading(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  const Body2D &b = scene->body;
  Schedule     &schedule = scene->schedule;
  PetscFunctionBeginUser;
  // The schedule: pairs (t, lambda), times strictly increasing from t >= 0.
  schedule.time.clear();
  schedule.stretch.clear();
  if (in.schedule_set) {
    SceneCheck(!in.schedule.empty() && in.schedule.size() % 2 == 0, comm,
               "-load_schedule holds %zu numbers: give pairs time,stretch t0,lambda0,t1,lambda1,... (e.g. 0,1,10,2 ramps lambda from 1 "
               "to 2 over 10 s)",
               in.schedule.size());
    for (std::size_t k = 0; 2 * k < in.schedule.size(); ++k) {
      const double t = in.schedule[2 * k], lambda = in.schedule[2 * k + 1];
      SceneCheck(t >= 0, comm, "-load_schedule: knot %zu has time %g s: times count from the start of the run, t >= 0", k + 1, t);
      if (k > 0)
        SceneCheck(t > schedule.time.back(), comm,
                   "-load_schedule: times must increase strictly, but knot %zu has t = %g s after t = %g s: a hold is two knots with "
                   "the same stretch at different times",
                   k + 1, t, schedule.time.back());
      SceneCheck(lambda > 0, comm, "-load_schedule: knot %zu has stretch %g: a stretch (current / initial length) must be > 0",
                 k + 1, lambda);
      schedule.time.push_back(t);
      schedule.stretch.push_back(lambda);
    }
    if (std::fabs(schedule.stretch_at(0.0) - 1.0) > 1e-12)
      PetscCall(Warn(comm, Format("-load_schedule starts at stretch %g, not 1: the grips jump at t = 0", schedule.stretch_at(0.0))));
  }
  if (in.reference_length_set)
    SceneCheck(scene->reference_length > 0, comm,
               "-load_reference_length %g: the length that turns stretch into displacement must be > 0 m (default: the body height)",
               scene->reference_length);
  else scene->reference_length = b.height;

  scene->loads.clear();
  for (const LoadInput &li : in.loads) {
    LoadSet     set;
    const char *n = li.name.c_str();
    set.name      = li.name;
    SceneCheck(li.region_set, comm, "-load_%s_region is required for load set '%s': choose top, bottom, left, right or box%s", n, n,
               MisspeltHint("-load_" + li.name + "_region").c_str());
    const std::string region = Lower(li.region);
    if (region == "top") set.region = LoadSet::Region::top;
    else if (region == "bottom") set.region = LoadSet::Region::bottom;
    else if (region == "left") set.region = LoadSet::Region::left;
    else if (region == "right") set.region = LoadSet::Region::right;
    else if (region == "box") set.region = LoadSet::Region::box;
    else SETERRQ(comm, PETSC_ERR_USER, "%s", Format("-load_%s_region '%s' is not a region: choose top, bottom, left, right or box", n, li.region.c_str()).c_str());

    if (set.region == LoadSet::Region::box) {
      SceneCheck(li.box_set, comm, "-load_%s_box is required with -load_%s_region box: give xmin,ymin,xmax,ymax in m%s", n, n,
                 MisspeltHint("-load_" + li.name + "_box").c_str());
      SceneCheck(li.box.size() == 4, comm, "-load_%s_box holds %zu numbers: give exactly four, xmin,ymin,xmax,ymax in m", n,
                 li.box.size());
      std::copy(li.box.begin(), li.box.end(), set.box);
      SceneCheck(set.box[0] < set.box[2] && set.box[1] < set.box[3], comm,
                 "-load_%s_box %g,%g,%g,%g is empty: the order is xmin,ymin,xmax,ymax with xmin < xmax and ymin < ymax", n, set.box[0],
                 set.box[1], set.box[2], set.box[3]);
      SceneCheck(set.box[2] >= 0 && set.box[0] <= b.width && set.box[3] >= 0 && set.box[1] <= b.height, comm,
                 "-load_%s_box %g,%g,%g,%g lies outside the body [0, %g] x [0, %g] m: move it onto the body", n, set.box[0], set.box[1],
                 set.box[2], set.box[3], b.width, b.height);
      SceneCheck(!li.layers_set, comm,
                 "-load_%s_layers is set but load set '%s' is a box: layers count from an edge; remove it or choose an edge region", n, n);
    } else {
      SceneCheck(!li.box_set, comm,
                 "-load_%s_box is set but -load_%s_region is %s: the box is only used with region box; remove it or set the region to box",
                 n, n, to_string(set.region));
      SceneCheck(li.layers >= 1, comm, "-load_%s_layers %" PetscInt_FMT ": take at least one point layer (the default, 1)", n,
                 li.layers);
      const bool   vertical = set.region == LoadSet::Region::top || set.region == LoadSet::Region::bottom;
      const double across   = vertical ? b.height : b.width;
      SceneCheck(li.layers * b.dx < across, comm,
                 "-load_%s_layers %" PetscInt_FMT " is %g m deep, the whole body %s (%g m): use fewer layers", n, li.layers, li.layers * b.dx,
                 vertical ? "height" : "width", across);
      set.layers = static_cast<int>(li.layers);
    }

    SceneCheck(ParseComponent(li.x, &set.x), comm, "-load_%s_x '%s' is not a choice: choose free, fixed or stretch", n, li.x.c_str());
    SceneCheck(ParseComponent(li.y, &set.y), comm, "-load_%s_y '%s' is not a choice: choose free, fixed or stretch", n, li.y.c_str());
    for (int c = 0; c < 2; ++c) {
      const char          axis  = c == 0 ? 'x' : 'y';
      const ComponentLoad load  = c == 0 ? set.x : set.y;
      const bool          given = c == 0 ? li.x_scale_set : li.y_scale_set;
      const double        scale = c == 0 ? li.x_scale : li.y_scale;
      SceneCheck(load == ComponentLoad::stretch || !given, comm,
                 "-load_%s_%c_scale is set but -load_%s_%c is %s: the scale applies to a stretch component only; remove it or set "
                 "-load_%s_%c stretch",
                 n, axis, n, axis, to_string(load), n, axis);
      if (load != ComponentLoad::stretch) continue;
      SceneCheck(!schedule.time.empty(), comm,
                 "-load_%s_%c stretch needs a stretch schedule: give -load_schedule t0,lambda0,t1,lambda1,... (e.g. 0,1,10,2 ramps lambda "
                 "from 1 to 2 over 10 s)%s",
                 n, axis, MisspeltHint("-load_schedule").c_str());
      if (scale == 0.0)
        PetscCall(Warn(comm, Format("-load_%s_%c_scale is 0: the stretch component never moves (same as -load_%s_%c fixed)", n, axis, n, axis)));
      (c == 0 ? set.x_scale : set.y_scale) = scale;
    }
    if (set.x == ComponentLoad::free && set.y == ComponentLoad::free)
      PetscCall(Warn(comm, Format("load set '%s' holds neither component (-load_%s_x and -load_%s_y are free): it does nothing; set "
                                  "one of them to fixed or stretch",
                                  n, n, n)));
    scene->loads.push_back(set);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckProbesOutputTime(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  const Body2D &b = scene->body;
  PetscFunctionBeginUser;
  const double tol = 1e-12 * std::max(b.width, b.height);
  scene->probes.clear();
  for (const ProbeInput &pi : in.probes) {
    const char *n = pi.name.c_str();
    SceneCheck(pi.at_set, comm, "-probe_%s_at is required for probe '%s': give its position x,y in m%s", n, n,
               MisspeltHint("-probe_" + pi.name + "_at").c_str());
    SceneCheck(pi.at.size() == 2, comm, "-probe_%s_at holds %zu numbers: give exactly two, x,y in m", n, pi.at.size());
    const Probe p = {pi.name, pi.at[0], pi.at[1]};
    SceneCheck(p.x >= -tol && p.x <= b.width + tol && p.y >= -tol && p.y <= b.height + tol, comm,
               "-probe_%s_at (%g, %g) m lies outside the body [0, %g] x [0, %g] m: move it onto the body", n, p.x, p.y, b.width, b.height);
    int hole = -1;
    SceneCheck(!InsideHole(b, p.x, p.y, &hole), comm,
               "-probe_%s_at (%g, %g) m lies inside hole %d, where there is no material: move it onto the body (a hole's edge is fine)", n, p.x,
               p.y, hole + 1);
    scene->probes.push_back(p);
  }

  SceneCheck(!scene->output_dir.empty(), comm, "-output_dir is empty: give a directory, e.g. -output_dir output");
  {
    // Rank 0 writes the output: it checks, every rank hears its verdict.
    PetscMPIInt rank;
    std::string problem;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (rank == 0) problem = OutputDirProblem(scene->output_dir);
    int length = static_cast<int>(problem.size());
    PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm));
    problem.resize(static_cast<std::size_t>(length));
    PetscCallMPI(MPI_Bcast(problem.data(), length, MPI_CHAR, 0, comm));
    SceneCheck(problem.empty(), comm, "-output_dir %s cannot be created or written: %s; choose a writable directory, e.g. -output_dir output",
               scene->output_dir.c_str(), problem.c_str());
  }
  SceneCheck(scene->output_interval >= 1, comm,
             "-output_interval %" PetscInt_FMT ": history rows are written every N >= 1 time steps (default 100)", scene->output_interval);

  SceneCheck(scene->time_step >= 0, comm,
             "-time_step %g: the time step must be > 0 s, or 0 for the automatic choice (safety x stable step)", scene->time_step);
  SceneCheck(scene->time_step_safety > 0, comm,
             "-time_step_safety %g must be > 0: it is the fraction of the estimated stable step that is taken (default 0.8)",
             scene->time_step_safety);
  if (scene->time_step_safety > 1)
    PetscCall(Warn(comm,
                   Format("-time_step_safety %g is above 1: the time step exceeds the estimated stable step and the explicit scheme "
                          "may blow up; use a value in (0, 1] (default 0.8)",
                          scene->time_step_safety),
                   true));
  SceneCheck(scene->time_step_travel >= 0, comm,
             "-time_step_travel %g must be >= 0: it is the largest distance, in dx, that a point with bonds may move in one step (0, the default: off; 0.1 for running cracks)",
             scene->time_step_travel);
  SceneCheck(scene->damping >= 0, comm, "-damping %g: the damping coefficient must be >= 0 1/s (0: undamped)", scene->damping);
  SceneCheck(scene->static_tolerance >= 0 && scene->static_tolerance < 1, comm,
             "-static_tolerance %g: use a small positive ratio such as 1e-6 (0: holds run their full length)", scene->static_tolerance);
  SceneCheck(scene->progress_interval >= 0, comm,
             "-progress_interval %" PetscInt_FMT ": give N >= 1 time steps between progress lines, or 0 for about 20 lines a run",
             scene->progress_interval);
  const double schedule_end = scene->schedule.end_time();
  if (in.end_time_set) {
    SceneCheck(scene->end_time > 0, comm, "-end_time %g: the run must end after t = 0 s", scene->end_time);
    if (scene->end_time < schedule_end)
      PetscCall(Warn(comm, Format("-end_time %g s stops the run before the end of -load_schedule (%g s)", scene->end_time, schedule_end)));
  } else {
    SceneCheck(schedule_end > 0, comm,
               "-end_time is required when -load_schedule does not end after t = 0: give the run's end in s, e.g. -end_time 1%s",
               (MisspeltHint("-end_time") + MisspeltHint("-load_schedule")).c_str());
    scene->end_time = schedule_end;
  }
  PetscFunctionReturn(0);
}

// PETSc's own run-time options, which may legitimately go unread (a TS type that
// ignores an option, -log_view read at the end, ...).
bool IsPetscOption(const std::string &name)
{
  static const char *const exact[]    = {"help", "h", "version", "info", "options_left", "nox", "nox_warning", "history", "checkstack",
                                         "objects_dump", "fp_trap", "no_signal_handler", "start_in_debugger", "stop_for_debugger",
                                         "display", "skip_petscrc", "petsc_ci", "use_gpu_aware_mpi", "memory_view", "x_virtual"};
  static const char *const prefixes[] = {"options_", "log_", "malloc", "on_error_", "info_", "ts_", "vec_", "mat_", "snes_", "ksp_",
                                         "pc_", "dm_", "viewer", "draw_", "saws_", "debugger_", "device_", "cuda", "hip", "sycl",
                                         "kokkos", "petsc", "is_", "sf_", "tao_", "mpi_", "check_pointer", "error_output", "memory_",
                                         "citations", "blas_", "omp_", "timeout", "sys_", "matload_", "pointer_", "fp_"};
  for (const char *e : exact)
    if (name == e) return true;
  for (const char *p : prefixes)
    if (name.compare(0, std::char_traits<char>::length(p), p) == 0) return true;
  return false;
}

// "-load_grip_region" when 'grip' is not in -load_sets: the set name, else "".
std::string UndeclaredName(const std::string &name, const char *head, std::initializer_list<const char *> tails)
{
  if (name.compare(0, std::char_traits<char>::length(head), head) != 0) return "";
  for (const char *tail : tails) {
    const std::size_t lh = std::char_traits<char>::length(head), lt = std::char_traits<char>::length(tail);
    if (name.size() > lh + lt && name.compare(name.size() - lt, lt, tail) == 0) return name.substr(lh, name.size() - lh - lt);
  }
  return "";
}

std::string UnusedMessage(const std::string &name)
{
  std::vector<std::string> known;
  for (const auto &entry : Registry()) known.push_back(entry.second);
  const std::string suggestion = SuggestOption(name, known);
  const std::string set        = UndeclaredName(Lower(name), "-load_", {"_x_scale", "_y_scale", "_region", "_box", "_layers", "_x", "_y"});
  const std::string probe      = UndeclaredName(Lower(name), "-probe_", {"_at"});
  std::string       message    = name + " is not a bapd option.";
  if (!set.empty()) message += " '" + set + "' is not one of -load_sets: add it there, or fix the name.";
  else if (!probe.empty()) message += " '" + probe + "' is not one of -probes: add it there, or fix the name.";
  if (!suggestion.empty()) message += " Did you mean " + suggestion + "?";
  return message;
}

} // namespace

// ---------------------------------------------------------------------------------
// Public interface

double Schedule::stretch_at(double t) const
{
  if (time.empty()) return 1.0;
  if (t <= time.front()) return stretch.front();
  if (t >= time.back()) return stretch.back();
  // time[k - 1] <= t < time[k]
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), t) - time.begin());
  const double      a = (t - time[k - 1]) / (time[k] - time[k - 1]);
  return stretch[k - 1] + a * (stretch[k] - stretch[k - 1]);
}

double Schedule::rate_at(double t) const
{
  if (time.size() < 2 || t < time.front() || t >= time.back()) return 0.0;
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), t) - time.begin());
  return (stretch[k] - stretch[k - 1]) / (time[k] - time[k - 1]);
}

const char *to_string(LoadSet::Region region)
{
  switch (region) {
  case LoadSet::Region::top: return "top";
  case LoadSet::Region::bottom: return "bottom";
  case LoadSet::Region::left: return "left";
  case LoadSet::Region::right: return "right";
  case LoadSet::Region::box: return "box";
  }
  return "unknown";
}

const char *to_string(ComponentLoad load)
{
  switch (load) {
  case ComponentLoad::free: return "free";
  case ComponentLoad::fixed: return "fixed";
  case ComponentLoad::stretch: return "stretch";
  }
  return "unknown";
}

const char *to_string(ForceForm form)
{
  switch (form) {
  case ForceForm::bond_only: return "bond_only";
  case ForceForm::energy_consistent: return "energy_consistent";
  }
  return "unknown";
}

const std::vector<std::string> &SceneWarnings() { return Warnings(); }

void RegisterOptionName(const std::string &name) { Registry().emplace(Lower(name), name); }

PetscInt ScenePointEstimate(const Scene &scene)
{
  const Body2D &b = scene.body;
  if (!(b.dx > 0) || !(b.width > 0) || !(b.height > 0)) return 0;
  const long nx = std::lround(b.width / b.dx), ny = std::lround(b.height / b.dx);
  if (nx < 1 || ny < 1) return 0;
  if (b.holes.empty()) return static_cast<PetscInt>(nx * ny);
  PetscInt count = 0;
  for (long iy = 0; iy < ny; ++iy) {
    const double py = (static_cast<double>(iy) + 0.5) * b.dx;
    for (long ix = 0; ix < nx; ++ix) {
      int hole = -1;
      if (!InsideHole(b, (static_cast<double>(ix) + 0.5) * b.dx, py, &hole)) ++count;
    }
  }
  return count;
}

PetscErrorCode SceneFromOptions(MPI_Comm comm, Scene *scene)
{
  SceneInput in;
  PetscBool  help = PETSC_FALSE;
  PetscFunctionBeginUser;
  *scene = Scene();
  Warnings().clear();
  PetscCall(ReadBody(comm, scene, &in));
  PetscCall(ReadMaterial(comm, scene, &in));
  PetscCall(ReadLoading(comm, scene, &in));
  PetscCall(ReadProbesOutputTime(comm, scene, &in));

  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help) {
    scene->help_only = true;
    PetscCall(PetscPrintf(comm, "  (per-set options -load_NAME_... and per-probe options -probe_NAME_at are listed for the names given "
                                "in -load_sets and -probes; see docs/options.md)\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(CheckBody(comm, in, scene));
  PetscCall(CheckMaterial(comm, in, scene));
  PetscCall(CheckLoading(comm, in, scene));
  PetscCall(CheckProbesOutputTime(comm, in, scene));
  PetscFunctionReturn(0);
}

PetscErrorCode SceneView(MPI_Comm comm, const Scene &s)
{
  const Body2D &b = s.body;
  std::string   text; // built with the C library's printf (see SceneCheck), printed once
  PetscFunctionBeginUser;
  if (s.help_only) PetscFunctionReturn(0);
  text += Format("Scene\n  body      %g m x %g m, thickness %g m, dx %g m: %ld x %ld lattice, %ld points, %zu hole(s), %zu notch(es)\n", b.width,
                 b.height, b.thickness, b.dx, std::lround(b.width / b.dx), std::lround(b.height / b.dx), (long)ScenePointEstimate(s),
                 b.holes.size(), b.notches.size());
  for (const Circle &c : b.holes) text += Format("            hole centre (%g, %g) m, radius %g m\n", c.cx, c.cy, c.radius);
  for (const Segment &g : b.notches) text += Format("            notch (%g, %g)-(%g, %g) m\n", g.x0, g.y0, g.x1, g.y1);
  text += Format("  horizon   delta = %g dx = %g m\n", s.horizon_factor, s.horizon());
  const double K = 2.0 / s.material.D;
  text += Format("  material  %s, %s: mu %g Pa", to_string(s.model), to_string(s.formulation), s.material.mu);
  if (s.model == ModelKind::gent) text += Format(", Jm %g", s.material.Jm);
  text += Format(", D %g 1/Pa (bulk modulus K = 2/D = %g Pa = %g mu), density %g kg/m^3\n", s.material.D, K, K / s.material.mu, s.density);
  text += Format("  force     %s\n", to_string(s.force_form));
  if (s.failure) text += Format("  failure   bonds break past stretch s_c = %g\n", s.critical_stretch);
  else text += "  failure   none\n";
  auto component = [](ComponentLoad c, double scale) {
    return c == ComponentLoad::stretch ? Format("stretch (scale %g)", scale) : std::string(to_string(c));
  };
  for (const LoadSet &l : s.loads) {
    const std::string where = l.region == LoadSet::Region::box ? Format("box [%g, %g] x [%g, %g] m", l.box[0], l.box[2], l.box[1], l.box[3])
                                                               : Format("%s edge, %d layer(s)", to_string(l.region), l.layers);
    text += Format("  load set  %s: %s; x %s, y %s\n", l.name.c_str(), where.c_str(), component(l.x, l.x_scale).c_str(),
                   component(l.y, l.y_scale).c_str());
  }
  if (s.loads.empty()) text += "  load set  none\n";
  if (!s.schedule.time.empty()) {
    text += "  schedule  (t, lambda):";
    for (std::size_t k = 0; k < s.schedule.time.size(); ++k) text += Format(" (%g s, %g)", s.schedule.time[k], s.schedule.stretch[k]);
    text += Format("; u = scale (lambda - 1) %g m\n", s.reference_length);
  }
  for (const Probe &p : s.probes) text += Format("  probe     %s at (%g, %g) m\n", p.name.c_str(), p.x, p.y);
  if (s.time_step > 0) text += Format("  time      step %g s", s.time_step);
  else text += Format("  time      step %g x the stable step", s.time_step_safety);
  if (s.time_step_travel > 0) text += Format(" (shorter while a point with bonds would move > %g dx a step)", s.time_step_travel);
  text += Format(", damping %g 1/s, end %g s\n", s.damping, s.end_time);
  if (s.static_tolerance > 0)
    text += Format("  static    a hold ends once kinetic energy < %g x internal energy (checked at every history row)\n", s.static_tolerance);
  text += Format("  output    %s/, history every %ld steps\n", s.output_dir.c_str(), (long)s.output_interval);
  PetscCall(PetscPrintf(comm, "%s", text.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckUnusedOptions(MPI_Comm comm)
{
  PetscInt    n      = 0;
  char      **names  = nullptr;
  char      **values = nullptr;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::vector<std::string> unused; // "-name", as the database holds it
  for (PetscInt i = 0; i < n; ++i)
    if (!IsPetscOption(Lower(names[i]))) unused.push_back(std::string("-") + names[i]);
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));

  // An option is unused only if no rank read it: rank 0's list, kept where every rank
  // agrees, so that every rank reaches the same verdict.
  std::string joined;
  for (const std::string &u : unused) joined += u + '\n';
  int length = static_cast<int>(joined.size());
  PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm));
  joined.resize(static_cast<std::size_t>(length));
  PetscCallMPI(MPI_Bcast(joined.data(), length, MPI_CHAR, 0, comm));
  std::vector<std::string> candidates;
  for (std::size_t start = 0; start < joined.size();) {
    const std::size_t end = joined.find('\n', start);
    candidates.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
  std::vector<int> here(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) here[i] = std::find(unused.begin(), unused.end(), candidates[i]) != unused.end();
  if (!here.empty()) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, here.data(), static_cast<int>(here.size()), MPI_INT, MPI_LAND, comm));

  std::string message;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (here[i]) message += (message.empty() ? "" : "\n") + UnusedMessage(candidates[i]);
  PetscCheck(message.empty(), comm, PETSC_ERR_USER, "%s (run with -help to list every option)", message.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode LoadSetSelect(const Scene &scene, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  const Body2D &b     = scene.body;
  const double  depth = set.layers * b.dx; // layer boundaries fall half-way between lattice rows
  PetscFunctionBeginUser;
  selected->clear();
  for (PetscInt i = 0; i < n; ++i) {
    const double px = x[2 * i], py = x[2 * i + 1];
    bool         in = false;
    switch (set.region) {
    case LoadSet::Region::top: in = py > b.height - depth; break;
    case LoadSet::Region::bottom: in = py < depth; break;
    case LoadSet::Region::left: in = px < depth; break;
    case LoadSet::Region::right: in = px > b.width - depth; break;
    case LoadSet::Region::box: in = px >= set.box[0] && px <= set.box[2] && py >= set.box[1] && py <= set.box[3]; break;
    }
    if (in) selected->push_back(i);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n, ProbeLocation *location)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  double   best_d2 = std::numeric_limits<double>::max();
  int64_t  best_id = std::numeric_limits<int64_t>::max();
  PetscInt best    = -1;
  for (PetscInt i = 0; i < n; ++i) {
    const double dx = x[2 * i] - probe.x, dy = x[2 * i + 1] - probe.y, d2 = dx * dx + dy * dy;
    if (d2 < best_d2 || (d2 == best_d2 && natural_id[i] < best_id)) {
      best_d2 = d2;
      best_id = natural_id[i];
      best    = i;
    }
  }
  // The smallest distance, then the smallest id among the points at that distance:
  // exact comparisons are safe because every rank compares the same stored values.
  double d2min = best_d2;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &d2min, 1, MPI_DOUBLE, MPI_MIN, comm));
  int64_t id = best_d2 == d2min ? best_id : std::numeric_limits<int64_t>::max();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &id, 1, MPI_INT64_T, MPI_MIN, comm));
  PetscMPIInt mine = (best >= 0 && best_id == id && best_d2 == d2min) ? rank : -1, owner = -1;
  PetscCallMPI(MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MAX, comm));
  PetscCheck(owner >= 0, comm, PETSC_ERR_ARG_WRONG, "ProbeLocate: probe '%s' found no material point: no rank passed any point",
             probe.name.c_str());
  location->owner       = owner;
  location->natural_id  = id;
  location->local_index = owner == rank ? best : -1;
  location->distance    = std::sqrt(d2min);
  PetscFunctionReturn(0);
}

} // namespace bapd
