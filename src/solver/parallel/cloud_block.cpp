// Given points set up on every rank (cloud_block.hpp): slabs along x, each slab's
// families built where it is held, the pieces check on the slabs, then each point with
// its family to the block of its natural id.
#include "bapd/solver/parallel/cloud_block.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "bapd/solver/parallel/exchange.hpp"
#include "bapd/solver/parallel/point_reals.hpp"

namespace bapd {

namespace {

// Slabs along x, one a rank, balanced by point counts on a histogram of kBins bins over
// the cloud's x extent: slab s owns the points whose bin lies in [bin[s], bin[s + 1]) and
// holds, besides, those within `halo` (the largest horizon, with a margin) of its bins.
struct Slabs {
  static constexpr int kBins = 4096;
  double               lo = 0, width = 0, halo = 0;
  std::vector<int>     bin; // size + 1 entries, bin[0] = 0, bin[size] = kBins

  int BinOf(double x) const { return width > 0 ? std::clamp((int)((x - lo) / width * kBins), 0, kBins - 1) : 0; }
  int OwnerOf(double x) const { return (int)(std::upper_bound(bin.begin(), bin.end(), BinOf(x)) - bin.begin()) - 1; }
  bool Holds(int s, double x) const // owned or within the halo of slab s
  {
    return bin[s] < bin[s + 1] && x >= lo + width * bin[s] / kBins - halo && x <= lo + width * bin[s + 1] / kBins + halo;
  }
};

// The slabs from every rank's chunk: the x extent, the largest horizon, the histogram.
template <int D> PetscErrorCode MakeSlabs(MPI_Comm comm, const PointCloud &chunk, Slabs *slabs)
{
  PetscMPIInt size;
  double      extent[3] = {INFINITY, -INFINITY, 0}; // -min x, max x, largest horizon

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  for (std::size_t i = 0; i < chunk.size(); ++i) {
    extent[0] = std::min(extent[0], chunk.x[D * i]);
    extent[1] = std::max(extent[1], chunk.x[D * i]);
    extent[2] = std::max(extent[2], chunk.horizon[i]);
  }
  extent[0] = -extent[0];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, extent, 3, MPI_DOUBLE, MPI_MAX, comm));
  slabs->lo    = -extent[0];
  slabs->width = extent[1] - slabs->lo;
  // A bond reaches max(delta_i, delta_j) (family.cpp): the largest horizon, and a margin
  // against the round-off of the bin edges (a point too many in a halo costs nothing).
  slabs->halo = 1.01 * extent[2];
  std::vector<int64_t> count(Slabs::kBins, 0);
  for (std::size_t i = 0; i < chunk.size(); ++i) ++count[slabs->BinOf(chunk.x[D * i])];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, count.data(), Slabs::kBins, MPI_INT64_T, MPI_SUM, comm));
  const int64_t n = std::accumulate(count.begin(), count.end(), int64_t{0});
  slabs->bin.assign(size + 1, Slabs::kBins);
  slabs->bin[0] = 0;
  int64_t below = 0; // points in the bins before b
  for (int b = 0, s = 1; b < Slabs::kBins && s < size; below += count[b++])
    while (s < size && below >= n * s / size) slabs->bin[s++] = b;
  PetscFunctionReturn(0);
}

