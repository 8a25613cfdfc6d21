// Per-point stress, deformation and energy for output (point_quantities.hpp).
#include "bapd/core/kernel/point_quantities.hpp"

#include "bapd/core/materials/models.hpp"

namespace bapd {

void point_quantities(ModelKind kind, Formulation formulation, const MaterialParameters &material,
                      const PointCloud &cloud, const double *y, const Families &families,
                      const nd::BondGeometry<2> &geometry,
                      const BondState &state, const double *c33, std::size_t n_points, StressWeights weights,
                      PointQuantities &out, Volumetric volumetric,
                      double stabilisation)
{
  with_model(kind, formulation, material, [&](const auto &model) {
    point_quantities(model, cloud, y, families, geometry, state, c33, n_points, weights, out, volumetric, stabilisation);
  });
}

void point_quantities(ModelKind kind, Formulation, const MaterialParameters &material, const PointCloud &cloud, const double *y,
                      const Families &families, const nd::BondGeometry<3> &geometry, const BondState &state, const double *c33,
                      std::size_t n_points, StressWeights weights, PointQuantities &out, Volumetric volumetric,
                      double stabilisation)
{
  with_model_3d(kind, material, [&](const auto &model) {
    point_quantities(model, cloud, y, families, geometry, state, c33, n_points, weights, out, volumetric, stabilisation);
  });
}

} // namespace bapd
