#pragma once
// The output directory a run writes into, claimed before anything is written in it
// (docs/faults.md):
//  - it is locked for the run's life (OutputDirectoryLock): a second run into the same
//    directory stops at once instead of overwriting the first one's files. Rank 0
//    holds a POSIX record lock (fcntl) on <dir>/.bapd.lock, an empty file; the kernel
//    drops the lock when the process ends, however it ends, so a killed run leaves no
//    stale lock. (An empty file takes no block on the disk: a nearly full disk keeps
//    its room for the results.)
//  - a restart does not replace results newer than its checkpoint
//    (CheckNewerResults): history rows after the checkpoint's step, a later
//    checkpoint.h5 or later field files are refused, or dropped on request
//    (-restart_discard_newer).
// And every end-of-run text file is written whole or not at all (WriteFileWhole).
// Every path into the directory is built by OutputPaths: one list of the files a run
// writes.
#include <petscsys.h>

#include <cstdio>
#include <functional>
#include <string>
#include <utility>

namespace bapd {

// The files of a run's output directory, named in one place: the driver, its
// reporters and the writers in solver/io build every path here.
class OutputPaths {
public:
  OutputPaths() = default;
  explicit OutputPaths(std::string dir) : dir_(std::move(dir)) {}

  const std::string &dir() const { return dir_; }
  std::string        file(const std::string &name) const { return dir_ + "/" + name; } // <dir>/name

  std::string history() const { return file("history.csv"); }           // a row per -output_interval steps
  std::string static_states() const { return file("static_states.csv"); } // a row per static state
  std::string checkpoint() const { return file("checkpoint.h5"); }
  std::string final_state() const { return file("final_state.csv"); }
  std::string broken_bonds() const { return file("broken_bonds.csv"); }
  std::string fields_folder() const { return file("fields"); }
  std::string field_index() const { return file("fields.xdmf"); }
  std::string field_file(long long step) const { return file(FieldName(step)); }
  std::string lock() const { return file(".bapd.lock"); }
  // A restart's copy of earlier rows whose columns this run does not write:
  // <stem>_to_step_N.csv (stem: history or static_states).
  std::string rows_copy_name(const std::string &stem, long long step) const { return stem + "_to_step_" + std::to_string(step) + ".csv"; }

  // A field file's name inside the directory, "fields/step_NNNNNNNN.h5" (fields.xdmf
  // lists them so).
  static std::string FieldName(long long step);

private:
  std::string dir_;
};

class OutputDirectoryLock {
public:
  OutputDirectoryLock() = default;
  ~OutputDirectoryLock(); // releases the lock (the file stays: it may be another run's by then)
  OutputDirectoryLock(const OutputDirectoryLock &)            = delete;
  OutputDirectoryLock &operator=(const OutputDirectoryLock &) = delete;

  // Collective. Rank 0 creates `dir` if needed and locks it; a directory another run
  // holds is refused on every rank with one message naming that run (its process
  // and host) and the fix. A file system without locks draws a warning, and the run
  // goes on unlocked.
  PetscErrorCode Acquire(MPI_Comm comm, const std::string &dir);

private:
  int fd_ = -1; // rank 0's open lock file while it holds the lock
};

// Collective. A restart from `checkpoint` (at `step`, time `time`) that writes into
// `dir`: refused with one message when `dir` holds results newer than the checkpoint
// (history.csv rows after `step`, a checkpoint.h5 other than `checkpoint` with a later
// step, field files after `step`), which continuing there would replace. With
// `discard` (-restart_discard_newer) they are dropped instead: the newer field files
// and checkpoint.h5 are deleted here, the history rows when the restart writes
// history.csv. The directory's own checkpoint.h5, with nothing newer than it but rows
// and field files (a run killed after its last checkpoint), is the usual restart: its
// newer results are dropped as with `discard`, with a note, and written again.
PetscErrorCode CheckNewerResults(MPI_Comm comm, const std::string &dir, const std::string &checkpoint, PetscInt step, double time,
                                 bool discard);

// The step of a history.csv row ("step,time,..."); -1 for the header or a cut row.
long long HistoryRowStep(const std::string &line);

// A path as an error line shows it: whole up to 400 characters, else its first and last
// 150 and its length (PETSc cuts a message at 2048 characters, which would drop the
// cause after a path of thousands).
std::string ShortenedPath(const std::string &path);

// Rank 0: writes the file `path` whole or not at all, as checkpoints and fields.xdmf
// are written: `write` fills `path`.tmp, which is flushed, synced and renamed over
// `path` only when every write succeeded; otherwise it is removed and a previous
// `path` stays as it was. Returns 0 or the errno of the first failure. With `keep`, the
// stream is left open on the renamed file, at its end, for rows that follow.
int WriteFileWhole(const std::string &path, const std::function<void(FILE *)> &write, FILE **keep = nullptr);

} // namespace bapd
