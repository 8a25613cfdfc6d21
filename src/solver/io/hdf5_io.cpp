#include "bapd/solver/io/hdf5_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace bapd {

H5Quiet::H5Quiet()
{
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

H5Quiet::~H5Quiet() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

// A failed call is recorded, not reported at once: every rank makes the same calls
// whatever their outcome, and Close() agrees on the outcome with a reduction before
// its collective close and one after (a reduction per call costs more than the
// writing on a busy node).
void H5ParallelFile::Record(bool ok, const char *what, const char *name)
{
  if (ok || !failed_.empty()) return;
  failed_ = std::string(what) + " '" + name + "'";
}

// Creates (writing) or opens read-only, collectively: every rank agrees on the outcome
// before anyone reports it, and a rank that did open the file closes it again.
PetscErrorCode H5ParallelFile::Begin(MPI_Comm comm, const std::string &path, bool writing)
{
  H5Quiet quiet;

  PetscFunctionBegin;
  comm_      = comm;
  path_      = path;
  writing_   = writing;
  failed_.clear();
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  bool  ok   = fapl >= 0 && H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL) >= 0;
  if (!ok) file_ = -1;
  else file_ = writing ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl) : H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  if (fapl >= 0) H5Pclose(fapl);
  int all = file_ >= 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, comm));
  if (!all && file_ >= 0) {
    H5Fclose(file_);
    file_ = -1;
  }
  if (!all && writing) {
    // HDF5 gives no errno: rank 0 tells a vanished directory from the rest.
    PetscMPIInt       rank;
    const std::size_t slash = path.find_last_of('/');
    struct stat       st;
    int               gone  = 0;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (rank == 0) gone = slash != std::string::npos && stat(path.substr(0, std::max<std::size_t>(slash, 1)).c_str(), &st) != 0;
    PetscCallMPI(MPI_Bcast(&gone, 1, MPI_INT, 0, comm));
    SETERRQ(comm, PETSC_ERR_FILE_OPEN, "Cannot create %s: %s", path.c_str(),
            gone ? "No such file or directory (the output directory was deleted during the run?)" : "choose a writable -output_dir");
  }
  PetscCheck(all, comm, PETSC_ERR_FILE_OPEN, "Cannot open %s for reading (missing, truncated or not an HDF5 file)", path.c_str());
  PetscFunctionReturn(0);
}

H5ParallelFile::~H5ParallelFile()
{
  GiveBackRoom();
  if (file_ < 0) return;
  H5Quiet quiet;
  H5Fclose(file_);
}

void H5ParallelFile::GiveBackRoom()
{
  if (room_.empty()) return;
  ::unlink(room_.c_str());
  room_.clear();
}

PetscErrorCode H5ParallelFile::Create(MPI_Comm comm, const std::string &path, std::uint64_t data_bytes, std::uint64_t objects)
{
  const std::uint64_t bytes = H5FileBytes(data_bytes, objects), room = H5FileBytes(0, objects);
  std::string         cause;
  PetscMPIInt         rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(H5ReserveSpace(comm, path, bytes, &cause));
  // The metadata's room, kept until the close (hdf5_io.hpp); part of `bytes`, so the
  // reservation above has made sure of it. A disk that fills in between fails here.
  int error = 0;
  if (cause.empty() && rank == 0) {
    const std::string name = path + ".room";
    const int         fd   = ::open(name.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) error = errno;
    else {
      error = posix_fallocate(fd, 0, (off_t)room);
      if (::close(fd) != 0 && !error) error = errno;
      if (error) ::unlink(name.c_str());
      else room_ = name;
    }
  }
  PetscCallMPI(MPI_Bcast(&error, 1, MPI_INT, 0, comm));
  if (cause.empty() && error) cause = std::strerror(error);
  PetscCheck(cause.empty(), comm, PETSC_ERR_FILE_WRITE, "Cannot write %s: %s (it needs about %.2f MB): free some space or choose another -output_dir",
             path.c_str(), cause.c_str(), (double)bytes / 1e6);
  PetscCall(Begin(comm, path, true));
  PetscFunctionReturn(0);
}

namespace {

// Rank 0's guess at why a write failed that the reservation did not foresee.
std::string WriteCause(const std::string &path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::string dir   = slash == std::string::npos ? "." : path.substr(0, std::max<std::size_t>(slash, 1));
  struct statvfs    fs;
  if (statvfs(dir.c_str(), &fs) == 0 && (double)fs.f_bavail * (double)fs.f_frsize < 1e6) return std::strerror(ENOSPC);
  return "disk full, quota or no permission?";
}

} // namespace

