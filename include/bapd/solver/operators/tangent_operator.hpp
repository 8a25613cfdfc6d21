#pragma once
// The tangent operator: the stiffness matrix H = d^2 W / du du of the energy-consistent
// force (docs/method.md sections 3 and 8), H = -V f' (the nodal force's Jacobian up to
// sign): symmetric, D x D blocks, one block row a point. Each owned point adds the dense
// Hessian of its own energy W_i over itself and its family (ba_tangent.hpp) into the rows
// of those points (ring-1 ghosts' rows go to their owners), so the pattern is the points
// within two horizons: the layout's two rings. The matrix is preallocated once from that
// pattern (MATPREALLOCATOR, each block row's union of those blocks inserted once).
//
// Like the force operator, the law is chosen once at set-up (with_model) and compiled
// into the loop; the body (layout, families, geometry, bond state) is the caller's.
#include <petscmat.h>

#include <functional>
#include <memory>

#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/parallel/layout.hpp"

namespace bapd {

class TangentOperator {
public:
  template <int D>
  PetscErrorCode Setup(MPI_Comm comm, const MaterialSection &force, const Layout &layout, const Families &families,
                       const nd::BondGeometry<D> &geometry, const BondState &state);
  // A matrix of block size D over the owned dofs, its pattern preallocated (the
  // caller destroys it). -mat_type chooses its type (default baij).
  PetscErrorCode CreateMatrix(Mat *H) const;
  // H at the positions y (every local point, D per point) and the plane-stress warm
  // starts c33 (1 per bond, or nullptr), assembled (MAT_FINAL_ASSEMBLY). *failed: bonds
  // whose law failed at a perturbed F (their tangent left out), summed over the ranks.
  PetscErrorCode Assemble(const double *y, const double *c33, Mat H, PetscInt *failed) const;
  // The law's exact dP/dF where it has one (the default), or central differences of P
  // everywhere (false; the tangent tests check both).
  void set_law_tangent(bool exact) { *law_tangent_ = exact; }

private:
  MPI_Comm      comm_   = MPI_COMM_NULL;
  const Layout *layout_ = nullptr;
  const Families *families_ = nullptr;
  int           dimension_ = 2;
  std::shared_ptr<bool> law_tangent_ = std::make_shared<bool>(true); // shared with add_blocks_
  PetscErrorCode InsertPattern(Mat pattern) const; // every block CreateMatrix's H will receive
  // Adds every owned point's block into H; returns the failed bonds of this rank.
  std::function<PetscErrorCode(const double *y, const double *c33, Mat H, PetscInt *failed)> add_blocks_;
};

} // namespace bapd
