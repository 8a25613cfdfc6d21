// Families (family.hpp). The builder is the dimension-generic one (nd/family.hpp,
// nd_family.cpp) at D = 2, with the notch segments as its bond cut: one cell search
// for 2D and 3D (issue 21 stage 2; it gives the former 2D builder's arrays bit for bit).
#include "bapd/family.hpp"

#include <limits>

#include "bapd/nd/family.hpp"

namespace bapd {

namespace {

// Orientation of c relative to the directed line a -> b (twice the signed area).
inline double orientation(double ax, double ay, double bx, double by, double cx, double cy)
{
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

} // namespace

bool segments_cross(double ax, double ay, double bx, double by, const Segment &s)
{
  const double o1 = orientation(ax, ay, bx, by, s.x0, s.y0);
  const double o2 = orientation(ax, ay, bx, by, s.x1, s.y1);
  const double o3 = orientation(s.x0, s.y0, s.x1, s.y1, ax, ay);
  const double o4 = orientation(s.x0, s.y0, s.x1, s.y1, bx, by);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

Families build_families(const PointCloud &cloud, std::size_t n_family, double horizon,
                        const std::vector<Segment> &notches)
{
  nd::BondCut cut; // empty without notches: no call per bond
  if (!notches.empty())
    cut = [&notches](const double *a, const double *b) {
      for (const Segment &s : notches)
        if (segments_cross(a[0], a[1], b[0], b[1], s)) return true;
      return false;
    };
  return nd::build_families<2>(cloud, n_family, horizon, cut);
}

void compute_family_volumes(PointCloud &cloud, const Families &families)
{
  if (cloud.family_volume.size() != cloud.size())
    cloud.family_volume.resize(cloud.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < families.n_family; ++i) {
    double v = 0.0;
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      v += cloud.volume[static_cast<std::size_t>(families.neighbour[b])];
    cloud.family_volume[i] = v;
  }
}

} // namespace bapd
