// The body's memory check (scene.hpp: CheckBodyFits, CheckBodyMemory): the points and
// bonds a body asks for against what the node of rank 0 and this process's own limits
// can still give, before anything is built and again with the real bond count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <utility>

#include <sys/resource.h>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

// Bytes the machine can still give, from /proc/meminfo's MemAvailable (Linux); 0 when
// it cannot be read (then nothing is refused).
double AvailableMemoryBytes()
{
  std::FILE *file = std::fopen("/proc/meminfo", "r");
  if (!file) return 0;
  char   line[256];
  double kib = 0;
  while (std::fgets(line, sizeof(line), file))
    if (std::sscanf(line, "MemAvailable: %lf kB", &kib) == 1) break;
  std::fclose(file);
  return kib * 1024.0;
}

// Bytes this process may still map under its own limits (ulimit -v: RLIMIT_AS against
// VmSize; ulimit -d: RLIMIT_DATA against VmData, /proc/self/status); 0 when neither is
// set (then only the machine's memory counts).
double ProcessRoomBytes()
{
  double       room = 0;
  std::FILE   *file = std::fopen("/proc/self/status", "r");
  double       vm_size = 0, vm_data = 0, kib;
  char         line[256];
  while (file && std::fgets(line, sizeof(line), file)) {
    if (std::sscanf(line, "VmSize: %lf kB", &kib) == 1) vm_size = kib * 1024.0;
    if (std::sscanf(line, "VmData: %lf kB", &kib) == 1) vm_data = kib * 1024.0;
  }
  if (file) std::fclose(file);
  const std::pair<int, double> limits[] = {{RLIMIT_AS, vm_size}, {RLIMIT_DATA, vm_data}};
  for (const auto &[resource, used] : limits) {
    struct rlimit limit;
    if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) continue;
    const double left = std::max((double)limit.rlim_cur - used, 1.0);
    room              = room > 0 ? std::min(room, left) : left;
  }
  return room;
}

