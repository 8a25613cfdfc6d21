// Region box: the points in an axis-aligned box, edges included (-load_NAME_box, the
// lower corner then the upper: 2D xmin,ymin,xmax,ymax; 3D xmin,ymin,zmin,xmax,ymax,zmax).
#include <algorithm>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {
namespace {

PetscErrorCode CheckBox2D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const Body<2>    &b  = r.body.sheet;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  PetscCall(CheckOwnPoints2D(r, set));
  SceneCheck(li.box_set, r.comm, "-load_%s_box is required with -load_%s_region box: give xmin,ymin,xmax,ymax in m%s", n, n,
             MisspeltHint("-load_" + li.name + "_box").c_str());
  SceneCheck(li.box.size() == 4, r.comm, "-load_%s_box holds %zu numbers: give exactly four, xmin,ymin,xmax,ymax in m", n, li.box.size());
  std::copy(li.box.begin(), li.box.end(), set->box);
  const double *x = set->box;
  SceneCheck(x[0] < x[2] && x[1] < x[3], r.comm,
             "-load_%s_box %g,%g,%g,%g is empty: the order is xmin,ymin,xmax,ymax with xmin < xmax and ymin < ymax", n, x[0], x[1], x[2], x[3]);
  SceneCheck(x[2] >= 0 && x[0] <= b.width && x[3] >= 0 && x[1] <= b.height, r.comm,
             "-load_%s_box %g,%g,%g,%g lies outside the body [0, %g] x [0, %g] m: move it onto the body", n, x[0], x[1], x[2], x[3], b.width,
             b.height);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckBox3D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const SolidSummary &b = r.body.solid_summary; // (the extent)
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  SceneCheck(li.box_set, r.comm, "-load_%s_box is required with -load_%s_region box: give xmin,ymin,zmin,xmax,ymax,zmax in m%s", n, n,
             MisspeltHint("-load_" + li.name + "_box").c_str());
  SceneCheck(li.box.size() == 6, r.comm, "-load_%s_box holds %zu numbers: a 3D box takes exactly six, xmin,ymin,zmin,xmax,ymax,zmax in m", n,
             li.box.size());
  std::copy(li.box.begin(), li.box.end(), set->box);
  const double *x = set->box;
  SceneCheck(x[0] < x[3] && x[1] < x[4] && x[2] < x[5], r.comm,
             "-load_%s_box %g,%g,%g,%g,%g,%g is empty: the order is xmin,ymin,zmin,xmax,ymax,zmax with each min < max", n, x[0], x[1], x[2],
             x[3], x[4], x[5]);
  bool meets = true;
  for (int k = 0; k < 3; ++k) meets = meets && x[3 + k] >= b.lo[k] && x[k] <= b.hi[k];
  SceneCheck(meets, r.comm, "-load_%s_box %g,%g,%g,%g,%g,%g lies outside the body [%g, %g] x [%g, %g] x [%g, %g] m: move it onto the body", n,
             x[0], x[1], x[2], x[3], x[4], x[5], b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2]);
  PetscFunctionReturn(0);
}

bool BoxContains2D(const BodyExtent &, const LoadSet &set, const double *p)
{
  return p[0] >= set.box[0] && p[0] <= set.box[2] && p[1] >= set.box[1] && p[1] <= set.box[3];
}

bool BoxContains3D(const BodyExtent &, const LoadSet &set, const double *p)
{
  for (int k = 0; k < 3; ++k)
    if (!(p[k] >= set.box[k] && p[k] <= set.box[3 + k])) return false;
  return true;
}

std::string BoxText(const BodyExtent &s, const LoadSet &l)
{
  const double *x = l.box;
  return s.dimension == 3 ? Format("box [%g, %g] x [%g, %g] x [%g, %g] m", x[0], x[3], x[1], x[4], x[2], x[5])
                          : Format("box [%g, %g] x [%g, %g] m", x[0], x[2], x[1], x[3]);
}

// Points sit at cell centres ((i + 1/2) dx, ...): a thin box can miss them all.
std::string BoxEmpty(const BodyExtent &s, const LoadSet &set)
{
  const char   *n = set.name.c_str();
  const double *x = set.box;
  if (s.dimension == 3)
    return Format("-load_%s_box %g,%g,%g,%g,%g,%g selects no material point for load set '%s': widen it to hold a lattice point "
                  "(points sit at ((i + 1/2) dx, (j + 1/2) dx, (k + 1/2) dx), dx = %g m)",
                  n, x[0], x[1], x[2], x[3], x[4], x[5], n, s.dx);
  return Format("-load_%s_box %g,%g,%g,%g selects no material point for load set '%s': widen it to hold a lattice point "
                "(points sit at ((i + 1/2) dx, (j + 1/2) dx), dx = %g m)",
                n, x[0], x[1], x[2], x[3], n, s.dx);
}

} // namespace

RegionType box_region(LoadSet::Region id, const char *word, const char *alias)
{
  return {id, word, alias, false, uses_box, uses_box, CheckBox2D, CheckBox3D, BoxContains2D, BoxContains3D, BoxText, BoxEmpty};
}

} // namespace bapd
