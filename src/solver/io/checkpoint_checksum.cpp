// Checksums of checkpoints and of the body they belong to (checkpoint_checksum.hpp,
// checkpoint.hpp).
#include "bapd/solver/io/checkpoint_checksum.hpp"

#include <algorithm>
#include <cstring>

namespace bapd {

namespace {

// splitmix64's finaliser: a cheap, well-mixed 64-bit hash step.
std::uint64_t Mix(std::uint64_t z)
{
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t Bits(double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// One entry of an order-independent checksum: the sum over entries (mod 2^64) does
// not depend on which rank holds which entry.
std::uint64_t Entry(std::uint64_t tag, std::uint64_t index, std::uint64_t bits) { return Mix(Mix(tag ^ Mix(index)) ^ bits); }

// The entries of a D-vector array of the block: point p's component c at D p + c.
template <int D>
std::uint64_t VectorsHash(std::uint64_t tag, const NaturalOrder &order, const std::vector<double> &values)
{
  std::uint64_t h = 0;
  for (PetscInt k = 0; k < order.point_count; ++k)
    for (int c = 0; c < D; ++c) h += Entry(tag, D * (std::uint64_t)(order.point_start + k) + c, Bits(values[D * k + c]));
  return h;
}

} // namespace

template <int D>
PetscErrorCode BlockHash(MPI_Comm comm, const NaturalOrder &order, const CheckpointBlock &block, std::uint64_t *hash)
{
  PetscFunctionBegin;
  // Tags: 1 u, 2 v, 3 family sizes, 4 bond states, 5 C33, 9 and 10 the relaxation's
  // displacement and acceleration, 12 the eigenvector, 15 the bonds' damage (6 to 8, 11,
  // 13 and 14 HeaderHash's).
  std::uint64_t h = VectorsHash<D>(1, order, block.u) + VectorsHash<D>(2, order, block.v);
  for (PetscInt k = 0; k < order.point_count; ++k) h += Entry(3, (std::uint64_t)(order.point_start + k), (std::uint64_t)block.family_size[k]);
  for (PetscInt b = 0; b < order.bond_count; ++b) {
    const std::uint64_t g = (std::uint64_t)(order.bond_start + b);
    h += Entry(4, g, block.intact[b]);
    if (!block.c33.empty()) h += Entry(5, g, Bits(block.c33[b]));
    if (!block.damage.empty()) h += Entry(15, g, Bits(block.damage[b]));
  }
  if (!block.relaxation_u.empty()) h += VectorsHash<D>(9, order, block.relaxation_u) + VectorsHash<D>(10, order, block.relaxation_a);
  if (!block.eigenvector.empty()) h += VectorsHash<D>(12, order, block.eigenvector);
  PetscCallMPI(MPI_Allreduce(&h, hash, 1, MPI_UINT64_T, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

std::uint64_t HeaderHash(const CheckpointHeader &h)
{
  std::uint64_t sum = Entry(6, 0, (std::uint64_t)h.step) + Entry(6, 1, Bits(h.time)) + Entry(6, 2, Bits(h.time_step)) +
                      Entry(6, 3, Bits(h.end_time)) + Entry(6, 4, Bits(h.end_time_original)) + Entry(6, 5, (std::uint64_t)h.static_hold_done);
  for (std::size_t k = 0; k < h.schedule_current.size(); ++k) sum += Entry(7, k, Bits(h.schedule_current[k]));
  for (std::size_t k = 0; k < h.schedule_original.size(); ++k) sum += Entry(8, k, Bits(h.schedule_original[k]));
  for (std::size_t k = 0; k < h.energy_totals.size(); ++k) sum += Entry(14, k, Bits(h.energy_totals[k])); // absent before version 7
  if (h.relaxation_records > 0) sum += Entry(11, 0, (std::uint64_t)h.relaxation_records); // absent in version 1
  if (h.step_lambda > 0) // absent in versions 1 and 2
    sum += Entry(13, 0, Bits(h.step_lambda)) + Entry(13, 1, Bits(h.step_stiffness_dt)) + Entry(13, 2, Bits(h.step_shortest)) +
           Entry(13, 3, (std::uint64_t)h.step_next_estimate) + Entry(13, 4, (std::uint64_t)h.step_by_stiffness) +
           Entry(13, 5, (std::uint64_t)h.step_by_travel) + Entry(13, 6, Bits(h.step_stretch));
  if (h.step_interval_now > 0) // absent in versions 1 to 3
    sum += Entry(13, 7, (std::uint64_t)h.step_interval_now) + Entry(13, 8, Bits(h.step_stretch_increment));
  if (h.step_indicator > 0) sum += Entry(13, 9, Bits(h.step_indicator)); // absent in versions 1 to 4, and before any search
  return sum;
}

std::uint64_t TextHash(const CheckpointHeader &h)
{
  std::uint64_t sum  = 0;
  auto          text = [&](std::uint64_t tag, const std::string &t) {
    sum += Entry(tag, ~0ULL, t.size());
    for (std::size_t k = 0; k < t.size(); k += 8) {
      std::uint64_t chunk = 0;
      std::memcpy(&chunk, t.data() + k, std::min<std::size_t>(8, t.size() - k));
      sum += Entry(tag, k, chunk);
    }
  };
  text(12, h.options);
  text(13, h.history);
  text(14, h.static_states);
  text(15, h.reason);
  sum += Entry(16, ~0ULL, h.field_frames.size());
  for (std::size_t k = 0; k < h.field_frames.size(); ++k) sum += Entry(16, k, Bits(h.field_frames[k]));
  return sum;
}

template <int D>
PetscErrorCode ComputeGeometryFingerprint(MPI_Comm comm, const Layout &layout, const Families &families, double dx,
                                          double horizon, GeometryFingerprint *fingerprint)
{
  PetscFunctionBegin;
  PetscCheck(layout.dimension == D, comm, PETSC_ERR_PLIB, "ComputeGeometryFingerprint<%d> on a layout of dimension %d", D, layout.dimension);
  std::uint64_t hash = 0;
  long long     bonds = 0;
  for (PetscInt i = 0; i < layout.n_owned; ++i) {
    std::uint64_t h = Mix((std::uint64_t)layout.cloud.natural_id[i]);
    for (int d = 0; d < D; ++d) h = Mix(h ^ Bits(layout.cloud.x[D * i + d]));
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) h = Mix(h ^ (std::uint64_t)layout.cloud.natural_id[families.neighbour[b]]);
    hash += h;
    bonds += (long long)families.size((std::size_t)i);
  }
  PetscCallMPI(MPI_Allreduce(&hash, &fingerprint->hash, 1, MPI_UINT64_T, MPI_SUM, comm));
  long long total = 0;
  PetscCallMPI(MPI_Allreduce(&bonds, &total, 1, MPI_LONG_LONG, MPI_SUM, comm));
  fingerprint->points  = layout.n_global;
  fingerprint->bonds   = total;
  fingerprint->dx      = dx;
  fingerprint->horizon = horizon;
  PetscFunctionReturn(0);
}

bool SameGeometry(const GeometryFingerprint &a, const GeometryFingerprint &b)
{
  return a.points == b.points && a.bonds == b.bonds && a.dx == b.dx && a.horizon == b.horizon && a.hash == b.hash;
}

template PetscErrorCode BlockHash<2>(MPI_Comm, const NaturalOrder &, const CheckpointBlock &, std::uint64_t *);
template PetscErrorCode BlockHash<3>(MPI_Comm, const NaturalOrder &, const CheckpointBlock &, std::uint64_t *);
template PetscErrorCode ComputeGeometryFingerprint<2>(MPI_Comm, const Layout &, const Families &, double, double, GeometryFingerprint *);
template PetscErrorCode ComputeGeometryFingerprint<3>(MPI_Comm, const Layout &, const Families &, double, double, GeometryFingerprint *);

} // namespace bapd