// This rank's slab: its own points first (natural order), then the halo's (*n_own: how
// many are its own), from every rank's chunk.
template <int D>
PetscErrorCode GatherSlab(MPI_Comm comm, const PointCloud &chunk, const Slabs &slabs, const PointReals<D> &reals, PointCloud *slab,
                          std::size_t *n_own)
{
  const int                          size = (int)slabs.bin.size() - 1;
  std::vector<std::vector<PetscInt>> out_int(size);
  std::vector<std::vector<double>>   out_real(size);
  std::vector<PetscInt>              in_int;
  std::vector<double>                in_real;

  PetscFunctionBegin;
  for (std::size_t i = 0; i < chunk.size(); ++i) {
    const double x     = chunk.x[D * i];
    const int    owner = slabs.OwnerOf(x);
    for (int s = 0; s < size; ++s) {
      if (s != owner && !slabs.Holds(s, x)) continue;
      out_int[s].push_back((PetscInt)chunk.natural_id[i]);
      out_int[s].push_back(s == owner);
      const std::size_t at = out_real[s].size();
      out_real[s].resize(at + reals.R);
      reals.Pack(chunk, (int)i, out_real[s].data() + at);
    }
  }
  PetscCall(Exchange(comm, out_int, &in_int));
  PetscCall(Exchange(comm, out_real, &in_real));
  // Own points first: the chunks arrive in rank order, natural order inside each.
  std::vector<int>    ids;
  std::vector<double> real;
  for (int own = 1; own >= 0; --own)
    for (std::size_t k = 0; 2 * k < in_int.size(); ++k) {
      if (in_int[2 * k + 1] != own) continue;
      ids.push_back((int)in_int[2 * k]);
      real.insert(real.end(), in_real.begin() + reals.R * k, in_real.begin() + reals.R * (k + 1));
    }
  *n_own = 0;
  for (std::size_t k = 0; 2 * k < in_int.size(); ++k) *n_own += in_int[2 * k + 1] == 1;
  reals.Unpack(ids, real, *slab);
  PetscFunctionReturn(0);
}

// Union-find over indices (path halving).
struct Forest {
  std::vector<std::size_t> parent;
  explicit Forest(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t Find(std::size_t i)
  {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void Join(std::size_t a, std::size_t b) { parent[Find(a)] = Find(b); }
};

// Rank 0 joins the slabs' components (label = the smallest natural id of a component's
// own points, its own-point count, the label point's position) along the cross-slab
// links (label pairs) and writes DescribePieces' message, or "", into `message`.
template <int D>
void JoinPieces(std::vector<PetscInt> comps, const std::vector<double> &at, const std::vector<PetscInt> &links, const std::string &source,
                char *message, std::size_t length)
{
  const std::size_t        n = comps.size() / 2;
  std::vector<std::size_t> order(n); // components by label
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return comps[2 * a] < comps[2 * b]; });
  std::vector<PetscInt> labels(n);
  for (std::size_t k = 0; k < n; ++k) labels[k] = comps[2 * order[k]];
  auto   index = [&](PetscInt label) { return (std::size_t)(std::lower_bound(labels.begin(), labels.end(), label) - labels.begin()); };
  Forest forest(n);
  for (std::size_t p = 0; p < links.size(); p += 2) forest.Join(index(links[p]), index(links[p + 1]));
  std::vector<std::size_t> count(n, 0), first(n, n); // per root: points, its first component (by label)
  std::size_t              n_pieces = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t r = forest.Find(k);
    n_pieces += first[r] == n;
    if (first[r] == n) first[r] = k;
    count[r] += (std::size_t)comps[2 * order[k] + 1];
  }
  message[0] = '\0';
  if (n_pieces <= 1) return;
  std::size_t smallest = n; // the root of the smallest piece, the one with the lowest first point among equals
  for (std::size_t k = 0; k < n; ++k)
    if (forest.Find(k) == k && (smallest == n || count[k] < count[smallest] || (count[k] == count[smallest] && first[k] < first[smallest])))
      smallest = k;
  const std::size_t c = order[first[smallest]];
  std::snprintf(message, length, "%s",
                PiecesMessage(source, n_pieces, count[smallest], comps[2 * c], &at[D * c], D).c_str());
}

