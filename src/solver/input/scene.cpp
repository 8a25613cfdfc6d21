// Scene configuration: every option of a run, read in one PetscOptionsBegin block
// per component (so -help lists them with units and defaults), then checked as a
// whole before any work is done. Each rejected value gets one message that names
// the option and the fix. Every name read is remembered, so that an option nobody
// read (a typo) can be answered with the nearest real one (CheckUnusedOptions).
//
// Reading and checking are separate passes: with -help every block is listed even
// when the scene is incomplete, and the checks, which need the whole scene (a probe
// must lie in the body, a stretch grip needs a schedule), see it all at once.
//
// Each section is read (Read*) and checked (Check*) by its file, which also writes its
// lines of SceneText (MaterialText, LoadingText, ProbesText, TimeSteppingText,
// OutputText; the body's are written here). Where each part lives (scene_input.hpp
// lists the sections):
//   options_reader.cpp   reading one option, the registry of names, warnings
//   options_unused.cpp   options nobody read, typo suggestions
//   scene_body.cpp       the sheet, holes, notches, horizon; the point estimate
//   scene_body_memory.cpp  whether the body fits in memory
//   scene_material.cpp   the constitutive model, its parameters, failure
//   scene_loading.cpp    grips and the stretch schedule
//   scene_probes.cpp     probes
//   scene_output.cpp     output: history, fields, checkpoints
//   scene_run.cpp        the solver, partition, static solver
//   scene_time_stepping.cpp  the time step, its re-estimate, damping, the run's end
//   scene_schedule.cpp   lambda(t) at run time
//   scene_selection.cpp  the points a load set or probe picks at run time
#include "bapd/solver/input/scene.hpp"

#include <cmath>
#include <string>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

const char *to_string(PatchCorrection c)
{
  static const char *const words[] = {"off", "on", "virial"}; // in the enum's order
  return words[static_cast<int>(c)];
}

std::vector<SetFamily> SetFamilies() { return {ShapeFamily(), LoadSetFamily(), ProbeFamily()}; }

namespace {

// -help's note on the options of named sets: listed above for the names given, and
// here by family (from the sets' option tables), so that a scene without any still
// shows them.
std::string SetFamiliesHelp()
{
  std::string text = "  Options of named sets, listed above for the names given in -body_shapes, -load_sets and -probes "
                     "(docs/options.md: Body, Loading, Probes):\n";
  for (const SetFamily &family : SetFamilies()) {
    text += "    " + family.head + "NAME_{";
    for (std::size_t k = 0; k < family.suffixes.size(); ++k) text += (k ? "," : "") + family.suffixes[k].substr(1);
    text += "}  (NAME in " + family.list_option + ")\n";
  }
  return text;
}

} // namespace

PetscErrorCode SceneFromOptions(MPI_Comm comm, Scene *scene)
{
  SceneInput in;
  PetscBool  help = PETSC_FALSE;
  PetscFunctionBeginUser;
  *scene = Scene();
  ClearWarnings();
  PetscCall(ReadBody(comm, &scene->body, &in));
  PetscCall(ReadMaterial(comm, &scene->material, &scene->failure, &in));
  PetscCall(ReadLoading(comm, &scene->loading, &in));
  PetscCall(ReadProbes(comm, &in));
  PetscCall(ReadOutput(comm, &scene->output, &in));
  PetscCall(ReadRun(comm, &scene->run, &in));
  PetscCall(ReadTimeStepping(comm, &scene->time_stepping, &in));

  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help) {
    scene->help_only = true;
    PetscCall(PetscPrintf(comm, "%s", SetFamiliesHelp().c_str()));
    PetscFunctionReturn(0);
  }
  PetscCall(CheckBody(comm, in, scene));
  PetscCall(CheckMaterial(comm, in, scene));
  PetscCall(CheckLoading(comm, in, scene));
  // The body is complete once the load sets are checked: the grips placed outside the
  // sheet add rows beyond its edges, and the memory check counts their points too.
  scene->body.sheet.grip_rows = OutsideGripRows(scene->loading);
  PetscCall(CheckBodyFits(comm, *scene));
  PetscCall(CheckProbes(comm, in, scene));
  PetscCall(CheckOutput(comm, in, scene));
  PetscCall(CheckRun(comm, in, scene));
  PetscCall(CheckTimeStepping(comm, in, scene));
  PetscFunctionReturn(0);
}