PetscErrorCode H5ParallelFile::Close()
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  if (file_ < 0) PetscFunctionReturn(0);
  H5Quiet quiet;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  // The ranks agree on what failed before the collective close and again after it;
  // every rank closes whatever the outcome (HDF5's close is collective). Rank 0
  // prints: it names its own failure, or the lowest failing rank's.
  int failing = failed_.empty() ? INT32_MAX : rank, first = INT32_MAX;
  PetscCallMPI(MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, comm_));
  // The close writes the metadata: rank 0 gives back the room it kept for it
  // (Create), and every rank flushes only once it has (a close failing on some ranks
  // hangs the others, or crashes them). The file is not cut short under HDF5: its
  // flush reads back what it wrote before.
  GiveBackRoom();
  if (writing_) PetscCallMPI(MPI_Barrier(comm_));
  Record(H5Fclose(file_) >= 0, "close", path_.c_str());
  file_ = -1;
  if (first == INT32_MAX) {
    failing = failed_.empty() ? INT32_MAX : rank;
    PetscCallMPI(MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, comm_));
  }
  if (first == INT32_MAX) PetscFunctionReturn(0);
  std::string what = failed_;
  unsigned long long n = what.size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, first, comm_));
  what.resize(n);
  PetscCallMPI(MPI_Bcast(what.data(), (int)n, MPI_CHAR, first, comm_));
  std::string cause = writing_ ? "" : "a damaged file?";
  if (writing_ && rank == 0) {
    cause = WriteCause(path_);
    std::remove(path_.c_str());
  }
  if (writing_) {
    n = cause.size();
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm_));
    cause.resize(n);
    PetscCallMPI(MPI_Bcast(cause.data(), (int)n, MPI_CHAR, 0, comm_));
  }
  SETERRQ(comm_, writing_ ? PETSC_ERR_FILE_WRITE : PETSC_ERR_FILE_UNEXPECTED, "HDF5 could not %s in %s (%s)%s", what.c_str(), path_.c_str(),
          cause.c_str(), writing_ ? ": the file is removed; free some space or choose another -output_dir" : "");
}

std::uint64_t H5FileBytes(std::uint64_t data_bytes, std::uint64_t objects)
{
  // HDF5's superblock, root group and free-space slack, plus about 1 KB of object
  // header, heap and B-tree per object: a generous bound (measured on the 21 x 21
  // sheet of tests/data/scenes/tiny.yaml, 2 ranks: checkpoint 119 KB written, 158 KB
  // reserved; field file 164 KB written, 196 KB reserved).
  return data_bytes + 1024 * objects + 16384;
}

PetscErrorCode H5ReserveSpace(MPI_Comm comm, const std::string &path, std::uint64_t bytes, std::string *cause)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  int error = 0;
  // BAPD_TEST_NO_SPACE_RESERVATION (tests/faults only): no reservation, so that a
  // full disk fails the writes themselves, as when another program fills it later.
  if (rank == 0 && bytes > 0 && !std::getenv("BAPD_TEST_NO_SPACE_RESERVATION")) {
    // Blocks really allocated (posix_fallocate writes them where the file system
    // cannot preallocate), then given back for HDF5 to write: the file fits.
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) error = errno;
    else {
      error = posix_fallocate(fd, 0, (off_t)bytes);
      if (::close(fd) != 0 && !error) error = errno;
      ::unlink(path.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(&error, 1, MPI_INT, 0, comm));
  *cause = error ? std::strerror(error) : "";
  PetscFunctionReturn(0);
}

namespace {

// File and memory dataspaces selecting rows [start, start + count).
struct BlockSpaces {
  hid_t file = -1, memory = -1;
  BlockSpaces(hsize_t rows, hsize_t cols, hsize_t start, hsize_t count)
  {
    const int     rank        = cols ? 2 : 1;
    const hsize_t dims[2]     = {rows, cols};
    const hsize_t offset[2]   = {start, 0};
    const hsize_t extent[2]   = {count, cols};
    const hsize_t mem_dims[2] = {std::max<hsize_t>(count, 1), cols};
    file                      = H5Screate_simple(rank, dims, nullptr);
    memory                    = H5Screate_simple(rank, mem_dims, nullptr);
    if (count == 0 || rows == 0) {
      H5Sselect_none(file);
      H5Sselect_none(memory);
    } else {
      H5Sselect_hyperslab(file, H5S_SELECT_SET, offset, nullptr, extent, nullptr);
    }
  }
  ~BlockSpaces()
  {
    if (file >= 0) H5Sclose(file);
    if (memory >= 0) H5Sclose(memory);
  }
};

// Each rank moves one contiguous block of every dataset: independent transfers do
// that directly, without the two-phase shuffle of collective ones (which on a busy
// node costs tens of ms per dataset).
hid_t BlockTransfer()
{
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_INDEPENDENT);
  return dxpl;
}

} // namespace