// DescribePieces (simulation_body.cpp) on the slabs: each slab's components over its own
// points and the halo points bonded to them, the halo points' labels asked of the slabs
// that own them, the components and links joined on rank 0. Every rank stops together.
template <int D>
PetscErrorCode CheckPieces(MPI_Comm comm, const PointCloud &slab, std::size_t n_own, const Families &fam, const Slabs &slabs,
                           const std::string &source)
{
  const int   size = (int)slabs.bin.size() - 1;
  Forest      forest(slab.size());
  char        message[512] = "";
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (std::size_t i = 0; i < n_own; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) forest.Join(i, (std::size_t)fam.neighbour[b]);
  // A component's label: its smallest own natural id (own points come in natural order).
  std::vector<PetscInt>              label(slab.size(), -1), count(slab.size(), 0);
  std::vector<std::vector<PetscInt>> comps(size), ask(size), asker(size), answer(size), links(size);
  std::vector<std::vector<double>>   at(size);
  for (std::size_t i = 0; i < n_own; ++i) {
    const std::size_t r = forest.Find(i);
    if (label[r] < 0) label[r] = (PetscInt)slab.natural_id[i];
    ++count[r];
  }
  for (std::size_t i = 0; i < n_own; ++i)
    if (label[forest.Find(i)] == (PetscInt)slab.natural_id[i]) {
      comps[0].push_back(label[forest.Find(i)]), comps[0].push_back(count[forest.Find(i)]);
      at[0].insert(at[0].end(), &slab.x[D * i], &slab.x[D * i] + D);
    }
  // The halo points bonded to own points: their labels from the slabs that own them.
  for (std::size_t h = n_own; h < slab.size(); ++h) {
    const PetscInt mine = label[forest.Find(h)];
    if (mine < 0) continue;
    const int owner = slabs.OwnerOf(slab.x[D * h]);
    ask[owner].push_back((PetscInt)slab.natural_id[h]);
    asker[owner].push_back(mine);
  }
  std::vector<PetscInt> from, asked, got;
  PetscCall(Ask(comm, ask, &asked, &from));
  std::size_t k = 0;
  for (int r = 0; r < size; ++r)
    for (PetscInt q = 0; q < from[r]; ++q, ++k) {
      const auto first = slab.natural_id.begin(), own_end = first + (std::ptrdiff_t)n_own;
      const auto i     = (std::size_t)(std::lower_bound(first, own_end, (int64_t)asked[k]) - first);
      answer[r].push_back(label[forest.Find(i)]);
    }
  PetscCall(Exchange(comm, answer, &got));
  std::vector<std::pair<PetscInt, PetscInt>> pairs; // distinct label pairs: a few a slab
  k = 0;
  for (int r = 0; r < size; ++r)
    for (PetscInt mine : asker[r]) pairs.emplace_back(mine, got[k++]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto &p : pairs) links[0].push_back(p.first), links[0].push_back(p.second);
  std::vector<PetscInt> all_comps, all_links;
  std::vector<double>   all_at;
  PetscCall(Exchange(comm, comps, &all_comps));
  PetscCall(Exchange(comm, links, &all_links));
  PetscCall(Exchange(comm, at, &all_at));
  if (rank == 0) JoinPieces<D>(std::move(all_comps), all_at, all_links, source, message, sizeof message);
  PetscCallMPI(MPI_Bcast(message, sizeof message, MPI_CHAR, 0, comm));
  PetscCheck(!message[0], comm, PETSC_ERR_USER, "%s", message);
  PetscFunctionReturn(0);
}

