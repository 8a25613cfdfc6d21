// Partition-only benchmark: what a cluster run would exchange.
//
//   partition_stats [--points N] [--factor f] [--parts 2,4,...] [--graph families|stencil] [--check]
//
//   --points N    about N points on a square lattice (side round(sqrt(N))); default 1e6
//   --factor f    horizon delta = f dx (default 3.015)
//   --parts list  part counts (default 2,4,8,...,1024)
//   --graph       families: the bond graph from build_families (family.hpp), as rank 0
//                 of the solver builds it (default);
//                 stencil: the same graph from the lattice stencil, without BA masks
//                 (16 B instead of ~450 B per point beyond the graph): for 10^7 points
//                 and more on a small machine
//   --check       build both graphs and stop with an error unless they are identical
//
// For every part count: the METIS k-way partition of the bond graph exactly as the
// solver makes it (PartitionBondGraph, partition.hpp: vertex weight = bond count), the
// edge cut, and the two rings of ghosts every part would hold (as in
// src/solver/parallel/layout.cpp: ring 1 = family members of owned points, ring 2 = family
// members of ring 1). A time step exchanges 2 doubles per ghost (VecGhostUpdate), so
// ghosts x 16 B is the halo traffic per force evaluation. The kernel also runs over
// the ring-1 points (their bond forces t_ji enter the owned sums): their bonds are
// computed twice, the redundant work; with it, the part with the most kernel bonds
// bounds the speedup at (all bonds) / (its bonds), communication left out.
//
// It also reports the peak resident set size (VmHWM) after each phase, so that the
// largest graph that fits a machine can be read off.
#include <petscsys.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/parallel/partition.hpp"

using namespace bapd;

namespace {

// kB of a /proc/self/status field (VmRSS, VmHWM).
long proc_status_kb(const char *field)
{
  std::ifstream in("/proc/self/status");
  std::string   line;
  const size_t  len = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, len, field) == 0 && line[len] == ':') return std::atol(line.c_str() + len + 1);
  return -1;
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// The bond graph of an nx x ny lattice without holes or notches from the stencil of
// lattice offsets within the horizon: the same set as build_families (same distance
// test on the same coordinates), each family in natural-id order (row-major lattice
// order = increasing offset (dy, dx)).
void stencil_graph(const PointCloud &cloud, int nx, int ny, double horizon, std::vector<int> *offsets,
                   std::vector<int> *neighbours)
{
  const double *x = cloud.x.data();
  const int     r = static_cast<int>(std::ceil(horizon / (x[2] - x[0]))) + 1;
  const double  h2 = horizon * horizon;
  offsets->assign(static_cast<std::size_t>(nx) * ny + 1, 0);
  neighbours->clear();
  // Count first (one pass), then fill: no vector doubling, exact memory.
  for (int pass = 0; pass < 2; ++pass) {
    std::size_t b = 0;
    for (int iy = 0; iy < ny; ++iy)
      for (int ix = 0; ix < nx; ++ix) {
        const std::size_t i = static_cast<std::size_t>(iy) * nx + ix;
        for (int dy = -r; dy <= r; ++dy) {
          const int jy = iy + dy;
          if (jy < 0 || jy >= ny) continue;
          for (int dxo = -r; dxo <= r; ++dxo) {
            const int jx = ix + dxo;
            if (jx < 0 || jx >= nx || (dxo == 0 && dy == 0)) continue;
            const std::size_t j  = static_cast<std::size_t>(jy) * nx + jx;
            const double      d0 = x[2 * j] - x[2 * i], d1 = x[2 * j + 1] - x[2 * i + 1];
            if (d0 * d0 + d1 * d1 > h2) continue;
            if (pass == 1) (*neighbours)[b] = static_cast<int>(j);
            ++b;
          }
        }
        if (pass == 0) (*offsets)[i + 1] = static_cast<int>(b);
      }
    if (pass == 0) neighbours->resize(b);
  }
}

struct Rings {
  std::size_t owned = 0, ring1 = 0, ring2 = 0, owned_bonds = 0, ring1_bonds = 0;
};

