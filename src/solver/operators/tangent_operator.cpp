// The tangent operator (tangent_operator.hpp): per-point Hessians into a PETSc matrix.
#include "bapd/solver/operators/tangent_operator.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include "bapd/core/kernel/ba_tangent.hpp"
#include "bapd/core/materials/models.hpp"

namespace bapd {

template <int D>
PetscErrorCode TangentOperator::Setup(MPI_Comm comm, const MaterialSection &force, const Layout &layout, const Families &families,
                                      const nd::BondGeometry<D> &geometry, const BondState &state)
{
  PetscFunctionBegin;
  PetscCheck(force.force_form == ForceForm::energy_consistent, comm, PETSC_ERR_USER,
             "-solver static needs -force_form energy_consistent (the default): the bond-only force is not the gradient of an "
             "energy, so it has no symmetric tangent and no energy to minimise");
  comm_      = comm;
  layout_    = &layout;
  families_  = &families;
  dimension_ = D;
  auto ws        = std::make_shared<nd::TangentWorkspace<D>>();
  ws->volumetric = force.volumetric;
  ws->kappa      = force.volumetric_stabilisation * force.parameters.mu;
  ws->reserve(families);
  // Per point: its block's points by increasing PETSc index (the order PETSc's row search
  // is fastest in), and the block permuted to that order.
  auto index  = std::make_shared<std::vector<PetscInt>>(families.max_family_size + 1);
  auto order  = std::make_shared<std::vector<std::size_t>>(families.max_family_size + 1);
  auto sorted = std::make_shared<std::vector<double>>(ws->H.size());
  const PointCloud          *cloud = &layout.cloud;
  const Families            *f     = &families;
  const nd::BondGeometry<D> *g     = &geometry;
  const BondState           *s     = &state;
  const Layout              *l     = &layout;
  auto choose = [&](const auto &model) {
    using Model = std::decay_t<decltype(model)>;
    add_blocks_ = [ws, index, order, sorted, cloud, f, g, s, l, law = law_tangent_, m = Model(model)](const double *y, const double *c33, Mat H,
                                                                                            PetscInt *failed) -> PetscErrorCode {
      PetscFunctionBegin;
      *failed         = 0;
      ws->law_tangent = *law;
      std::vector<std::size_t> &k = *order;
      for (PetscInt i = 0; i < l->n_owned; ++i) {
        const std::size_t o = f->offsets[i], n = f->size(i) + 1, N = D * n;
        auto petsc = [&](std::size_t a) { return l->petsc_index[a == 0 ? (std::size_t)i : (std::size_t)f->neighbour[o + a - 1]]; };
        for (std::size_t a = 0; a < n; ++a) k[a] = a;
        std::sort(k.begin(), k.begin() + n, [&](std::size_t a, std::size_t b) { return petsc(a) < petsc(b); });
        for (std::size_t a = 0; a < n; ++a) (*index)[a] = petsc(k[a]);
        *failed += (PetscInt)nd::point_tangent<D>(m, *cloud, y, *f, *g, *s, c33, (std::size_t)i, *ws);
        for (std::size_t a = 0; a < n; ++a)
          for (int r = 0; r < D; ++r) {
            const double *row = &ws->H[(D * k[a] + r) * N];
            double       *out = &(*sorted)[(D * a + r) * N];
            for (std::size_t b = 0; b < n; ++b)
              for (int c = 0; c < D; ++c) out[D * b + c] = row[D * k[b] + c];
          }
        PetscCall(MatSetValuesBlocked(H, (PetscInt)n, index->data(), (PetscInt)n, index->data(), sorted->data(), ADD_VALUES));
      }
      PetscFunctionReturn(0);
    };
  };
  if constexpr (D == 2) with_model(force.model, force.formulation, force.parameters, choose);
  else with_model_3d(force.model, force.parameters, choose);
  PetscFunctionReturn(0);
}

template PetscErrorCode TangentOperator::Setup<2>(MPI_Comm, const MaterialSection &, const Layout &, const Families &, const nd::BondGeometry<2> &,
                                                  const BondState &);
template PetscErrorCode TangentOperator::Setup<3>(MPI_Comm, const MaterialSection &, const Layout &, const Families &, const nd::BondGeometry<3> &,
                                                  const BondState &);

// The pattern: owned point i adds S_i x S_i blocks, S_i = {i} and its family, so the
// block row of a local point a holds the union of the S_i that contain a. Each row's
// union is formed here (a stamp per local point) and inserted once, rather than every
// point's whole block (its family size squared insertions into MATPREALLOCATOR's hash).
PetscErrorCode TangentOperator::InsertPattern(Mat pattern) const
{
  const Layout   &l = *layout_;
  const Families &f = *families_;
  const std::size_t n_local = (std::size_t)l.n_local();

  PetscFunctionBegin;
  // contributors[a]: the owned i with a in S_i (CSR)
  std::vector<std::size_t> start(n_local + 1, 0);
  for (PetscInt i = 0; i < l.n_owned; ++i) {
    ++start[(std::size_t)i + 1];
    for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) ++start[(std::size_t)f.neighbour[b] + 1];
  }
  for (std::size_t a = 0; a < n_local; ++a) start[a + 1] += start[a];
  std::vector<std::size_t> contributors(start[n_local]), next(start.begin(), start.end() - 1);
  for (PetscInt i = 0; i < l.n_owned; ++i) {
    contributors[next[(std::size_t)i]++] = (std::size_t)i;
    for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) contributors[next[(std::size_t)f.neighbour[b]]++] = (std::size_t)i;
  }
  std::vector<std::size_t> stamp(n_local, n_local);
  std::vector<PetscInt>    columns;
  std::vector<double>      zeros;
  for (std::size_t a = 0; a < n_local; ++a) {
    if (start[a] == start[a + 1]) continue;
    columns.clear();
    auto add = [&](std::size_t c) {
      if (stamp[c] == a) return;
      stamp[c] = a;
      columns.push_back(l.petsc_index[c]);
    };
    for (std::size_t k = start[a]; k < start[a + 1]; ++k) {
      const std::size_t i = contributors[k];
      add(i);
      for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) add((std::size_t)f.neighbour[b]);
    }
    std::sort(columns.begin(), columns.end());
    const std::size_t values = columns.size() * (std::size_t)(dimension_ * dimension_);
    if (zeros.size() < values) zeros.resize(values, 0.0);
    const PetscInt row = l.petsc_index[a];
    PetscCall(MatSetValuesBlocked(pattern, 1, &row, (PetscInt)columns.size(), columns.data(), zeros.data(), ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TangentOperator::CreateMatrix(Mat *H) const
{
  Mat            pattern;
  const PetscInt n = dimension_ * layout_->n_owned;

  PetscFunctionBegin;
  PetscCall(MatCreate(comm_, &pattern));
  PetscCall(MatSetSizes(pattern, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(pattern, dimension_));
  PetscCall(MatSetType(pattern, MATPREALLOCATOR));
  PetscCall(MatSetUp(pattern));
  PetscCall(InsertPattern(pattern));
  PetscCall(MatAssemblyBegin(pattern, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(pattern, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreate(comm_, H));
  PetscCall(MatSetSizes(*H, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(*H, dimension_));
  PetscCall(MatSetType(*H, MATBAIJ)); // D x D blocks: each insertion one search (the static solver hands an AIJ copy to the preconditioner)
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
  PetscCall(add_blocks_(y, c33, H, &mine));
  PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
  PetscCallMPI(MPI_Allreduce(&mine, failed, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

} // namespace bapd
