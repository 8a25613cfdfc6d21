// The tangent operator (tangent_operator.hpp): per-point Hessians into a PETSc matrix.
#include "bapd/solver/operators/tangent_operator.hpp"

#include <memory>
#include <vector>

#include "bapd/core/kernel/ba_tangent.hpp"
#include "bapd/core/materials/models.hpp"

namespace bapd {

template <int D>
PetscErrorCode TangentOperator::Setup(MPI_Comm comm, const Scene &scene, const Layout &layout, const Families &families,
                                      const nd::BondGeometry<D> &geometry, const BondState &state)
{
  PetscFunctionBegin;
  PetscCheck(scene.force_form == ForceForm::energy_consistent, comm, PETSC_ERR_USER,
             "-solver static needs -force_form energy_consistent (the default): the bond-only force is not the gradient of an "
             "energy, so it has no symmetric tangent and no energy to minimise");
  comm_      = comm;
  layout_    = &layout;
  dimension_ = D;
  auto ws        = std::make_shared<nd::TangentWorkspace<D>>();
  ws->volumetric = scene.volumetric;
  ws->kappa      = scene.volumetric_stabilisation * scene.material.mu;
  ws->reserve(families);
  auto index = std::make_shared<std::vector<PetscInt>>(families.max_family_size + 1);
  const PointCloud          *cloud = &layout.cloud;
  const Families            *f     = &families;
  const nd::BondGeometry<D> *g     = &geometry;
  const BondState           *s     = &state;
  const Layout              *l     = &layout;
  auto choose = [&](const auto &model) {
    using Model = std::decay_t<decltype(model)>;
    add_blocks_ = [ws, index, cloud, f, g, s, l, m = Model(model)](const double *y, const double *c33, Mat H, bool values,
                                                                    PetscInt *failed) -> PetscErrorCode {
      PetscFunctionBegin;
      *failed = 0;
      for (PetscInt i = 0; i < l->n_owned; ++i) {
        const std::size_t o = f->offsets[i], n = f->size(i) + 1;
        (*index)[0] = l->petsc_index[i];
        for (std::size_t p = 0; p + 1 < n; ++p) (*index)[1 + p] = l->petsc_index[f->neighbour[o + p]];
        if (values) *failed += (PetscInt)nd::point_tangent<D>(m, *cloud, y, *f, *g, *s, c33, (std::size_t)i, *ws);
        else std::fill(ws->H.begin(), ws->H.begin() + n * n * D * D, 0.0);
        PetscCall(MatSetValuesBlocked(H, (PetscInt)n, index->data(), (PetscInt)n, index->data(), ws->H.data(), ADD_VALUES));
      }
      PetscFunctionReturn(0);
    };
  };
  if constexpr (D == 2) with_model(scene.model, scene.formulation, scene.material, choose);
  else with_model_3d(scene.model, scene.material, choose);
  PetscFunctionReturn(0);
}

template PetscErrorCode TangentOperator::Setup<2>(MPI_Comm, const Scene &, const Layout &, const Families &, const nd::BondGeometry<2> &,
                                                  const BondState &);
template PetscErrorCode TangentOperator::Setup<3>(MPI_Comm, const Scene &, const Layout &, const Families &, const nd::BondGeometry<3> &,
                                                  const BondState &);

PetscErrorCode TangentOperator::CreateMatrix(Mat *H) const
{
  Mat            pattern;
  PetscInt       failed;
  const PetscInt n = dimension_ * layout_->n_owned;

  PetscFunctionBegin;
  PetscCall(MatCreate(comm_, &pattern));
  PetscCall(MatSetSizes(pattern, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(pattern, dimension_));
  PetscCall(MatSetType(pattern, MATPREALLOCATOR));
  PetscCall(MatSetUp(pattern));
  PetscCall(add_blocks_(layout_->cloud.x.data(), nullptr, pattern, false, &failed));
  PetscCall(MatAssemblyBegin(pattern, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(pattern, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreate(comm_, H));
  PetscCall(MatSetSizes(*H, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(*H, dimension_));
  PetscCall(MatSetType(*H, MATBAIJ));
  PetscCall(MatSetOptionsPrefix(*H, nullptr));
  PetscCall(MatSetFromOptions(*H)); // -mat_type
  PetscCall(MatPreallocatorPreallocate(pattern, PETSC_TRUE, *H));
  PetscCall(MatDestroy(&pattern));
  PetscCall(MatSetOption(*H, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(*H, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PetscCall(MatSetOption(*H, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode TangentOperator::Assemble(const double *y, const double *c33, Mat H, PetscInt *failed) const
{
  PetscInt mine;

  PetscFunctionBegin;
  PetscCall(MatZeroEntries(H));
  PetscCall(add_blocks_(y, c33, H, true, &mine));
  PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
  PetscCallMPI(MPI_Allreduce(&mine, failed, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

} // namespace bapd
