// The probes section: named points whose displacement is recorded (-probes,
// -probe_NAME_at, or -probe_NAME_group: a physical point of a Gmsh file, so that a
// probe drawn in the geometry moves with it). A probe must lie on material: in the
// body and outside every hole (the hole rule of lattice.hpp). Which point it reads at
// run time: ProbeLocate (scene_selection.cpp).
#include <algorithm>
#include <string>

#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"
#include "bapd/solver/input/scene_loading.hpp"

namespace bapd {

namespace {

// One probe's options (-probe_NAME_...), in -help's order.
const OptionTable<ProbeInput> kProbeOptions = {
    {"-at", "Position x,y [m] (3D: x,y,z); the nearest material point is recorded (this or -group is required)", &ProbeInput::at, &ProbeInput::at_set},
    {"-group", "A physical point of a Gmsh file (Physical Point(\"name\") = {k};): the probe is placed at it", &ProbeInput::group},
    {"-file", "The Gmsh .geo or .msh file of -group (default: the body's mesh shape's file)", &ProbeInput::file},
    {"-block", "A block id of the point cloud (-body_cloud's block_id column) that one point has: the probe reads it", &ProbeInput::block,
     &ProbeInput::block_set},
};

} // namespace

std::string ProbesText(const Scene &s)
{
  std::string text;
  for (const Probe &p : s.loading.probes)
    text += s.body.dimension == 3 ? Format("  probe     %s at (%g, %g, %g) m\n", p.name.c_str(), p.x, p.y, p.z)
                             : Format("  probe     %s at (%g, %g) m\n", p.name.c_str(), p.x, p.y);
  return text;
}

SetFamily ProbeFamily() { return {"-probe_", "-probes", OptionRowSuffixes(kProbeOptions)}; }

PetscErrorCode ReadProbes(MPI_Comm comm, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Probes: points whose displacement is recorded", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.StringArray("-probes", "Names of the probes name1,name2,... (each probe P is placed by -probe_P_at)", &in->probe_names));
    return 0;
  }));
  PetscCall(CheckNames(comm, in->probe_names, "-probes", "probe"));
  for (const std::string &name : in->probe_names) {
    ProbeInput        probe;
    const std::string prefix = "probe_" + name + "_";
    const std::string title  = "Probe " + name;
    probe.name               = name;
    PetscCall(ReadOptionBlock(comm, prefix.c_str(), title.c_str(), [&](OptionReader &r) { return ReadOptionRows(r, kProbeOptions, &probe); }));
    in->probes.push_back(probe);
  }
  PetscFunctionReturn(0);
}

