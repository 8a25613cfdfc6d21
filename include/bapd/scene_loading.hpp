#pragma once
// Grips (load sets, -load_sets): which points a grip holds and how each component
// moves. Included by scene.hpp.
#include <petscsys.h>
#include <string>
#include <vector>

namespace bapd {

struct Scene;

enum class ComponentLoad { free, fixed, stretch };

// How a top or bottom grip moves the y component of its points (-load_grip_field;
// issue 14 item 2, docs/stress_consistency.md): rigid, every point of the grip by the
// same u (the default), or affine, the grip's points on the affine continuation of the
// free region's mean stretch, u = u_rigid + (lambda - 1) (L / L_free) (y - y_inner),
// y_inner the grip's inner boundary, L_free the distance between the two grips'
// inner boundaries. The free points next to a grip then see no kink of the
// displacement within their horizon.
enum class GripField { rigid, affine };

// A named set of points held by a grip. Per component: free, fixed (u = 0) or
// following the stretch schedule, u = scale * (lambda(t) - 1) * reference_length.
struct LoadSet {
  enum class Region { top, bottom, left, right, box };
  std::string   name;
  Region        region = Region::top;
  double        box[4] = {0, 0, 0, 0}; // xmin, ymin, xmax, ymax (Region::box)
  int           layers = 1;            // point layers taken from the named edge
  ComponentLoad x = ComponentLoad::free, y = ComponentLoad::free;
  double        x_scale = 0.0, y_scale = 0.0;
};

// The local points (reference positions x, 2 per point, n points) that a load set
// holds: within `layers` layers of its edge (top: y > height - layers*dx, bottom:
// y < layers*dx, left: x < layers*dx, right: x > width - layers*dx) or inside its
// box (edges included). Indices into x, increasing. Pass owned points only; whether
// a set holds any point at all is for the caller to check over the communicator.
PetscErrorCode LoadSetSelect(const Scene &scene, const LoadSet &set, const double *x, PetscInt n,
                             std::vector<PetscInt> *selected);

const char *to_string(LoadSet::Region region);
const char *to_string(ComponentLoad load);

} // namespace bapd