// Two rings of ghosts per part, as CollectRings in src/solver/parallel/layout.cpp.
std::vector<Rings> collect_rings(int nparts, const std::vector<int> &part, const std::vector<int> &offsets,
                                 const std::vector<int> &neighbours)
{
  const std::size_t             n = part.size();
  std::vector<std::vector<int>> owned(nparts);
  for (std::size_t i = 0; i < n; ++i) owned[part[i]].push_back(static_cast<int>(i));
  std::vector<int>   mark(n, -1);
  std::vector<int>   ring1;
  std::vector<Rings> out(nparts);
  for (int r = 0; r < nparts; ++r) {
    Rings &R = out[r];
    R.owned  = owned[r].size();
    for (int i : owned[r]) mark[i] = 2 * r;
    ring1.clear();
    for (int i : owned[r]) {
      R.owned_bonds += static_cast<std::size_t>(offsets[i + 1] - offsets[i]);
      for (int b = offsets[i]; b < offsets[i + 1]; ++b)
        if (mark[neighbours[b]] != 2 * r) {
          mark[neighbours[b]] = 2 * r;
          ring1.push_back(neighbours[b]);
        }
    }
    R.ring1 = ring1.size();
    for (int i : ring1) R.ring1_bonds += static_cast<std::size_t>(offsets[i + 1] - offsets[i]);
    for (int i : ring1) mark[i] = 2 * r + 1;
    for (int i : owned[r]) mark[i] = 2 * r + 1;
    for (int i : ring1)
      for (int b = offsets[i]; b < offsets[i + 1]; ++b)
        if (mark[neighbours[b]] != 2 * r + 1) {
          mark[neighbours[b]] = 2 * r + 1;
          ++R.ring2;
        }
    std::vector<int>().swap(owned[r]);
  }
  return out;
}

