// Region block: the given points (-body_cloud's block_id column; a 2D cloud's or a 3D
// one's) of block id -load_NAME_block, found by position: their coordinates, sorted,
// compared bit for bit (LoadSet::block_points).
#include <algorithm>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {
namespace {

PetscErrorCode ReadBlock(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li    = r.li;
  const char      *n     = li.name.c_str();
  const bool       three = r.body.dimension == 3;
  const Body<2>    &b2    = r.body.sheet;
  const Body<3>    &b3    = r.body.solid;
  PetscFunctionBeginUser;
  SceneCheck(li.block_set, r.comm, "-load_%s_block is required with -load_%s_region block: give a block id of the point cloud%s", n, n,
             MisspeltHint("-load_" + li.name + "_block").c_str());
  SceneCheck(three ? b3.given_points != nullptr : b2.given_points != nullptr, r.comm,
             "-load_%s_region block: block ids come with the points of a cloud (-body_cloud, column block_id), and this body is a "
             "lattice: choose %s",
             n, three ? "a face or a box" : "another region (box, polygon, curve, group)");
  set->block        = static_cast<int64_t>(li.block);
  set->block_points = three ? BlockPoints3D(b3.given_points->x, b3.given_block, set->block) : BlockPoints(b2, set->block);
  SceneCheck(!set->block_points.empty(), r.comm,
             "-load_%s_block %" PetscInt_FMT ": no point of '%s' has block id %" PetscInt_FMT " (its block ids: %s): give one of them", n,
             li.block, three ? b3.source.c_str() : b2.given_points->source.c_str(), li.block,
             (three ? BlockIdList(b3.given_block) : BlockIdList(b2)).c_str());
  PetscFunctionReturn(0);
}

// (2D: the points of the body's own, like every region but the edges.)
PetscErrorCode CheckBlock2D(const RegionInput &r, LoadSet *set)
{
  PetscFunctionBeginUser;
  PetscCall(CheckOwnPoints2D(r, set));
  PetscCall(ReadBlock(r, set));
  PetscFunctionReturn(0);
}

// Whether p (D coordinates) is one of the sorted D-tuples of `points`: a binary search,
// exact comparison (BlockPoints).
template <int D> bool AmongSorted(const BodyExtent &, const LoadSet &set, const double *p)
{
  const std::vector<double> &points = set.block_points;
  const auto less = [](const double *a, const double *b) { return std::lexicographical_compare(a, a + D, b, b + D); };
  const std::size_t n  = points.size() / D;
  std::size_t       lo = 0, hi = n;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (less(&points[D * mid], p)) lo = mid + 1;
    else hi = mid;
  }
  return lo < n && std::equal(p, p + D, &points[D * lo]);
}

std::string BlockText(const BodyExtent &s, const LoadSet &l)
{
  return Format("block %lld of the cloud (%zu points)", static_cast<long long>(l.block), l.block_points.size() / (s.dimension == 3 ? 3 : 2));
}

// The body's shapes or holes can cut a block's points away.
std::string BlockEmpty(const BodyExtent &s, const LoadSet &set)
{
  const char *n = set.name.c_str();
  return Format("-load_%s_block %lld selects no material point for load set '%s': the body's shapes or holes cut away "
                "all %zu points of that block",
                n, static_cast<long long>(set.block), n, set.block_points.size() / s.dimension);
}

} // namespace

RegionType block_region(LoadSet::Region id, const char *word, const char *alias)
{
  return {id, word, alias, false, uses_block, uses_block, CheckBlock2D, ReadBlock, AmongSorted<2>, AmongSorted<3>, BlockText, BlockEmpty, "a block id of the point cloud"};
}

} // namespace bapd
