// The probes section: named points whose displacement is recorded (-probes,
// -probe_NAME_at). A probe must lie on material: in the body and outside every hole
// (the hole rule of lattice.hpp). Which point it reads at run time: ProbeLocate
// (scene_selection.cpp).
#include <algorithm>
#include <string>

#include "bapd/lattice.hpp"
#include "bapd/options_reader.hpp"
#include "bapd/scene_input.hpp"

namespace bapd {

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
    PetscCall(ReadOptionBlock(comm, prefix.c_str(), title.c_str(), [&](OptionReader &r) -> PetscErrorCode {
      PetscCall(r.RealArray("-at", "Position x,y [m]; the nearest material point is recorded (required)", &probe.at, &probe.at_set));
      return 0;
    }));
    in->probes.push_back(probe);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckProbes(MPI_Comm comm, const SceneInput &in, Scene *scene)
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
    const int hole = hole_containing(b, p.x, p.y);
    SceneCheck(hole < 0, comm,
               "-probe_%s_at (%g, %g) m lies inside hole %d, where there is no material: move it onto the body (a hole's edge is fine)", n, p.x,
               p.y, hole + 1);
    const int shape = b.shapes.empty() ? -1 : shape_removing(b.shapes, p.x, p.y);
    SceneCheck(shape < 0, comm, "-probe_%s_at (%g, %g) m lies where shape '%s' (%s) removed the material: move it onto the body", n, p.x,
               p.y, shape < 0 ? "" : b.shapes[shape].name.c_str(), shape < 0 ? "" : to_string(b.shapes[shape].op));
    scene->probes.push_back(p);
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
