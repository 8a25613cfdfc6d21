// The output directory a run writes into: its lock, a restart's check for newer
// results, and files written whole (output_directory.hpp).
#include "bapd/solver/io/output_directory.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "bapd/solver/io/hdf5_io.hpp"

namespace bapd {

namespace {

// Rank 0's text on every rank.
PetscErrorCode BcastText(MPI_Comm comm, std::string *text)
{
  PetscFunctionBegin;
  int length = (int)text->size();
  PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm));
  text->resize((std::size_t)length);
  if (length) PetscCallMPI(MPI_Bcast(text->data(), length, MPI_CHAR, 0, comm));
  PetscFunctionReturn(0);
}

std::string HostName()
{
  char host[HOST_NAME_MAX + 1] = "";
  if (gethostname(host, sizeof host) != 0) return "this host";
  host[HOST_NAME_MAX] = '\0';
  return host;
}

// Who holds the lock on `fd`'s file: "bapd process 1234 on host node7" (the holder's
// process id from F_GETLK; its name from /proc when it runs on this host).
std::string LockHolder(int fd)
{
  struct flock probe = {};
  probe.l_type       = F_WRLCK;
  probe.l_whence     = SEEK_SET;
  if (fcntl(fd, F_GETLK, &probe) != 0 || probe.l_type == F_UNLCK || probe.l_pid <= 0) return "another process";
  const std::string proc = "/proc/" + std::to_string((long)probe.l_pid);
  std::ifstream     comm(proc + "/comm");
  std::string       name;
  if (!comm || !std::getline(comm, name)) return "process " + std::to_string((long)probe.l_pid) + ", not on this host (" + HostName() + ")";
  return name + " process " + std::to_string((long)probe.l_pid) + " on host " + HostName();
}


// Rank 0: the results in `dir` newer than a checkpoint's step, in words ("" if none):
// history rows, another checkpoint.h5, field files. `newer_checkpoint` and
// `newer_fields` receive what -restart_discard_newer deletes.
std::string FindNewerResults(const std::string &dir, const std::string &checkpoint, long long step, std::string *newer_checkpoint,
                             std::vector<std::string> *newer_fields)
{
  std::vector<std::string> found;
  {
    std::ifstream in(OutputPaths(dir).history());
    long long     rows = 0, last = -1;
    for (std::string line; std::getline(in, line);) {
      const long long s = HistoryRowStep(line);
      if (s > step) ++rows, last = std::max(last, s);
    }
    if (rows) found.push_back("history.csv has " + std::to_string(rows) + " row(s) after step " + std::to_string(step) + " (up to step " +
                              std::to_string(last) + ")");
  }
  {
    const std::string other = OutputPaths(dir).checkpoint();
    std::error_code   ec;
    if (std::filesystem::exists(other, ec) && !std::filesystem::equivalent(other, checkpoint, ec)) {
      H5Quiet      quiet;
      const hid_t  file = H5Fopen(other.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      std::int64_t other_step = -1;
      double       other_time = 0;
      if (file >= 0) {
        if (!H5ReadAttribute(file, "/", "step", &other_step) || !H5ReadAttribute(file, "/", "time_s", &other_time)) other_step = -1;
        H5Fclose(file);
      }
      // (one that cannot be read is no result: a restart from it would be refused too)
      if (other_step > step) {
        char text[256];
        std::snprintf(text, sizeof text, "checkpoint.h5 is at step %lld (t = %.6e s)", (long long)other_step, other_time);
        found.push_back(text);
        *newer_checkpoint = other;
      }
    }
  }
  {
    std::error_code ec;
    long long       last = -1;
    std::string     last_name;
    for (const auto &entry : std::filesystem::directory_iterator(OutputPaths(dir).fields_folder(), ec)) {
      const std::string name = entry.path().filename().string();
      long long         s    = -1;
      char              tail[8];
      if (std::sscanf(name.c_str(), "step_%lld.h%2s", &s, tail) == 2 && std::strcmp(tail, "5") == 0 && s > step) {
        newer_fields->push_back(entry.path().string());
        if (s > last) last = s, last_name = name;
      }
    }
    if (!newer_fields->empty())
      found.push_back(std::to_string(newer_fields->size()) + " field file(s) after step " + std::to_string(step) + " (up to fields/" +
                      last_name + ")");
  }
  std::string text;
  for (std::size_t k = 0; k < found.size(); ++k) text += (k ? ", " : "") + found[k];
  return text;
}

} // namespace

std::string OutputPaths::FieldName(long long step)
{
  char name[64];
  std::snprintf(name, sizeof name, "fields/step_%08lld.h5", step);
  return name;
}

std::string ShortenedPath(const std::string &path)
{
  if (path.size() <= 400) return path;
  return path.substr(0, 150) + "..." + path.substr(path.size() - 150) + " (" + std::to_string(path.size()) + " characters)";
}

long long HistoryRowStep(const std::string &line)
{
  if (line.empty() || line[0] < '0' || line[0] > '9') return -1;
  return std::atoll(line.c_str());
}

OutputDirectoryLock::~OutputDirectoryLock()
{
  if (fd_ >= 0) ::close(fd_); // (closing drops the lock)
}

