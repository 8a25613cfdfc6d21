// The force operator (force_operator.hpp): ghost exchange, positions, bond loop.
#include "bapd/solver/operators/force_operator.hpp"

#include <cstring>

#include "bapd/core/materials/models.hpp"

namespace bapd {

template <int D>
PetscErrorCode ForceOperator::Setup(MPI_Comm comm, const MaterialSection &force, const Layout &layout, const Families &families,
                                    const nd::BondGeometry<D> &geometry, const BondState &state,
                                    PetscLogStage stage_ghost, PetscLogStage stage_force)
{
  PetscFunctionBegin;
  comm_        = comm;
  layout_      = &layout;
  families_    = &families;
  stage_ghost_ = stage_ghost;
  stage_force_ = stage_force;
  dimension_   = D;
  nd::Workspace<D> &workspace = [this]() -> nd::Workspace<D> & {
    if constexpr (D == 2) return workspace2_;
    else return workspace3_;
  }();
  failed_          = &workspace.failed;
  workspace.volumetric               = force.volumetric; // -material_volumetric (volumetric.hpp)
  workspace.volumetric_stabilisation = force.volumetric_stabilisation * force.parameters.mu; // kappa [Pa]
  keep_warm_start_ = &workspace.keep_warm_start;
  const std::size_t nbonds = families.neighbour.size();
  c33_.assign(D == 2 ? nbonds : 0, 0.0); // the 2D models' C33 warm starts; a 3D model has none (c33 nullptr)
  bond_force_.assign(D * nbonds, 0.0);
  y_.assign(layout.cloud.x.begin(), layout.cloud.x.end());
  // The constitutive model is chosen here, once; inside the closure it is a concrete
  // type and the bond loop is compiled for it.
  const PointCloud          *cloud = &layout.cloud;
  const Families            *f     = &families;
  const nd::BondGeometry<D> *g     = &geometry;
  const BondState           *s     = &state;
  nd::Workspace<D>          *ws    = &workspace;
  // -force_form: both forms write t_ij per bond, and assemble_force_density turns
  // either into f_i (the energy-consistent t_ij make it -(1/V_i) dW/dy_i).
  const ForceForm form = force.force_form;
  auto choose = [&](const auto &model) {
    using Model  = std::decay_t<decltype(model)>;
    bond_forces_ = [this, form, cloud, f, g, s, ws, m = Model(model)](const double *y, double *c33, double *force_density) {
      const KernelStats stats = nd::compute_bond_forces<D>(form, m, *cloud, y, *f, *g, *s, c33, bond_force_.data(), *ws);
      nd::assemble_force_density<D>(*f, *cloud, bond_force_.data(), (std::size_t)layout_->n_owned, force_density);
      return stats;
    };
    point_energies_ = [this, cloud, f, g, s, ws, m = Model(model)](const double *y, double *energy) {
      nd::strain_energy<D>(m, *cloud, y, *f, *g, *s, c33_.data(), (std::size_t)layout_->n_owned, *ws, nullptr, energy);
    };
    bond_energies_ = [this, cloud, f, g, s, ws, m = Model(model)](const double *y, double *psi) {
      nd::bond_energies<D>(m, *cloud, y, *f, *g, *s, c33_.data(), (std::size_t)layout_->n_family(), *ws, psi);
    };
    listed_energies_ = [this, cloud, f, g, s, ws, m = Model(model)](const double *y, const std::size_t *points, std::size_t count,
                                                                    double *energy) {
      nd::listed_strain_energies<D>(m, *cloud, y, *f, *g, *s, c33_.data(), points, count, *ws, energy);
    };
  };
  if constexpr (D == 2) with_model(force.model, force.formulation, force.parameters, choose);
  else with_model_3d(force.model, force.parameters, choose);
  PetscCall(CreateGhostedVector<D>(comm, layout, &u_ghosted_));
  PetscFunctionReturn(0);
}

template PetscErrorCode ForceOperator::Setup<2>(MPI_Comm, const MaterialSection &, const Layout &, const Families &, const nd::BondGeometry<2> &,
                                                const BondState &, PetscLogStage, PetscLogStage);
template PetscErrorCode ForceOperator::Setup<3>(MPI_Comm, const MaterialSection &, const Layout &, const Families &, const nd::BondGeometry<3> &,
                                                const BondState &, PetscLogStage, PetscLogStage);

PetscErrorCode ForceOperator::UpdatePositions(const double *u_owned)
{
  Vec           local;
  const double *u;
  double       *ug;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_ghost_));
  PetscCall(VecGetArray(u_ghosted_, &ug));
  std::memcpy(ug, u_owned, sizeof(double) * dimension_ * layout_->n_owned);
  PetscCall(VecRestoreArray(u_ghosted_, &ug));
  PetscCall(VecGhostUpdateBegin(u_ghosted_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGhostUpdateEnd(u_ghosted_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(PetscLogStagePop());
  PetscCall(VecGhostGetLocalForm(u_ghosted_, &local));
  PetscCall(VecGetArrayRead(local, &u));
  const std::size_t n = (std::size_t)dimension_ * (std::size_t)layout_->n_local();
  const double     *x = layout_->cloud.x.data();
  for (std::size_t k = 0; k < n; ++k) y_[k] = x[k] + u[k];
  PetscCall(VecRestoreArrayRead(local, &u));
  PetscCall(VecGhostRestoreLocalForm(u_ghosted_, &local));
  PetscFunctionReturn(0);
}

PetscErrorCode ForceOperator::Kernel(const double *u_owned, double *force_density, double *c33, KernelStats *stats)
{
  PetscFunctionBegin;
  PetscCall(UpdatePositions(u_owned));
  PetscCall(PetscLogStagePush(stage_force_));
  *stats = bond_forces_(y_.data(), c33, force_density);
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

PetscErrorCode ForceOperator::Evaluate(const double *u_owned, double *force_density, WarmStart warm_start)
{
  PetscFunctionBegin;
  if (warm_start == WarmStart::commit) {
    PetscCall(Kernel(u_owned, force_density, c33_.data(), &stats_));
    PetscFunctionReturn(0);
  }
  PetscCall(EvaluateFrom(u_owned, force_density, c33_)); // reads the warm start, writes nothing back
  PetscFunctionReturn(0);
}

PetscErrorCode ForceOperator::EvaluateWithWarmStart(const double *u_owned, double *force_density, std::vector<double> &c33)
{
  KernelStats probe;

  PetscFunctionBegin;
  PetscCheck(c33.size() == c33_.size(), comm_, PETSC_ERR_ARG_SIZ, "EvaluateWithWarmStart: %zu warm starts for %zu bonds", c33.size(),
             c33_.size());
  PetscCall(Kernel(u_owned, force_density, c33.data(), &probe));
  PetscFunctionReturn(0);
}

PetscErrorCode ForceOperator::EvaluateFrom(const double *u_owned, double *force_density, const std::vector<double> &c33)
{
  KernelStats probe;

  PetscFunctionBegin;
  PetscCheck(c33.size() == c33_.size(), comm_, PETSC_ERR_ARG_SIZ, "EvaluateFrom: %zu warm starts for %zu bonds", c33.size(), c33_.size());
  // The kernel reads c33 and writes nothing back (ws.keep_warm_start: the const_cast is
  // never written through). The failed-bond list is the committed evaluation's, for the
  // breaking pass after the step: it is set aside (a swap of buffers, no allocation).
  kept_failed_.swap(*failed_);
  *keep_warm_start_         = true;
  const PetscErrorCode ierr = Kernel(u_owned, force_density, const_cast<double *>(c33.data()), &probe);
  *keep_warm_start_         = false;
  kept_failed_.swap(*failed_);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode ForceOperator::PointEnergies(const double *u_owned, double *energy)
{
  PetscFunctionBegin;
  PetscCall(UpdatePositions(u_owned));
  point_energies_(y_.data(), energy);
  PetscFunctionReturn(0);
}

} // namespace bapd