PetscErrorCode H5ParallelFile::Block(const char *name, hid_t type, hsize_t rows, hsize_t cols, hsize_t start,
                                     hsize_t count, bool write, void *data)
{
  H5Quiet quiet;

  PetscFunctionBegin;
  BlockSpaces spaces(rows, cols, start, count);
  hid_t       dxpl = BlockTransfer();
  hid_t       set  = write ? H5Dcreate2(file_, name, type, spaces.file, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)
                           : H5Dopen2(file_, name, H5P_DEFAULT);
  bool        ok   = set >= 0;
  if (ok && rows > 0)
    ok = (write ? H5Dwrite(set, type, spaces.memory, spaces.file, dxpl, data)
                : H5Dread(set, type, spaces.memory, spaces.file, dxpl, data)) >= 0;
  if (set >= 0) ok = H5Dclose(set) >= 0 && ok;
  H5Pclose(dxpl);
  Record(ok, write ? "write" : "read", name);
  PetscFunctionReturn(0);
}

PetscErrorCode H5ParallelFile::WriteBlock(const char *name, hid_t type, hsize_t rows, hsize_t cols, hsize_t start,
                                          hsize_t count, const void *data)
{
  // H5Dwrite only reads the buffer.
  return Block(name, type, rows, cols, start, count, true, const_cast<void *>(data));
}

PetscErrorCode H5ParallelFile::ReadBlock(const char *name, hid_t type, hsize_t rows, hsize_t cols, hsize_t start,
                                         hsize_t count, void *data)
{
  return Block(name, type, rows, cols, start, count, false, data);
}

PetscErrorCode H5ParallelFile::WriteRoot(const char *name, hid_t type, hsize_t length, const void *root_data)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCall(WriteBlock(name, type, length, 0, 0, rank == 0 ? length : 0, root_data));
  PetscFunctionReturn(0);
}