PetscErrorCode OutputDirectoryLock::Acquire(MPI_Comm comm, const std::string &dir)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // 0: locked; 1: another run holds it (text: who); 2: cannot be created or opened
  // (text: why); 3: the file system has no locks (text: why).
  int         outcome = 0;
  std::string text;
  const std::string path = OutputPaths(dir).lock();
  if (rank == 0 && fd_ < 0) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const int fd = ec ? -1 : ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) outcome = 2, text = ec ? "cannot create the directory: " + ec.message() : std::string(std::strerror(errno));
    else {
      struct flock lock = {};
      lock.l_type       = F_WRLCK; // the whole file
      lock.l_whence     = SEEK_SET;
      if (fcntl(fd, F_SETLK, &lock) == 0) fd_ = fd;
      else {
        const int error = errno;
        if (error == EACCES || error == EAGAIN) outcome = 1, text = LockHolder(fd);
        else outcome = 3, text = std::strerror(error);
        ::close(fd);
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&outcome, 1, MPI_INT, 0, comm));
  PetscCall(BcastText(comm, &text));
  PetscCheck(outcome != 2, comm, PETSC_ERR_FILE_OPEN, "-output_dir %s: cannot write %s (%s): choose a writable directory, e.g. -output_dir output",
             ShortenedPath(dir).c_str(), ShortenedPath(path).c_str(), text.c_str());
  PetscCheck(outcome != 1, comm, PETSC_ERR_USER,
             "-output_dir %s is in use by another run (%s holds %s): two runs in one directory would overwrite each other's files. "
             "Give this run another directory (e.g. -output_dir %s_2) or wait until that run ends",
             dir.c_str(), text.c_str(), path.c_str(), dir.c_str());
  if (outcome == 3)
    PetscCall(PetscFPrintf(comm, PETSC_STDERR,
                           "bapd: warning: cannot lock %s (%s): this file system has no locks, so another run started in %s would not be "
                           "stopped: start only one run there at a time\n",
                           path.c_str(), text.c_str(), dir.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckNewerResults(MPI_Comm comm, const std::string &dir, const std::string &checkpoint, PetscInt step, double time, bool discard)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::string              newer, newer_checkpoint;
  std::vector<std::string> newer_fields;
  if (rank == 0) newer = FindNewerResults(dir, checkpoint, (long long)step, &newer_checkpoint, &newer_fields);
  PetscCall(BcastText(comm, &newer));
  if (newer.empty()) PetscFunctionReturn(0);
  // The directory's own checkpoint.h5 with nothing newer than it but rows and field
  // files: what a run killed after its last checkpoint left, which this continuation
  // writes again (bit for bit with the same options): the usual restart, not refused.
  int own = 0;
  if (rank == 0) {
    std::error_code ec;
    own = newer_checkpoint.empty() && std::filesystem::equivalent(OutputPaths(dir).checkpoint(), checkpoint, ec) ? 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(&own, 1, MPI_INT, 0, comm));
  if (!discard && !own) {
    // The fix: the newest checkpoint if there is one, else another directory or the option.
    std::string fix;
    PetscCall(BcastText(comm, &newer_checkpoint));
    if (!newer_checkpoint.empty()) fix = "Continue from the newest checkpoint (-restart " + newer_checkpoint + "), or write";
    else fix = "Write";
    fix += " this continuation into another directory (-output_dir " + dir + "_from_step_" + std::to_string((long long)step) +
           "), or give -restart_discard_newer to drop the newer results and continue here";
    SETERRQ(comm, PETSC_ERR_USER,
            "-restart %s is the state at step %" PetscInt_FMT " (t = %.6e s), but %s holds newer results: %s. Continuing there would "
            "replace them. %s",
            checkpoint.c_str(), step, time, dir.c_str(), newer.c_str(), fix.c_str());
  }
  int error = 0;
  if (rank == 0) {
    for (const std::string &file : newer_fields)
      if (std::remove(file.c_str()) != 0 && !error) error = errno;
    if (!newer_checkpoint.empty() && std::remove(newer_checkpoint.c_str()) != 0 && !error) error = errno;
  }
  PetscCallMPI(MPI_Bcast(&error, 1, MPI_INT, 0, comm));
  PetscCheck(!error, comm, PETSC_ERR_FILE_WRITE, "-restart_discard_newer: cannot delete the newer results in %s (%s): delete them yourself",
             dir.c_str(), std::strerror(error));
  if (discard) PetscCall(PetscPrintf(comm, "-restart_discard_newer: dropped what %s held after step %" PetscInt_FMT ": %s\n", dir.c_str(), step, newer.c_str()));
  else
    PetscCall(PetscPrintf(comm, "Note: %s holds results after its checkpoint's step %" PetscInt_FMT " (%s), from the run stopped after it: this run writes them again\n",
                          dir.c_str(), step, newer.c_str()));
  PetscFunctionReturn(0);
}

int WriteFileWhole(const std::string &path, const std::function<void(FILE *)> &write, FILE **keep)
{
  const std::string tmp = path + ".tmp";
  FILE             *f   = std::fopen(tmp.c_str(), "w");
  if (!f) return errno ? errno : EIO;
  errno = 0;
  write(f);
  // Every write checked: a full disk shows at the flush or the sync, or earlier as the error flag.
  int error = (std::fflush(f) != 0 || std::ferror(f)) ? (errno ? errno : EIO) : 0;
  if (!error && ::fsync(fileno(f)) != 0) error = errno;
  if (error || !keep) {
    if (std::fclose(f) != 0 && !error) error = errno ? errno : EIO;
    f = nullptr;
  }
  if (!error && std::rename(tmp.c_str(), path.c_str()) != 0) error = errno;
  if (error) {
    if (f) std::fclose(f);
    std::remove(tmp.c_str()); // a previous `path` stays
    return error;
  }
  if (keep) *keep = f; // (the stream follows the file through the rename)
  return 0;
}

} // namespace bapd