// Each own point of the slab with its family (natural ids, sorted) and reals to the
// rank whose block holds its natural id; *block: this rank's, in natural order.
template <int D>
PetscErrorCode SendToBlocks(MPI_Comm comm, const PointCloud &slab, const Families &fam, const std::vector<PetscInt> &starts,
                            const PointReals<D> &reals, PetscInt first, PetscInt m, BodyBlock *block)
{
  const int                          size = (int)starts.size() - 1;
  std::vector<std::vector<PetscInt>> out_int(size);
  std::vector<std::vector<double>>   out_real(size);
  std::vector<PetscInt>              in_int;
  std::vector<double>                in_real;

  PetscFunctionBegin;
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    const int              r = HolderOf(starts, (PetscInt)slab.natural_id[i]);
    std::vector<PetscInt> &o = out_int[r];
    o.push_back((PetscInt)slab.natural_id[i]);
    o.push_back((PetscInt)fam.size(i));
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) o.push_back((PetscInt)slab.natural_id[(std::size_t)fam.neighbour[b]]);
    const std::size_t at = out_real[r].size();
    out_real[r].resize(at + reals.R);
    reals.Pack(slab, (int)i, out_real[r].data() + at);
  }
  PetscCall(Exchange(comm, out_int, &in_int));
  PetscCall(Exchange(comm, out_real, &in_real));
  // The points arrive by slab: where each one's record starts in in_int and in_real, by natural id.
  std::vector<std::size_t> int_at(m), real_at(m);
  for (std::size_t p = 0, k = 0; p < in_int.size(); p += 2 + (std::size_t)in_int[p + 1], ++k)
    int_at[in_int[p] - first] = p, real_at[in_int[p] - first] = reals.R * k;
  std::vector<int>    ids(m);
  std::vector<double> real((std::size_t)reals.R * m);
  block->first = first;
  block->offsets.assign(1, 0);
  block->neighbours.clear();
  for (PetscInt i = 0; i < m; ++i) {
    const std::size_t p = int_at[i];
    ids[i]              = (int)(first + i);
    std::copy(in_real.begin() + real_at[i], in_real.begin() + real_at[i] + reals.R, real.begin() + reals.R * i);
    block->neighbours.insert(block->neighbours.end(), in_int.begin() + p + 2, in_int.begin() + p + 2 + in_int[p + 1]);
    block->offsets.push_back((PetscInt)block->neighbours.size());
  }
  reals.Unpack(ids, real, block->cloud);
  PetscFunctionReturn(0);
}

} // namespace

std::string PiecesMessage(const std::string &source, std::size_t n_pieces, std::size_t smallest_count, int64_t first_id, const double *x,
                          int dimension)
{
  char at[96], message[512];
  if (dimension == 2) std::snprintf(at, sizeof at, "(%g, %g)", x[0], x[1]);
  else std::snprintf(at, sizeof at, "(%g, %g, %g)", x[0], x[1], x[2]);
  std::snprintf(message, sizeof message,
                "%s: the given points fall apart into %zu pieces with no bond between them (the smallest: %zu point(s), e.g. "
                "point %lld at %s m): a piece not bonded to the rest has no stiffness against it. Remove the "
                "stray points from the file, close the gap, or raise -horizon_factor",
                source.c_str(), n_pieces, smallest_count, static_cast<long long>(first_id), at);
  return message;
}

template <int D>
PetscErrorCode CloudBlock(MPI_Comm comm, const PointCloud &chunk, PetscInt first, const FamilyBuilder &build_families,
                          const std::string &source, BodyBlock *block)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<PetscInt> starts(size + 1);
  const PetscInt        m = (PetscInt)chunk.size();
  PetscCallMPI(MPI_Allgather(&first, 1, MPIU_INT, starts.data(), 1, MPIU_INT, comm));
  PetscCallMPI(MPI_Allreduce(&m, &starts[size], 1, MPIU_INT, MPI_SUM, comm));
  for (int r = size - 1; r >= 0; --r) starts[r] = std::min(starts[r], starts[r + 1]); // (an empty chunk holds no id)
  // The reals a point travels with: position, volume, family volume, its own horizon.
  const PointReals<D> reals{D + 3, 0, D + 3, true};
  Slabs               slabs;
  PetscCall(MakeSlabs<D>(comm, chunk, &slabs));
  PointCloud  slab;
  std::size_t n_own = 0;
  {
    PointCloud travelling = chunk; // (Pack ships the family volume, set once the families are built)
    travelling.family_volume.assign(chunk.size(), 0.0);
    PetscCall(GatherSlab<D>(comm, travelling, slabs, reals, &slab, &n_own));
  }
  const Families families = build_families(slab, n_own);
  compute_family_volumes(slab, families);
  PetscCall(CheckPieces<D>(comm, slab, n_own, families, slabs, source));
  PetscCall(SendToBlocks<D>(comm, slab, families, starts, reals, first, m, block));
  PetscFunctionReturn(0);
}

template PetscErrorCode CloudBlock<2>(MPI_Comm, const PointCloud &, PetscInt, const FamilyBuilder &, const std::string &, BodyBlock *);
template PetscErrorCode CloudBlock<3>(MPI_Comm, const PointCloud &, PetscInt, const FamilyBuilder &, const std::string &, BodyBlock *);

} // namespace bapd