std::vector<int> parse_list(const char *s)
{
  std::vector<int>  v;
  std::stringstream ss(s);
  std::string       item;
  while (std::getline(ss, item, ',')) v.push_back(std::atoi(item.c_str()));
  return v;
}

} // namespace

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  double           points = 1e6, factor = 3.015;
  std::vector<int> parts  = {2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
  std::string      graph  = "families";
  bool             check  = false;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--points" && a + 1 < argc) points = std::atof(argv[++a]);
    else if (s == "--factor" && a + 1 < argc) factor = std::atof(argv[++a]);
    else if (s == "--parts" && a + 1 < argc) parts = parse_list(argv[++a]);
    else if (s == "--graph" && a + 1 < argc) graph = argv[++a];
    else if (s == "--check") check = true;
    else if (s.rfind("-", 0) == 0 && s.rfind("--", 0) != 0) continue; // PETSc options
    else {
      std::fprintf(stderr, "partition_stats: bad argument %s (see bench/partition_stats.cpp)\n", s.c_str());
      PetscCall(PetscFinalize());
      return 2;
    }
  }
  PetscCheck(graph == "families" || graph == "stencil", PETSC_COMM_SELF, PETSC_ERR_USER,
             "--graph must be families or stencil, not %s", graph.c_str());

  const int side = static_cast<int>(std::lround(std::sqrt(points)));
  Body<2>    body;
  body.dx        = 1e-3;
  body.width     = side * body.dx;
  body.height    = side * body.dx;
  body.thickness = 1e-3;
  const double horizon = factor * body.dx;

  double     t0    = now();
  PointCloud cloud = make_lattice(body);
  const std::size_t n = cloud.size();

  std::vector<int> offsets, neighbours;
  double           families_s = 0, families_hwm_mb = 0, families_bytes_per_point = 0;
  if (graph == "families" || check) {
    Families fam = build_families(cloud, n, horizon, body.notches);
    families_s   = now() - t0;
    families_bytes_per_point =
        static_cast<double>(fam.offsets.capacity() * sizeof(std::size_t) + fam.neighbour.capacity() * 4 +
                            fam.reverse.capacity() * 4 + fam.ba_mask.capacity() * 8) /
        static_cast<double>(n);
    families_hwm_mb = proc_status_kb("VmHWM") / 1024.0;
    offsets.assign(fam.offsets.begin(), fam.offsets.end());
    neighbours.assign(fam.neighbour.begin(), fam.neighbour.end());
  }
  if (graph == "stencil" || check) {
    std::vector<int> so, sn;
    t0 = now();
    stencil_graph(cloud, side, side, horizon, &so, &sn);
    if (graph == "stencil") families_s = now() - t0;
    if (check) {
      PetscCheck(so == offsets && sn == neighbours, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "stencil graph differs from build_families on %d x %d points", side, side);
      std::printf("check: stencil graph == build_families graph (%zu points, %zu bonds)\n", n, sn.size());
    }
    offsets.swap(so);
    neighbours.swap(sn);
  }
  const double nb = static_cast<double>(neighbours.size());
  std::printf("%d x %d lattice, delta = %.3f dx: %zu points, %.0f directed bonds (%.2f per point); graph from %s in "
              "%.1f s; VmHWM %.0f MB after families (%.0f B/point in Families), %.0f MB now\n",
              side, side, factor, n, nb, nb / static_cast<double>(n), graph.c_str(), families_s, families_hwm_mb,
              families_bytes_per_point, proc_status_kb("VmHWM") / 1024.0);
  std::printf("RESULT kind=graph points=%zu bonds=%.0f factor=%.3f graph=%s build_s=%.2f families_hwm_mb=%.0f "
              "families_bytes_per_point=%.1f hwm_mb=%.0f\n",
              n, nb, factor, graph.c_str(), families_s, families_hwm_mb, families_bytes_per_point,
              proc_status_kb("VmHWM") / 1024.0);

  std::printf("%6s %12s %9s %12s %9s %9s %9s %9s %9s %10s %9s %9s\n", "parts", "edge_cut", "cut/edge", "ghosts",
              "ghost/own", "max g/o", "imbal", "redund", "speedup", "halo_MB", "metis_s", "HWM_MB");
  for (int np : parts) {
    if (np < 2 || static_cast<std::size_t>(np) > n) continue;
    std::vector<int> part;
    PetscInt         edge_cut = 0;
    t0                        = now();
    PetscCall(PartitionBondGraph(offsets, neighbours, np, &part, &edge_cut));
    const double             metis_s = now() - t0;
    const std::vector<Rings> rings   = collect_rings(np, part, offsets, neighbours);
    std::size_t              ghosts = 0, max_bonds = 0, ring1_bonds = 0, max_kernel_bonds = 0;
    double                   worst  = 0;
    for (const Rings &R : rings) {
      ghosts += R.ring1 + R.ring2;
      ring1_bonds += R.ring1_bonds;
      max_bonds        = std::max(max_bonds, R.owned_bonds);
      max_kernel_bonds = std::max(max_kernel_bonds, R.owned_bonds + R.ring1_bonds);
      if (R.owned) worst = std::max(worst, static_cast<double>(R.ring1 + R.ring2) / static_cast<double>(R.owned));
    }
    // The kernel runs over owned + ring-1 points (their bond forces t_ji enter the
    // owned sums), so ring-1 bonds are computed twice: redundant work. The part with
    // the most kernel bonds sets the pace: speedup bound = nb / (that count).
    const double redundant = static_cast<double>(ring1_bonds) / nb;
    const double speedup   = nb / static_cast<double>(max_kernel_bonds);
    const double ratio = static_cast<double>(ghosts) / static_cast<double>(n);
    const double imbal = static_cast<double>(max_bonds) / (nb / np); // most bonds on a part / mean
    const double halo  = static_cast<double>(ghosts) * 16.0 / 1e6;   // 2 doubles per ghost, all parts
    // METIS counts each cut undirected edge once; the graph has nb/2 undirected edges.
    const double cut_fraction = static_cast<double>(edge_cut) / (0.5 * nb);
    const double hwm          = proc_status_kb("VmHWM") / 1024.0;
    std::printf("%6d %12lld %9.4f %12zu %9.4f %9.4f %9.4f %9.4f %9.2f %10.2f %9.2f %9.0f\n", np, (long long)edge_cut,
                cut_fraction, ghosts, ratio, worst, imbal, redundant, speedup, halo, metis_s, hwm);
    std::printf("RESULT kind=parts points=%zu factor=%.3f parts=%d edge_cut=%lld cut_fraction=%.5f ghosts=%zu "
                "ghost_ratio=%.5f max_ghost_ratio=%.5f imbalance=%.4f redundant_bonds=%.5f speedup_bound=%.2f "
                "halo_mb=%.3f metis_s=%.2f hwm_mb=%.0f\n",
                n, factor, np, (long long)edge_cut, cut_fraction, ghosts, ratio, worst, imbal, redundant, speedup, halo,
                metis_s, hwm);
    std::fflush(stdout);
  }
  PetscCall(PetscFinalize());
  return 0;
}
