// Per-point stress, deformation and energy for output (point_quantities.hpp).
#include "bapd/core/kernel/point_quantities.hpp"

#include "bapd/core/materials/models.hpp"

namespace bapd {

template <int D>
void point_quantities(ModelKind kind, Formulation formulation, const MaterialParameters &material, const PointCloud &cloud,
                      const double *y, const Families &families, const nd::BondGeometry<D> &geometry, const BondState &state,
                      const double *c33, std::size_t n_points, StressWeights weights, PointQuantities &out,
                      Volumetric volumetric, double stabilisation)
{
  const auto run = [&](const auto &model) {
    point_quantities(model, cloud, y, families, geometry, state, c33, n_points, weights, out, volumetric, stabilisation);
  };
  if constexpr (D == 2) with_model(kind, formulation, material, run);
  else with_model_3d(kind, material, run);
}

#define BAPD_POINT_QUANTITIES(D)                                                                                                 \
  template void point_quantities<D>(ModelKind, Formulation, const MaterialParameters &, const PointCloud &, const double *,     \
                                    const Families &, const nd::BondGeometry<D> &, const BondState &, const double *,          \
                                    std::size_t, StressWeights, PointQuantities &, Volumetric, double);
BAPD_POINT_QUANTITIES(2)
BAPD_POINT_QUANTITIES(3)
#undef BAPD_POINT_QUANTITIES

} // namespace bapd