namespace {

// -probe_NAME_group: the position of a physical point (one node) of the Gmsh file.
PetscErrorCode ProbeAtGroup(MPI_Comm comm, const ProbeInput &pi, const Body<2> &body, Probe *p)
{
  const char *n = pi.name.c_str();
  PetscFunctionBeginUser;
  std::string file;
  PetscCall(GroupGmshFile(comm, pi.file, BodyGmshFiles(body), "probe", "probe", pi.name, "mesh shapes", pi.group, &file));
  GmshGroup         group;
  const std::string problem = ReadGmshGroup(file, pi.group, &group);
  SceneCheck(problem.empty(), comm, "-probe_%s_group %s: %s", n, pi.group.c_str(), problem.c_str());
  SceneCheck(group.dim == 0 && group.segments.size() == 4, comm,
             "-probe_%s_group %s: a probe is one point, but group '%s' of '%s' is %s: name a physical point of one node "
             "(Physical Point(\"%s\") = {k};), or place the probe by -probe_%s_at x,y",
             n, pi.group.c_str(), pi.group.c_str(), file.c_str(),
             group.dim == 2 ? "a physical surface" : group.dim == 1 ? "a physical curve" : "several points", pi.group.c_str(), n);
  p->x = group.segments[0], p->y = group.segments[1];
  PetscFunctionReturn(0);
}

// -probe_NAME_block: the position of the one given point with that block id.
PetscErrorCode ProbeAtBlock(MPI_Comm comm, const ProbeInput &pi, const Body<2> &body, Probe *p)
{
  const char *n = pi.name.c_str();
  PetscFunctionBeginUser;
  SceneCheck(body.given_points != nullptr, comm,
             "-probe_%s_block: block ids come with the points of a cloud (-body_cloud, column block_id), and this body is a lattice: "
             "place the probe by -probe_%s_at x,y",
             n, n);
  const std::vector<double> at = BlockPoints(body, static_cast<int64_t>(pi.block));
  SceneCheck(!at.empty(), comm, "-probe_%s_block %" PetscInt_FMT ": no point of '%s' has block id %" PetscInt_FMT " (its block ids: %s): give one of them",
             n, pi.block, body.given_points->source.c_str(), pi.block, BlockIdList(body).c_str());
  SceneCheck(at.size() == 2, comm,
             "-probe_%s_block %" PetscInt_FMT ": a probe is one point, but block %" PetscInt_FMT " has %zu points: give the probe its own block id, or "
             "place it by -probe_%s_at x,y",
             n, pi.block, pi.block, at.size() / 2, n);
  p->x = at[0], p->y = at[1];
  PetscFunctionReturn(0);
}

// A probe of a 3D body: -probe_NAME_at x,y,z on material (Body<3>'s solids keep it; for
// given points, within the points' extent), -probe_NAME_group (a Gmsh physical point),
// or -probe_NAME_block of a 3D cloud.
PetscErrorCode CheckProbe3D(MPI_Comm comm, const ProbeInput &pi, const BodySection &b, Probe *p)
{
  const char *n = pi.name.c_str();
  PetscFunctionBeginUser;
  if (!pi.group.empty()) { // a physical point (one node) of the body's Gmsh volume, or of -probe_NAME_file
    std::string file;
    PetscCall(GroupGmshFile(comm, pi.file, BodyGmshFiles(b.solid), "probe", "probe", pi.name, "mesh solids", pi.group, &file));
    nd::ElementRegion group;
    const std::string problem = ReadGmshGroup3D(file, pi.group, 0.0, &group);
    SceneCheck(problem.empty(), comm, "-probe_%s_group %s: %s", n, pi.group.c_str(), problem.c_str());
    SceneCheck(group.dim == 0 && group.segments.size() == 6, comm,
               "-probe_%s_group %s: a probe is one point, but group '%s' of '%s' is %s: name a physical point of one node "
               "(Physical Point(\"%s\") = {k};), or place the probe by -probe_%s_at x,y,z",
               n, pi.group.c_str(), pi.group.c_str(), file.c_str(),
               group.dim == 3   ? "a physical volume"
               : group.dim == 2 ? "a physical surface"
               : group.dim == 1 ? "a physical curve"
                                : "several points",
               pi.group.c_str(), n);
    p->x = group.segments[0], p->y = group.segments[1], p->z = group.segments[2];
    SceneCheck(b.solid.given_points || nd::body_contains(b.solid.solids, &group.segments[0]), comm,
               "-probe_%s_group %s at (%g, %g, %g) m lies where the body's solids leave no material: name a point on the body", n,
               pi.group.c_str(), p->x, p->y, p->z);
    PetscFunctionReturn(0);
  }
  if (pi.block_set) {
    SceneCheck(b.solid.given_points != nullptr, comm,
               "-probe_%s_block: block ids come with the points of a cloud (-body_cloud, column block_id), and this body is a lattice: "
               "place the probe by -probe_%s_at x,y,z",
               n, n);
    const std::vector<double> at = BlockPoints3D(b.solid.given_points->x, b.solid.given_block, static_cast<int64_t>(pi.block));
    SceneCheck(at.size() == 3, comm,
               "-probe_%s_block %" PetscInt_FMT ": a probe is one point, but block %" PetscInt_FMT " has %zu points in '%s' (its block ids: "
               "%s): give the probe its own block id, or place it by -probe_%s_at x,y,z",
               n, pi.block, pi.block, at.size() / 3, b.solid.source.c_str(), BlockIdList(b.solid.given_block).c_str(), n);
    p->x = at[0], p->y = at[1], p->z = at[2];
    PetscFunctionReturn(0);
  }
  SceneCheck(pi.at_set, comm, "-probe_%s_at is required for probe '%s': give its position x,y,z in m%s", n, n,
             MisspeltHint("-probe_" + pi.name + "_at").c_str());
  SceneCheck(pi.at.size() == 3, comm, "-probe_%s_at holds %zu numbers: a probe of a 3D body takes exactly three, x,y,z in m", n, pi.at.size());
  p->x = pi.at[0], p->y = pi.at[1], p->z = pi.at[2];
  const double tol = 1e-12 * std::max({b.solid_summary.hi[0] - b.solid_summary.lo[0], b.solid_summary.hi[1] - b.solid_summary.lo[1], b.solid_summary.hi[2] - b.solid_summary.lo[2]});
  bool         in_extent = true;
  for (int r = 0; r < 3; ++r) in_extent = in_extent && pi.at[r] >= b.solid_summary.lo[r] - tol && pi.at[r] <= b.solid_summary.hi[r] + tol;
  SceneCheck(in_extent, comm, "-probe_%s_at (%g, %g, %g) m lies outside the body [%g, %g] x [%g, %g] x [%g, %g] m: move it onto the body", n,
             p->x, p->y, p->z, b.solid_summary.lo[0], b.solid_summary.hi[0], b.solid_summary.lo[1], b.solid_summary.hi[1], b.solid_summary.lo[2], b.solid_summary.hi[2]);
  if (!b.solid.given_points)
    SceneCheck(nd::body_contains(b.solid.solids, pi.at.data()), comm,
               "-probe_%s_at (%g, %g, %g) m lies where the body's solids leave no material (outside the solids that add, or in one "
               "that subtracts): move it onto the body",
               n, p->x, p->y, p->z);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckProbes(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  const Body<2> &b = scene->body.sheet;
  PetscFunctionBeginUser;
  const double tol = 1e-12 * std::max(b.width, b.height);
  scene->loading.probes.clear();
  for (const ProbeInput &pi : in.probes) {
    const char *n = pi.name.c_str();
    SceneCheck(!(pi.at_set && !pi.group.empty()), comm, "probe '%s' has both -probe_%s_at and -probe_%s_group: give one of them", n, n, n);
    SceneCheck(!(pi.block_set && (pi.at_set || !pi.group.empty())), comm, "probe '%s' has both -probe_%s_block and -probe_%s_%s: give one of them",
               n, n, n, pi.at_set ? "at" : "group");
    Probe p = {pi.name, 0, 0};
    if (scene->body.dimension == 3) {
      PetscCall(CheckProbe3D(comm, pi, scene->body, &p));
      scene->loading.probes.push_back(p);
      continue;
    }
    if (!pi.group.empty()) PetscCall(ProbeAtGroup(comm, pi, b, &p));
    else if (pi.block_set) PetscCall(ProbeAtBlock(comm, pi, b, &p));
    else {
      SceneCheck(pi.at_set, comm, "-probe_%s_at is required for probe '%s': give its position x,y in m, or a Gmsh physical point by -probe_%s_group%s",
                 n, n, n, MisspeltHint("-probe_" + pi.name + "_at").c_str());
      SceneCheck(pi.at.size() == 2, comm, "-probe_%s_at holds %zu numbers: give exactly two, x,y in m", n, pi.at.size());
      p.x = pi.at[0], p.y = pi.at[1];
    }
    const std::string where = !pi.group.empty() ? "-probe_" + pi.name + "_group " + pi.group + " at"
                              : pi.block_set ? "-probe_" + pi.name + "_block " + std::to_string(pi.block) + " at"
                                             : "-probe_" + pi.name + "_at";
    const char       *w     = where.c_str();
    SceneCheck(p.x >= -tol && p.x <= b.width + tol && p.y >= -tol && p.y <= b.height + tol, comm,
               "%s (%g, %g) m lies outside the body [0, %g] x [0, %g] m: move it onto the body", w, p.x, p.y, b.width, b.height);
    const int hole = hole_containing(b, p.x, p.y);
    SceneCheck(hole < 0, comm,
               "%s (%g, %g) m lies inside hole %d, where there is no material: move it onto the body (a hole's edge is fine)", w, p.x,
               p.y, hole + 1);
    const int shape = b.shapes.empty() ? -1 : shape_removing(b.shapes, p.x, p.y);
    SceneCheck(shape < 0, comm, "%s (%g, %g) m lies where shape '%s' (%s) removed the material: move it onto the body", w, p.x,
               p.y, shape < 0 ? "" : b.shapes[shape].name.c_str(), shape < 0 ? "" : to_string(b.shapes[shape].op));
    scene->loading.probes.push_back(p);
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
