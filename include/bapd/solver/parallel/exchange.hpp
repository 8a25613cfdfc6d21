#pragma once
// The set-up's all-to-all exchange of numbers between ranks (distributed_body.cpp,
// cloud_block.cpp), and the natural-id blocks it addresses.
#include <petscsys.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace bapd {

template <typename T> MPI_Datatype DatatypeOf();
template <> inline MPI_Datatype DatatypeOf<double>() { return MPI_DOUBLE; }
template <> inline MPI_Datatype DatatypeOf<PetscInt>() { return MPIU_INT; }

// out[r] to rank r; *in gets what every rank sent here, in rank order.
template <typename T> PetscErrorCode Exchange(MPI_Comm comm, const std::vector<std::vector<T>> &out, std::vector<T> *in)
{
  const int        size = (int)out.size();
  std::vector<int> send_count(size), recv_count(size), send_at(size + 1, 0), recv_at(size + 1, 0);

  PetscFunctionBegin;
  for (int r = 0; r < size; ++r) {
    PetscCheck(out[r].size() < (std::size_t)std::numeric_limits<int>::max(), comm, PETSC_ERR_SUP,
               "The set-up sends more than 2^31 numbers to one rank: run on more ranks");
    send_count[r]   = (int)out[r].size();
    send_at[r + 1]  = send_at[r] + send_count[r];
  }
  PetscCallMPI(MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm));
  for (int r = 0; r < size; ++r) recv_at[r + 1] = recv_at[r] + recv_count[r];
  std::vector<T> send(send_at[size]);
  for (int r = 0; r < size; ++r) std::copy(out[r].begin(), out[r].end(), send.begin() + send_at[r]);
  in->resize(recv_at[size]);
  PetscCallMPI(MPI_Alltoallv(send.data(), send_count.data(), send_at.data(), DatatypeOf<T>(), in->data(), recv_count.data(),
                             recv_at.data(), DatatypeOf<T>(), comm));
  PetscFunctionReturn(0);
}

// Questions ask[r] to rank r: *asked gets every rank's questions here, in rank order,
// and from[r] how many came from rank r (the answers go back in the order asked).
inline PetscErrorCode Ask(MPI_Comm comm, const std::vector<std::vector<PetscInt>> &ask, std::vector<PetscInt> *asked, std::vector<PetscInt> *from)
{
  const int             size = (int)ask.size();
  std::vector<PetscInt> counts(size);

  PetscFunctionBegin;
  for (int r = 0; r < size; ++r) counts[r] = (PetscInt)ask[r].size();
  from->resize(size);
  PetscCallMPI(MPI_Alltoall(counts.data(), 1, MPIU_INT, from->data(), 1, MPIU_INT, comm));
  PetscCall(Exchange(comm, ask, asked));
  PetscFunctionReturn(0);
}

// The rank whose block holds natural id `id` (starts: every rank's first id, then n).
inline int HolderOf(const std::vector<PetscInt> &starts, PetscInt id)
{
  return (int)(std::upper_bound(starts.begin(), starts.end(), id) - starts.begin()) - 1;
}

// The first natural id of rank r's block when n points are cut into `size` blocks of
// n / size points each (the first n % size ranks one more): ScatterBody's blocks.
inline PetscInt BlockFirst(PetscInt n, int size, int r) { return n / size * r + std::min<PetscInt>(r, n % size); }

} // namespace bapd
