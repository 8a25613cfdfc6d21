// The force operator (force_operator.hpp): ghost exchange, positions, bond loop.
#include "bapd/force_operator.hpp"

#include <cstring>

#include "bapd/models.hpp"

namespace bapd {

PetscErrorCode ForceOperator::Setup(MPI_Comm comm, const Scene &scene, const Layout &layout, const Families &families,
                                    const nd::BondGeometry<2> &geometry, const BondState &state,
                                    PetscLogStage stage_ghost, PetscLogStage stage_force)
{
  PetscFunctionBegin;
  comm_        = comm;
  layout_      = &layout;
  families_    = &families;
  stage_ghost_ = stage_ghost;
  stage_force_ = stage_force;
  const std::size_t nbonds = families.neighbour.size();
  c33_.assign(nbonds, 0.0);
  bond_force_.assign(2 * nbonds, 0.0);
  y_.assign(layout.cloud.x.begin(), layout.cloud.x.end());
  // The constitutive model is chosen here, once; inside the closure it is a concrete
  // type and the bond loop is compiled for it.
  const PointCloud          *cloud = &layout.cloud;
  const Families            *f     = &families;
  const nd::BondGeometry<2> *g     = &geometry;
  const BondState           *s     = &state;
  // -force_form: both forms write t_ij per bond, and assemble_force_density turns
  // either into f_i (the energy-consistent t_ij make it -(1/V_i) dW/dy_i).
  const ForceForm form = scene.force_form;
  with_model(scene.model, scene.formulation, scene.material, [&](const auto &model) {
    using Model  = std::decay_t<decltype(model)>;
    bond_forces_ = [this, form, cloud, f, g, s, m = Model(model)](const double *y, double *c33) {
      return nd::compute_bond_forces<2>(form, m, *cloud, y, *f, *g, *s, c33, bond_force_.data(), workspace_);
    };
    point_energies_ = [this, cloud, f, g, s, m = Model(model)](const double *y, double *energy) {
      nd::strain_energy<2>(m, *cloud, y, *f, *g, *s, c33_.data(), (std::size_t)layout_->n_owned, workspace_, nullptr,
                           energy);
    };
  });
  PetscCall(CreateGhostedVector<2>(comm, layout, &u_ghosted_));
  PetscFunctionReturn(0);
}

PetscErrorCode ForceOperator::UpdatePositions(const double *u_owned)
{
  Vec           local;
  const double *u;
  double       *ug;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_ghost_));
  PetscCall(VecGetArray(u_ghosted_, &ug));
  std::memcpy(ug, u_owned, sizeof(double) * 2 * layout_->n_owned);
  PetscCall(VecRestoreArray(u_ghosted_, &ug));
  PetscCall(VecGhostUpdateBegin(u_ghosted_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGhostUpdateEnd(u_ghosted_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(PetscLogStagePop());
  PetscCall(VecGhostGetLocalForm(u_ghosted_, &local));
  PetscCall(VecGetArrayRead(local, &u));
  const std::size_t n = 2 * (std::size_t)layout_->n_local();
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
  *stats = bond_forces_(y_.data(), c33);
  nd::assemble_force_density<2>(*families_, layout_->cloud, bond_force_.data(), (std::size_t)layout_->n_owned, force_density);
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
  kept_failed_.swap(workspace_.failed);
  workspace_.keep_warm_start = true;
  const PetscErrorCode ierr  = Kernel(u_owned, force_density, const_cast<double *>(c33.data()), &probe);
  workspace_.keep_warm_start = false;
  kept_failed_.swap(workspace_.failed);
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