// Refuses a body that cannot fit: the points, their bonds (before anything is built:
// about pi x horizon_factor^2 a point, the lattice's; after rank 0 has built the bond
// graph: the real count, CheckBodyMemory) and the memory they need, against what
// the node of rank 0 has available for the ranks it runs. The cost per point is the
// one measured at delta = 3.015 dx (docs/performance.md section 2: 1.83 KB, 27.9
// bonds a point), scaled with the bonds a point has.
PetscErrorCode CheckMemory(MPI_Comm comm, const Scene &scene, int64_t points, double bonds_per_point)
{
  const double bytes_per_point_paper = 1.9e3, horizon_factor_paper = 3.015;
  const double bytes_per_point = bytes_per_point_paper * bonds_per_point / (M_PI * horizon_factor_paper * horizon_factor_paper);
  PetscMPIInt  size, rank, node_ranks;
  MPI_Comm     node;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &node_ranks));
  PetscCallMPI(MPI_Comm_free(&node));
  double available = rank == 0 ? AvailableMemoryBytes() : 0.0;
  PetscCallMPI(MPI_Bcast(&available, 1, MPI_DOUBLE, 0, comm));
  PetscCallMPI(MPI_Bcast(&node_ranks, 1, MPI_INT, 0, comm));
  const double per_rank = static_cast<double>(points) * bytes_per_point / size;
  const double needed   = per_rank * node_ranks; // on rank 0's node
  const double gb       = 1e9;
  // The process's own limit (a batch system's or the shell's ulimit), which
  // MemAvailable does not show: std::bad_alloc half-way through the set-up otherwise.
  // Each rank holds at least its share; rank 0 builds the bonds of the whole body.
  double room = ProcessRoomBytes(), worst = 0;
  if (room > 0 && per_rank > room) worst = per_rank / room;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscCheck(!(worst > 0), comm, PETSC_ERR_USER,
             "%lld material points need about %.3g GB on each of %d rank(s), %.3g times what a rank's process limit leaves it (ulimit -v "
             "or -d, RLIMIT_AS/RLIMIT_DATA; %.3g GB left on rank 0): raise the limit, run on more ranks, or use a coarser %s",
             static_cast<long long>(points), per_rank / gb, size, worst, rank == 0 ? room / gb : 0.0,
             scene.body.dimension == 3 && (scene.body.solid.given_points || scene.body.solid.centroids) ? "point set" : "-body_dx");
  if (available <= 0 || needed <= available) PetscFunctionReturn(0);
  // Points go as 1/dx^2 (3D: 1/dx^3): the spacing at which the estimate just fits.
  const double      dx_fit = scene.body.dx() * (scene.body.dimension == 3 ? std::cbrt(needed / available) : std::sqrt(needed / available));
  const std::string what   = Format("%lld material points and %.3g bonds, about %.3g GB (%.3g GB on each of %d rank(s); %.2g KB a point "
                                    "at delta = %g x spacing), but this machine has %.3g GB available (MemAvailable, /proc/meminfo)",
                                    static_cast<long long>(points), static_cast<double>(points) * bonds_per_point,
                                    static_cast<double>(points) * bytes_per_point / gb, per_rank / gb, size, bytes_per_point / 1e3,
                                    scene.body.horizon_factor, available / gb);
  // Given points have no -body_dx (it is refused with them): the fix is fewer points at
  // their source, about needed / available times fewer (a spacing that much coarser).
  const Body<2> &b = scene.body.sheet;
  if (scene.body.solid.centroids)
    SETERRQ(comm, PETSC_ERR_USER, "%s",
            Format("-body_%s_discretisation centroids: the tetrahedra of '%s' give %s: mesh it about %.2g times coarser, use the "
                   "lattice (-body_dx) instead, or run on more machines",
                   scene.body.solid_summary.solid_names[0].c_str(), scene.body.solid.source.c_str(), what.c_str(), 1.05 * std::cbrt(needed / available))
                .c_str());
  if (scene.body.solid.given_points)
    SETERRQ(comm, PETSC_ERR_USER, "%s",
            Format("-body_cloud '%s' gives %s: give a cloud about %.2g times coarser in spacing, a smaller -horizon_factor (bonds go as "
                   "its cube in 3D), or run on more machines",
                   scene.body.solid.source.c_str(), what.c_str(), 1.05 * std::cbrt(needed / available))
                .c_str());
  if (b.given_points) {
    const Shape *mesh = nullptr;
    for (const Shape &s : b.shapes)
      if (s.centroids) mesh = &s;
    const double coarser = 1.05 * std::sqrt(needed / available);
    if (mesh)
      SETERRQ(comm, PETSC_ERR_USER, "%s",
              Format("-body_%s_discretisation centroids: the elements of '%s' give %s: mesh it about %.2g times coarser (e.g. a "
                     "larger characteristic length in the .geo, or gmsh -clscale %.2g), use -body_%s_discretisation lattice with "
                     "a -body_dx of your choice, or run on more machines",
                     mesh->name.c_str(), b.given_points->source.c_str(), what.c_str(), coarser, coarser, mesh->name.c_str())
                  .c_str());
    SETERRQ(comm, PETSC_ERR_USER, "%s",
            Format("-body_cloud '%s' gives %s: give a cloud about %.2g times coarser in spacing (%.2g times fewer points), a smaller "
                   "-horizon_factor (bonds go as its square), or run on more machines",
                   b.given_points->source.c_str(), what.c_str(), coarser, coarser * coarser)
                .c_str());
  }
  SETERRQ(comm, PETSC_ERR_USER, "%s",
          Format("-body_dx %g m asks for about %s: choose -body_dx %.2g or coarser, or run on more machines", scene.body.dx(), what.c_str(), 1.05 * dx_fit)
              .c_str());
}

} // namespace

// The grips outside the sheet (Body<2>::grip_rows, set from the load sets) are points too.
PetscErrorCode CheckBodyFits(MPI_Comm comm, const Scene &scene)
{
  PetscFunctionBeginUser;
  const double f = scene.body.horizon_factor; // bonds a point on the lattice: the horizon's area (2D) or volume (3D) in cells
  PetscCall(CheckMemory(comm, scene, ScenePointEstimate(scene), scene.body.dimension == 3 ? 4.0 / 3.0 * M_PI * f * f * f : M_PI * f * f));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckBodyMemory(MPI_Comm comm, const Scene &scene, int64_t points, int64_t bonds)
{
  PetscFunctionBeginUser;
  PetscCall(CheckMemory(comm, scene, points, points > 0 ? static_cast<double>(bonds) / static_cast<double>(points) : 0.0));
  PetscFunctionReturn(0);
}

} // namespace bapd
