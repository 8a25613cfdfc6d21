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
// Where each part lives (scene_input.hpp lists the sections):
//   options_reader.cpp   reading one option, the registry of names, warnings
//   options_unused.cpp   options nobody read, typo suggestions
//   scene_body.cpp       the sheet, holes, notches, horizon; the point estimate
//   scene_material.cpp   the constitutive model, its parameters, failure
//   scene_loading.cpp    grips and the stretch schedule
//   scene_probes.cpp     probes
//   scene_run.cpp        output and time stepping
//   scene_schedule.cpp   lambda(t) at run time
//   scene_selection.cpp  the points a load set or probe picks at run time
#include "bapd/scene.hpp"

#include <cmath>
#include <string>

#include "bapd/options_reader.hpp"
#include "bapd/scene_input.hpp"

namespace bapd {

const char *to_string(PatchCorrection c)
{
  switch (c) {
  case PatchCorrection::off: return "off";
  case PatchCorrection::lambda: return "on";
  case PatchCorrection::virial: return "virial";
  }
  return "unknown";
}

PetscErrorCode SceneFromOptions(MPI_Comm comm, Scene *scene)
{
  SceneInput in;
  PetscBool  help = PETSC_FALSE;
  PetscFunctionBeginUser;
  *scene = Scene();
  ClearWarnings();
  PetscCall(ReadBody(comm, scene, &in));
  PetscCall(ReadMaterial(comm, scene, &in));
  PetscCall(ReadLoading(comm, scene, &in));
  PetscCall(ReadProbes(comm, &in));
  PetscCall(ReadOutputTime(comm, scene, &in));

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
  PetscCall(CheckBodyFits(comm, *scene));
  PetscCall(CheckProbes(comm, in, scene));
  PetscCall(CheckOutputTime(comm, in, scene));
  PetscFunctionReturn(0);
}

PetscErrorCode SceneView(MPI_Comm comm, const Scene &s)
{
  const Body2D &b = s.body;
  std::string   text; // built with the C library's printf (see SceneCheck), printed once
  PetscFunctionBeginUser;
  if (s.help_only) PetscFunctionReturn(0);
  const EdgeRows &g = b.grip_rows;
  if (b.given_points) // (geometry.hpp: points with their own volumes and horizons)
    text += Format("Scene\n  body      %g m x %g m, thickness %g m: %ld points of %s (%zu given), spacing sqrt(V/t) from dx = %g m, %zu "
                   "hole(s), %zu notch(es)\n",
                   b.width, b.height, b.thickness, (long)ScenePointEstimate(s), b.given_points->source.c_str(), b.given_points->size(), b.dx,
                   b.holes.size(), b.notches.size());
  else text += Format("Scene\n  body      %g m x %g m, thickness %g m, dx %g m: %ld x %ld lattice%s, %ld points, %zu hole(s), %zu notch(es)\n",
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
  if (b.given_points) text += Format("  horizon   delta_i = %g h_i, h_i = sqrt(V_i / t) (at least %g m); a bond where either reaches\n", s.horizon_factor, s.horizon());
  else text += Format("  horizon   delta = %g dx = %g m\n", s.horizon_factor, s.horizon());
  const double K = 2.0 / s.material.D;
  text += Format("  material  %s, %s: mu %g Pa", to_string(s.model), to_string(s.formulation), s.material.mu);
  if (s.model == ModelKind::gent) text += Format(", Jm %g", s.material.Jm);
  text += Format(", D %g 1/Pa (bulk modulus K = 2/D = %g Pa = %g mu), density %g kg/m^3\n", s.material.D, K, K / s.material.mu, s.density);
  text += Format("  force     %s", to_string(s.force_form));
  if (s.stress_correction != StressCorrection::none) // (absent by default: the summary stays as it was)
    text += Format(", stress correction %s%s", to_string(s.stress_correction),
                   s.force_form == ForceForm::energy_consistent ? " (the identity for this form)" : "");
  if (s.patch_correction != PatchCorrection::off) text += Format(", patch correction %s", to_string(s.patch_correction));
  text += "\n";
  if (s.failure) text += Format("  failure   bonds break past stretch s_c = %g\n", s.critical_stretch);
  else text += "  failure   none\n";
  auto component = [](ComponentLoad c, double scale) {
    return c == ComponentLoad::stretch ? Format("stretch (scale %g)", scale) : std::string(to_string(c));
  };
  for (const LoadSet &l : s.loads) {
    std::string where;
    switch (l.region) {
    case LoadSet::Region::box: where = Format("box [%g, %g] x [%g, %g] m", l.box[0], l.box[2], l.box[1], l.box[3]); break;
    case LoadSet::Region::polygon: where = Format("polygon of %zu vertices", l.area.vertices.size() / 2); break;
    case LoadSet::Region::curve: where = Format("within %g m of a polyline of %zu segments", l.depth, l.segments.size() / 4); break;
    case LoadSet::Region::group:
      where = l.segments.empty() ? Format("physical surface '%s' of %s", l.group.c_str(), l.file.c_str())
                                 : Format("within %g m of physical group '%s' of %s", l.depth, l.group.c_str(), l.file.c_str());
      break;
    case LoadSet::Region::block: where = Format("block %lld of the cloud (%zu points)", static_cast<long long>(l.block), l.block_points.size() / 2); break;
    default: where = Format("%s edge, %d row(s) %s", to_string(l.region), l.layers, to_string(l.placement));
    }
    text += Format("  load set  %s: %s; x %s, y %s\n", l.name.c_str(), where.c_str(), component(l.x, l.x_scale).c_str(),
                   component(l.y, l.y_scale).c_str());
  }
  if (s.loads.empty()) text += "  load set  none\n";
  if (!s.schedule.time.empty()) {
    text += "  schedule  (t, lambda):";
    for (std::size_t k = 0; k < s.schedule.time.size(); ++k) text += Format(" (%g s, %g)", s.schedule.time[k], s.schedule.stretch[k]);
    text += Format("; u = scale (lambda - 1) %g m; grip field %s\n", s.reference_length, to_string(s.grip_field));
  }
  for (const Probe &p : s.probes) text += Format("  probe     %s at (%g, %g) m\n", p.name.c_str(), p.x, p.y);
  if (s.time_step > 0) text += Format("  time      step %g s", s.time_step);
  else text += Format("  time      step %g x the stable step", s.time_step_safety);
  if (s.time_step_travel > 0) text += Format(" (shorter while a point with bonds would move > %g dx a step)", s.time_step_travel);
  else if (s.time_step_travel < 0 && s.failure) text += " (shorter while a point with bonds would move > 0.1 dx a step)";
  text += Format(", damping %g 1/s, end %g s\n", s.damping, s.end_time);
  if (s.static_tolerance > 0)
    text += Format("  static    a hold ends once kinetic energy < %g x internal energy (checked at every history row)\n", s.static_tolerance);
  text += Format("  output    %s/, history every %ld steps\n", s.output_dir.c_str(), (long)s.output_interval);
  PetscCall(PetscPrintf(comm, "%s", text.c_str()));
  PetscFunctionReturn(0);
}

} // namespace bapd