PetscErrorCode H5ParallelFile::WriteText(const char *name, const std::string &root_text)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  unsigned long long length = root_text.size();
  PetscCallMPI(MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, comm_));
  PetscCall(WriteRoot(name, H5T_NATIVE_CHAR, (hsize_t)length, root_text.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode H5ParallelFile::CreateGroup(const char *name)
{
  H5Quiet quiet;

  PetscFunctionBegin;
  hid_t group = H5Gcreate2(file_, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool  ok    = group >= 0 && H5Gclose(group) >= 0;
  Record(ok, "create group", name);
  PetscFunctionReturn(0);
}

namespace {

bool WriteAttributeRaw(hid_t file, const char *object, const char *name, hid_t type, const void *value)
{
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr  = H5Acreate_by_name(file, object, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool  ok    = attr >= 0 && H5Awrite(attr, type, value) >= 0;
  if (attr >= 0) ok = H5Aclose(attr) >= 0 && ok;
  H5Sclose(space);
  return ok;
}

} // namespace

PetscErrorCode H5ParallelFile::WriteAttribute(const char *object, const char *name, double value)
{
  H5Quiet quiet;
  PetscFunctionBegin;
  Record(WriteAttributeRaw(file_, object, name, H5T_NATIVE_DOUBLE, &value), "write attribute", name);
  PetscFunctionReturn(0);
}

PetscErrorCode H5ParallelFile::WriteAttribute(const char *object, const char *name, std::int64_t value)
{
  H5Quiet quiet;
  PetscFunctionBegin;
  Record(WriteAttributeRaw(file_, object, name, H5T_NATIVE_INT64, &value), "write attribute", name);
  PetscFunctionReturn(0);
}

PetscErrorCode H5ParallelFile::WriteAttribute(const char *object, const char *name, std::uint64_t value)
{
  H5Quiet quiet;
  PetscFunctionBegin;
  Record(WriteAttributeRaw(file_, object, name, H5T_NATIVE_UINT64, &value), "write attribute", name);
  PetscFunctionReturn(0);
}

PetscErrorCode H5ParallelFile::WriteAttribute(const char *object, const char *name, const std::string &value)
{
  H5Quiet quiet;
  PetscFunctionBegin;
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, std::max<std::size_t>(value.size(), 1));
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  std::string padded = value.empty() ? std::string(1, '\0') : value;
  const bool  ok     = WriteAttributeRaw(file_, object, name, type, padded.data());
  H5Tclose(type);
  Record(ok, "write attribute", name);
  PetscFunctionReturn(0);
}

namespace {

hid_t OpenScalarAttribute(hid_t file, const char *object, const char *name, H5T_class_t type_class)
{
  H5Quiet quiet;
  if (H5Aexists_by_name(file, object, name, H5P_DEFAULT) <= 0) return -1;
  hid_t attr = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0) return -1;
  hid_t space = H5Aget_space(attr), type = H5Aget_type(attr);
  const bool scalar = space >= 0 && H5Sget_simple_extent_npoints(space) == 1;
  const bool klass  = type >= 0 && H5Tget_class(type) == type_class;
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  if (!scalar || !klass) {
    H5Aclose(attr);
    return -1;
  }
  return attr;
}

template <class T>
bool ReadNumberAttribute(hid_t file, const char *object, const char *name, H5T_class_t type_class, hid_t memory_type, T *value)
{
  H5Quiet quiet;
  hid_t   attr = OpenScalarAttribute(file, object, name, type_class);
  if (attr < 0) return false;
  const bool ok = H5Aread(attr, memory_type, value) >= 0;
  H5Aclose(attr);
  return ok;
}

} // namespace

bool H5ReadAttribute(hid_t file, const char *object, const char *name, double *value)
{
  return ReadNumberAttribute(file, object, name, H5T_FLOAT, H5T_NATIVE_DOUBLE, value);
}

bool H5ReadAttribute(hid_t file, const char *object, const char *name, std::int64_t *value)
{
  return ReadNumberAttribute(file, object, name, H5T_INTEGER, H5T_NATIVE_INT64, value);
}

bool H5ReadAttribute(hid_t file, const char *object, const char *name, std::uint64_t *value)
{
  return ReadNumberAttribute(file, object, name, H5T_INTEGER, H5T_NATIVE_UINT64, value);
}

bool H5ReadAttribute(hid_t file, const char *object, const char *name, std::string *value)
{
  H5Quiet quiet;
  hid_t   attr = OpenScalarAttribute(file, object, name, H5T_STRING);
  if (attr < 0) return false;
  hid_t       stored = H5Aget_type(attr);
  const bool  is_var = H5Tis_variable_str(stored) > 0;
  std::size_t size   = H5Tget_size(stored);
  H5Tclose(stored);
  bool ok = !is_var && size > 0 && size < (1u << 20);
  if (ok) {
    std::string text(size, '\0');
    hid_t       type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, size);
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    ok = H5Aread(attr, type, text.data()) >= 0;
    H5Tclose(type);
    text.resize(std::min(text.size(), text.find('\0')));
    *value = text;
  }
  H5Aclose(attr);
  return ok;
}

std::vector<hsize_t> H5DatasetShape(hid_t file, const char *name)
{
  H5Quiet quiet;
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return {};
  hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  if (set < 0) return {};
  hid_t                space = H5Dget_space(set);
  const int            rank  = space >= 0 ? H5Sget_simple_extent_ndims(space) : -1;
  std::vector<hsize_t> dims(rank > 0 ? rank : 0);
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  if (rank == 0) dims.push_back(1); // scalar
  if (space >= 0) H5Sclose(space);
  H5Dclose(set);
  return dims;
}

namespace {

bool ReadWhole(hid_t file, const char *name, hid_t memory_type, std::size_t elements, void *data)
{
  H5Quiet quiet;
  if (elements == 0) return true;
  hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  if (set < 0) return false;
  const bool ok = H5Dread(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0;
  H5Dclose(set);
  return ok;
}

} // namespace

bool H5ReadText(hid_t file, const char *name, std::string *text)
{
  const std::vector<hsize_t> shape = H5DatasetShape(file, name);
  if (shape.size() != 1) return false;
  text->assign(shape[0], '\0');
  return ReadWhole(file, name, H5T_NATIVE_CHAR, shape[0], text->data());
}

bool H5ReadDoubles(hid_t file, const char *name, std::vector<double> *values)
{
  const std::vector<hsize_t> shape = H5DatasetShape(file, name);
  if (shape.empty()) return false;
  std::size_t n = 1;
  for (hsize_t d : shape) n *= d;
  values->assign(n, 0.0);
  return ReadWhole(file, name, H5T_NATIVE_DOUBLE, n, values->data());
}

} // namespace bapd
