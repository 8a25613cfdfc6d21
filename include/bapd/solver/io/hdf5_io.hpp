#pragma once
// Small helpers over parallel HDF5 for the field and checkpoint files: 1-D or 2-D
// datasets whose rows are split over the ranks in contiguous blocks
// (natural_order.hpp), attributes, and text. Every rank makes the same calls, in the
// same order. A failure is recorded and reported by Close(), on every rank alike
// (the ranks agree before HDF5's collective close and after it), so it never leaves
// a rank waiting: check Close() before using what was read.
//
// A full disk: parallel HDF5 cannot recover from a write that fails on some ranks
// inside its collective metadata flush (H5Fclose then waits in mismatched
// collectives, or leaves a half-closed file that crashes MPI_Finalize). So a file
// is created only after its whole size has been reserved on the disk (Create's
// `bytes`): a disk without the room is reported before HDF5 writes anything. A disk
// that another program fills after the reservation fails a write: the ranks agree on
// it before the close. The close itself needs room for HDF5's metadata, which it
// writes then: a close that fails on one rank only leaves the others in mismatched
// collectives (a hang, or a crash). So rank 0 also keeps that room taken, in a file
// `<path>.room` (allocated, empty of data) from the creation to the close, and gives
// it back just before the collective close: the metadata fits even on a disk filled
// since, and the close ends alike on every rank.
#include <hdf5.h>
#include <petscsys.h>

#include <cstdint>
#include <string>
#include <vector>

namespace bapd {

// Silences HDF5's own error stack while alive: bapd reports one clear message.
class H5Quiet {
public:
  H5Quiet();
  ~H5Quiet();
  H5Quiet(const H5Quiet &)            = delete;
  H5Quiet &operator=(const H5Quiet &) = delete;

private:
  H5E_auto2_t func_ = nullptr;
  void       *data_ = nullptr;
};

// A parallel HDF5 file (MPI-IO driver, collective transfers).
class H5ParallelFile {
public:
  H5ParallelFile() = default;
  ~H5ParallelFile(); // closes without reporting (after an error elsewhere)
  H5ParallelFile(const H5ParallelFile &)            = delete;
  H5ParallelFile &operator=(const H5ParallelFile &) = delete;

  // Creates (truncating) a file of `data_bytes` in datasets and `objects` datasets,
  // groups and attributes, after reserving its size (H5FileBytes) on its disk and
  // taking the room of its metadata (H5FileBytes(0, objects)) until Close(); or opens
  // read-only. Errors: PETSC_ERR_FILE_WRITE (no room: the cause, e.g. "No space left
  // on device"), PETSC_ERR_FILE_OPEN.
  PetscErrorCode Create(MPI_Comm comm, const std::string &path, std::uint64_t data_bytes, std::uint64_t objects);
  PetscErrorCode Open(MPI_Comm comm, const std::string &path) { return Begin(comm, path, false); }
  // Collective: flushes, closes, reports any failure (the destructor only closes). A
  // file being written that failed is removed: a partial file is no use to anyone.
  PetscErrorCode Close();

  // rows x cols dataset (cols = 0: 1-D of `rows`); this rank writes or reads rows
  // [start, start + count) from/to data (count * max(cols, 1) entries).
  PetscErrorCode WriteBlock(const char *name, hid_t type, hsize_t rows, hsize_t cols, hsize_t start, hsize_t count,
                            const void *data);
  PetscErrorCode ReadBlock(const char *name, hid_t type, hsize_t rows, hsize_t cols, hsize_t start, hsize_t count,
                           void *data);
  // A 1-D dataset written by rank 0 alone (text, short tables): `root_data` is only
  // read on rank 0; `length` must agree on every rank.
  PetscErrorCode WriteRoot(const char *name, hid_t type, hsize_t length, const void *root_data);
  PetscErrorCode WriteText(const char *name, const std::string &root_text); // rank 0's text
  PetscErrorCode CreateGroup(const char *name);

  // Attributes of the root group ("/") or of a group; the same value on every rank.
  PetscErrorCode WriteAttribute(const char *object, const char *name, double value);
  PetscErrorCode WriteAttribute(const char *object, const char *name, std::int64_t value);
  PetscErrorCode WriteAttribute(const char *object, const char *name, std::uint64_t value);
  PetscErrorCode WriteAttribute(const char *object, const char *name, const std::string &value);

  hid_t id() const { return file_; }

private:
  PetscErrorCode Begin(MPI_Comm comm, const std::string &path, bool writing); // Create or Open
  void        Record(bool ok, const char *what, const char *name);
  // WriteBlock (write: create the dataset and write) and ReadBlock (open and read).
  PetscErrorCode Block(const char *name, hid_t type, hsize_t rows, hsize_t cols, hsize_t start, hsize_t count, bool write,
                       void *data);
  MPI_Comm    comm_ = MPI_COMM_NULL;
  hid_t       file_ = -1;
  std::string path_, failed_; // the first failed call on this rank
  std::string room_;          // rank 0: the metadata's room (`<path>.room`) while it exists
  void        GiveBackRoom();
  bool        writing_ = true;
};

// An upper bound of the size of an HDF5 file holding `data_bytes` of datasets and
// `objects` datasets, groups and attributes (HDF5's headers, heaps and B-trees).
std::uint64_t H5FileBytes(std::uint64_t data_bytes, std::uint64_t objects);

// Collective: rank 0 reserves `bytes` for `path` (posix_fallocate, then removed again)
// and every rank learns the outcome; "" if there is room, else the cause (strerror).
PetscErrorCode H5ReserveSpace(MPI_Comm comm, const std::string &path, std::uint64_t bytes, std::string *cause);

// Serial reads (one rank) of a file another process wrote; false on any failure
// (missing object, wrong type or shape), never an HDF5 error stack.
bool H5ReadAttribute(hid_t file, const char *object, const char *name, double *value);
bool H5ReadAttribute(hid_t file, const char *object, const char *name, std::int64_t *value);
bool H5ReadAttribute(hid_t file, const char *object, const char *name, std::uint64_t *value);
bool H5ReadAttribute(hid_t file, const char *object, const char *name, std::string *value);
// Dimensions of a dataset (empty if it does not exist).
std::vector<hsize_t> H5DatasetShape(hid_t file, const char *name);
bool                 H5ReadText(hid_t file, const char *name, std::string *text);
bool                 H5ReadDoubles(hid_t file, const char *name, std::vector<double> *values);

} // namespace bapd
