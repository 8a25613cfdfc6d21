#pragma once
// The checksums of a checkpoint (checkpoint.hpp), shared by its writer
// (checkpoint_write.cpp) and its reader (checkpoint_read.cpp): a damaged file is
// refused instead of silently continuing from wrong data.
//
// Every checksum is a sum (mod 2^64) of one well-mixed entry per value, each keyed by a
// tag (which array) and its place in the file (global point, component, bond), so it
// does not depend on which rank held which value: a file written on 2 ranks checks on
// 3. The tags and places are those of format versions 1 to 5, so their files still
// check; a D-vector's component c of point p is at D p + c. The dimension itself is
// not in the sums: a wrong one fails the shape checks of the arrays (D columns) first.
#include <petscsys.h>

#include <cstdint>
#include <vector>

#include "bapd/solver/io/checkpoint.hpp"
#include "bapd/solver/parallel/natural_order.hpp"

namespace bapd {

// This rank's natural block of the arrays a checkpoint holds ([point_start,
// point_start + point_count) and the bonds of those points, natural_order.hpp): D-vectors
// D numbers a point; an empty vector is an array the file does not hold.
struct CheckpointBlock {
  std::vector<double>        u, v;                       // displacement, velocity
  std::vector<std::int32_t>  family_size;
  std::vector<unsigned char> intact;                     // a bond
  std::vector<double>        c33;                        // a bond (empty: no /bonds/c33)
  std::vector<double>        damage;                     // a bond, -failure_softening (empty: no /bonds/damage)
  std::vector<double>        relaxation_u, relaxation_a; // -relaxation adaptive
  std::vector<double>        eigenvector;                // the re-estimated step
};

// Collective: the checksum of the arrays of every rank's block.
template <int D>
PetscErrorCode BlockHash(MPI_Comm comm, const NaturalOrder &order, const CheckpointBlock &block, std::uint64_t *hash);

// The header values that steer the continuation (step, time, schedule, relaxation and
// time-step state), added to BlockHash's sum to make content_hash.
std::uint64_t HeaderHash(const CheckpointHeader &h);

// Format version 3 on: the checksum of what rank 0 stores and a restart restores
// besides the arrays (the options, history.csv, static_states.csv, the field frames
// and the reason), checked as the header is read, before the options are merged.
std::uint64_t TextHash(const CheckpointHeader &h);

} // namespace bapd