namespace {

// The horizon line: the lattice's one horizon, or given points' own (geometry.hpp:
// delta_i = factor h_i, h_i = `spacing`; s.body.horizon() is the smallest, of the smallest
// spacing, Body<2>::dx).
std::string HorizonText(const Scene &s, bool given_points, const char *spacing)
{
  if (given_points)
    return Format("  horizon   delta_i = %g h_i, h_i = %s (at least %g m); a bond where either reaches\n", s.body.horizon_factor, spacing,
                  s.body.horizon());
  return Format("  horizon   delta = %g dx = %g m\n", s.body.horizon_factor, s.body.horizon());
}

// The body and horizon lines of a 2D sheet: its size, lattice (or given points), holes,
// shapes and notches.
std::string BodyText2D(const Scene &s)
{
  const Body<2>   &b = s.body.sheet;
  const EdgeRows &g = b.grip_rows;
  std::string     text;
  if (b.given_points) // (geometry.hpp: points with their own volumes and horizons)
    text += Format("  body      %g m x %g m, thickness %g m: %ld points of %s (%zu given), spacing sqrt(V/t) from dx = %g m, %zu "
                   "hole(s), %zu notch(es)\n",
                   b.width, b.height, b.thickness, (long)ScenePointEstimate(s), b.given_points->source.c_str(), b.given_points->size(), b.dx,
                   b.holes.size(), b.notches.size());
  else text += Format("  body      %g m x %g m, thickness %g m, dx %g m: %ld x %ld lattice%s, %ld points, %zu hole(s), %zu notch(es)\n",
                 b.width, b.height, b.thickness, b.dx, std::lround(b.width / b.dx), std::lround(b.height / b.dx),
                 g.any() ? Format(" + grip rows outside (%ld top, %ld bottom, %ld left, %ld right)", (long)g.top, (long)g.bottom,
                                  (long)g.left, (long)g.right)
                               .c_str()
                         : "",
                 (long)ScenePointEstimate(s), b.holes.size(), b.notches.size());
  for (const Circle &c : b.holes) text += Format("            hole centre (%g, %g) m, radius %g m\n", c.cx, c.cy, c.radius);
  for (const Shape &sh : b.shapes) {
    std::string where;
    switch (sh.kind) {
    case Shape::Kind::rectangle: where = Format("[%g, %g] x [%g, %g] m", sh.box[0], sh.box[2], sh.box[1], sh.box[3]); break;
    case Shape::Kind::circle: where = Format("centre (%g, %g) m, radius %g m", sh.cx, sh.cy, sh.a); break;
    case Shape::Kind::ellipse:
      where = Format("centre (%g, %g) m, semi-axes %g m, %g m at %g deg", sh.cx, sh.cy, sh.a, sh.b, sh.angle * 180.0 / M_PI);
      break;
    case Shape::Kind::polygon: where = Format("%zu vertices, area %g m^2", sh.vertices.size() / 2, shape_area(sh)); break;
    case Shape::Kind::mesh: where = Format("%s: %zu triangles, area %g m^2", sh.file.c_str(), sh.triangles.size(), shape_area(sh)); break;
    }
    const char *article = sh.kind == Shape::Kind::ellipse ? "an" : "a";
    text += Format("            shape %s: %s %s %s, %s\n", sh.name.c_str(), to_string(sh.op), article, to_string(sh.kind), where.c_str());
  }
  for (const Segment &g : b.notches) text += Format("            notch (%g, %g)-(%g, %g) m\n", g.x0, g.y0, g.x1, g.y1);
  return text + HorizonText(s, b.given_points != nullptr, "sqrt(V_i / t)");
}

// The body and horizon lines of a 3D body: the lattice or the cloud, the extent of the
// points' cells (the faces the load sets hold), each solid and notch by name.
std::string BodyText3D(const Scene &s)
{
  const Body<3>      &b = s.body.solid;
  const SolidSummary &m = s.body.solid_summary;
  std::string         text;
  const std::string extent =
      Format("[%g, %g] x [%g, %g] x [%g, %g] m", m.lo[0], m.hi[0], m.lo[1], m.hi[1], m.lo[2], m.hi[2]);
  if (b.given_points)
    text += Format("  body      3D: %lld %s of %s (spacing cbrt(V), the smallest %g m), cells in %s, %zu solid(s) cutting them, %zu "
                   "notch(es)\n",
                   static_cast<long long>(m.points), b.centroids ? "tetrahedron centroids" : "points", b.source.c_str(), b.dx,
                   extent.c_str(), b.solids.size() - (b.centroids ? 1 : 0), b.notches.size());
  else
    text += Format("  body      3D, dx %g m: %lld points, cells in %s, %zu solid(s), %zu notch(es)\n", b.dx,
                   static_cast<long long>(m.points), extent.c_str(), b.solids.size(), b.notches.size());
  for (std::size_t k = 0; k < b.solids.size(); ++k) {
    const nd::Solid &solid = b.solids[k];
    std::string      where;
    switch (solid.kind) {
    case nd::Solid::Kind::box:
      where = Format("[%g, %g] x [%g, %g] x [%g, %g] m", solid.lo[0], solid.hi[0], solid.lo[1], solid.hi[1], solid.lo[2], solid.hi[2]);
      break;
    case nd::Solid::Kind::cylinder:
      where = Format("axis (%g, %g, %g)-(%g, %g, %g) m, radius %g m", solid.a[0], solid.a[1], solid.a[2], solid.b[0], solid.b[1], solid.b[2],
                     solid.radius);
      break;
    case nd::Solid::Kind::sphere: where = Format("centre (%g, %g, %g) m, radius %g m", solid.a[0], solid.a[1], solid.a[2], solid.radius); break;
    case nd::Solid::Kind::mesh:
      where = Format("%s: %zu tetrahedra, volume %g m^3", solid.mesh->file.c_str(), solid.mesh->size(), nd::solid_volume(solid));
      break;
    }
    const std::string name = k < m.solid_names.size() ? m.solid_names[k] : std::to_string(k + 1);
    text += Format("            solid %s: %s a %s, %s\n", name.c_str(), to_string(solid.op), nd::to_string(solid.kind), where.c_str());
  }
  for (std::size_t k = 0; k < b.notches.size(); ++k) {
    const std::vector<double> &v    = b.notches[k].vertices;
    const std::string          name = k < m.notch_names.size() ? m.notch_names[k] : std::to_string(k + 1);
    std::string                corners;
    for (std::size_t c = 0; c + 3 <= v.size(); c += 3) corners += Format(" (%g, %g, %g)", v[c], v[c + 1], v[c + 2]);
    text += Format("            notch %s: a planar polygon of %zu vertices,%s m\n", name.c_str(), v.size() / 3, corners.c_str());
  }
  return text + HorizonText(s, b.given_points != nullptr, "cbrt(V_i)");
}

} // namespace

std::string SceneText(const Scene &s)
{
  // built with the C library's printf (see SceneCheck), printed once by SceneView; each
  // section's lines from the section (scene_input.hpp)
  std::string text = "Scene\n";
  text += s.body.dimension == 3 ? BodyText3D(s) : BodyText2D(s);
  return text + MaterialText(s) + LoadingText(s) + ProbesText(s) + TimeSteppingText(s) + OutputText(s.output);
}

PetscErrorCode SceneView(MPI_Comm comm, const Scene &s)
{
  PetscFunctionBeginUser;
  if (s.help_only) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(comm, "%s", SceneText(s).c_str()));
  PetscFunctionReturn(0);
}

} // namespace bapd
