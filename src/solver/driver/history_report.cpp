// history.csv and static_states.csv: their columns, rows, schedule and restart
// (history_report.hpp).
#include "bapd/solver/driver/history_report.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "bapd/solver/input/options_reader.hpp"

namespace bapd {

namespace {

// The outcome of rank 0's writing of rows to a CSV file since `row_start` (its
// offset before them): 0; the errno of a failed write or flush, after which the file
// is cut back to its last whole row (the rows before are kept) and what stdio still
// holds goes to /dev/null; or -1 if the file was deleted (st_nlink 0: the output
// directory removed during the run). One fstat: cheap at each history row.
int FinishRows(FILE *f, long row_start)
{
  errno = 0;
  int error = 0;
  if (std::fflush(f) != 0 || std::ferror(f)) error = errno ? errno : EIO;
  struct stat st;
  if (!error && fstat(fileno(f), &st) == 0 && st.st_nlink == 0) return -1;
  if (error) {
    // (never longer: a header that did not reach the disk is not padded with zeros)
    if (row_start >= 0 && fstat(fileno(f), &st) == 0 && st.st_size > row_start && ftruncate(fileno(f), row_start) != 0) {
    } // best effort: the error is reported either way
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, fileno(f));
      ::close(null);
    }
  }
  return error;
}

// The message for FinishRows' outcome (collective after the broadcast of `error`).
PetscErrorCode CheckRows(MPI_Comm comm, int error, const std::string &dir, const char *file)
{
  PetscFunctionBegin;
  PetscCheck(error != -1, comm, PETSC_ERR_FILE_WRITE,
             "%s/%s was deleted during the run (the output directory removed?): the run stops. Keep -output_dir until the run ends",
             dir.c_str(), file);
  PetscCheck(error == 0, comm, PETSC_ERR_FILE_WRITE,
             "Cannot write %s/%s: %s; the rows written before are kept: free some space or choose another -output_dir (continue from "
             "a checkpoint with -restart if one was written)",
             dir.c_str(), file, std::strerror(error));
  PetscFunctionReturn(0);
}

std::vector<std::string> SplitCells(const std::string &line)
{
  std::vector<std::string> cells;
  std::istringstream       in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// The rows of a CSV text (`lines`, the first its header) under another header: each
// cell moves to the column of the same name, and a column the old header lacks gets
// "nan" (what a history column holds before it has a value, e.g. the crack's tip).
// `dropped`: the old columns the new header lacks (their values are not in the result).
std::vector<std::string> RemapColumns(const std::vector<std::string> &lines, const std::string &header, std::vector<std::string> *added,
                                      std::vector<std::string> *dropped)
{
  const std::vector<std::string> from = SplitCells(lines.front()), to = SplitCells(header);
  std::vector<int>               source(to.size(), -1);
  for (std::size_t j = 0; j < to.size(); ++j) {
    const auto it = std::find(from.begin(), from.end(), to[j]);
    if (it != from.end()) source[j] = (int)(it - from.begin());
    else added->push_back(to[j]);
  }
  for (const std::string &name : from)
    if (std::find(to.begin(), to.end(), name) == to.end()) dropped->push_back(name);
  std::vector<std::string> out{header};
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const std::vector<std::string> cells = SplitCells(lines[k]);
    std::string                    row;
    for (std::size_t j = 0; j < to.size(); ++j) {
      if (j) row += ',';
      row += source[j] >= 0 && (std::size_t)source[j] < cells.size() ? cells[(std::size_t)source[j]] : "nan";
    }
    out.push_back(row);
  }
  return out;
}

// The time of a history.csv row ("step,time,..."), as written (%.17g: the same bits).
double HistoryRowTime(const std::string &line)
{
  const std::size_t comma = line.find(',');
  return comma == std::string::npos ? 0.0 : std::strtod(line.c_str() + comma + 1, nullptr);
}

std::string Joined(const std::vector<std::string> &names)
{
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k) text += (k ? ", " : "") + names[k];
  return text;
}

} // namespace

double NominalArea(const BodyExtent &b)
{
  return b.dimension == 3 ? (b.hi[0] - b.lo[0]) * (b.hi[2] - b.lo[2]) : (b.hi[0] - b.lo[0]) * b.thickness;
}

HistoryReport::~HistoryReport()
{
  if (history_) std::fclose(history_);
  if (static_states_) std::fclose(static_states_);
}

void HistoryReport::Setup(const LoadingSection &loading, const FailureSection &failure, const OutputSection &output,
                          const BodyExtent &body, const OutputPaths &paths)
{
  loading_  = &loading;
  failure_  = failure.enabled;
  interval_ = output.interval;
  area_     = NominalArea(body);
  paths_    = paths;
  dim_      = body.dimension;
}

// The header of history.csv: its columns for this scene's load sets, probes,
// dimension and failure (docs/options_run.md, "Output").
std::string HistoryReport::Header() const
{
  std::string h = "step,time_s,stretch";
  // (z columns in 3D only: a 2D history keeps its columns)
  for (const LoadSet &s : loading_->sets) {
    h += Format(",%s_reaction_x_N,%s_reaction_y_N", s.name.c_str(), s.name.c_str());
    if (dim_ == 3) h += Format(",%s_reaction_z_N", s.name.c_str());
    h += Format(",%s_nominal_stress_Pa", s.name.c_str());
  }
  for (const Probe &p : loading_->probes) {
    h += Format(",%s_ux_m,%s_uy_m", p.name.c_str(), p.name.c_str());
    if (dim_ == 3) h += Format(",%s_uz_m", p.name.c_str());
  }
  h += ",kinetic_energy_J,internal_energy_J,broken_bonds,dt_s"; // dt_s: the next step (time_step_control.hpp)
  // The energy budget (energy_budget.hpp), the crack's columns only with failure.
  for (const LoadSet &s : loading_->sets) h += Format(",%s_work_J", s.name.c_str());
  h += ",damping_dissipation_J,fracture_dissipation_J,energy_balance_residual_J";
  if (failure_) {
    h += ",crack_area_m2,effective_fracture_energy_J_m2,crack_length_m,crack_tip_x_m,crack_tip_y_m";
    if (dim_ == 3) h += ",crack_tip_z_m";
  }
  // The grips' displacement, the mean over each load set's points along each component
  // it holds (fixed or stretched): with <set>_reaction_*_N a force-displacement curve.
  // Last, so that the columns before keep their places.
  for (const LoadSet &s : loading_->sets)
    for (int c = 0; c < dim_; ++c)
      if (s.component(c) != ComponentLoad::free) h += Format(",%s_displacement_%c_m", s.name.c_str(), "xyz"[c]);
  return h;
}

// The header of static_states.csv.
std::string HistoryReport::StaticStatesHeader() const
{
  std::string h = "stretch,time_s,step,kinetic_over_internal";
  for (const Probe &p : loading_->probes) {
    h += Format(",%s_ux_m,%s_uy_m", p.name.c_str(), p.name.c_str());
    if (dim_ == 3) h += Format(",%s_uz_m", p.name.c_str());
  }
  for (const LoadSet &l : loading_->sets) h += Format(",%s_reaction_y_N", l.name.c_str());
  return h;
}

PetscErrorCode HistoryReport::Open(MPI_Comm comm)
{
  PetscMPIInt rank;
  int         ok = 1;
  std::string why; // rank 0, which prints the message

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::error_code ec;
    std::filesystem::create_directories(paths_.dir(), ec);
    const std::string path = paths_.history();
    history_               = ec ? nullptr : std::fopen(path.c_str(), "w");
    ok                     = history_ != nullptr;
    if (!ok) why = ec ? "cannot create the directory: " + ec.message() : std::string(std::strerror(errno));
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "-output_dir %s: cannot write %s/history.csv (%s): choose a writable directory, e.g. -output_dir output",
             paths_.dir().c_str(), paths_.dir().c_str(), why.c_str());
  if (rank == 0) std::fprintf(history_, "%s\n", Header().c_str());
  PetscFunctionReturn(0);
}

bool HistoryReport::Due(PetscInt step, double t, bool *interval_row)
{
  *interval_row       = step % interval_ == 0;
  const bool load_row = by_load_.Due(t); // (every step: it counts the steps it passes)
  return *interval_row || load_row;
}

PetscErrorCode HistoryReport::WriteRow(MPI_Comm comm, const HistoryRow &row)
{
  const int    D     = dim_;
  PetscMPIInt  rank;
  int          error = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    const EnergyBudget &budget    = *row.budget;
    const long          row_start = std::ftell(history_);
    const double        area      = area_;
    std::fprintf(history_, "%" PetscInt_FMT ",%.17g,%.17g", row.step, row.time, row.stretch);
    for (std::size_t s = 0; s < loading_->sets.size(); ++s) {
      for (int c = 0; c < D; ++c) std::fprintf(history_, ",%.17g", row.reaction[D * s + c]);
      std::fprintf(history_, ",%.17g", row.reaction[D * s + 1] / area);
    }
    for (std::size_t p = 0; p < loading_->probes.size(); ++p)
      for (int c = 0; c < D; ++c) std::fprintf(history_, ",%.17g", row.probe_u[D * p + c]);
    std::fprintf(history_, ",%.17g,%.17g,%" PetscInt_FMT ",%.17g", row.kinetic, row.internal, row.broken_bonds, row.next_dt);
    for (std::size_t s = 0; s < budget.load_sets(); ++s) std::fprintf(history_, ",%.17g", budget.grip_work(s));
    std::fprintf(history_, ",%.17g,%.17g,%.17g", budget.damped(), budget.released(), row.residual);
    if (failure_) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      std::fprintf(history_, ",%.17g,%.17g", row.crack_area, row.crack_area > 0 ? budget.released() / row.crack_area : nan);
      for (int c = 0; c <= D; ++c) std::fprintf(history_, ",%.17g", row.crack_tip[c]);
    }
    for (std::size_t s = 0; s < loading_->sets.size(); ++s)
      for (int c = 0; c < D; ++c)
        if (loading_->sets[s].component(c) != ComponentLoad::free) std::fprintf(history_, ",%.17g", row.grip_u[D * s + c]);
    std::fprintf(history_, "\n");
    error = FinishRows(history_, row_start);
  }
  PetscCallMPI(MPI_Bcast(&error, 1, MPI_INT, 0, comm)); // rank 0 wrote: every rank stops alike
  PetscCall(CheckRows(comm, error, paths_.dir(), "history.csv"));
  last_step_ = row.step;
  PetscFunctionReturn(0);
}

PetscErrorCode HistoryReport::WriteStaticState(MPI_Comm comm, double stretch, double t, PetscInt step, double ratio, const double *probe_u,
                                               const double *reaction)
{
  const int   D = dim_;
  PetscMPIInt rank;
  int         error = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0 && !static_states_) {
    static_states_ = std::fopen(paths_.static_states().c_str(), "w");
    if (!static_states_) error = errno;
  }
  if (rank == 0 && static_states_) {
    const long row_start = std::ftell(static_states_);
    if (row_start == 0) std::fprintf(static_states_, "%s\n", StaticStatesHeader().c_str());
    std::fprintf(static_states_, "%.17g,%.17g,%" PetscInt_FMT ",%.6e", stretch, t, step, ratio);
    for (std::size_t p = 0; p < loading_->probes.size(); ++p)
      for (int c = 0; c < D; ++c) std::fprintf(static_states_, ",%.17g", probe_u[D * p + c]);
    for (std::size_t l = 0; l < loading_->sets.size(); ++l) std::fprintf(static_states_, ",%.17g", reaction[D * l + 1]);
    std::fprintf(static_states_, "\n");
    error = FinishRows(static_states_, row_start);
  }
  PetscCallMPI(MPI_Bcast(&error, 1, MPI_INT, 0, comm));
  PetscCall(CheckRows(comm, error, paths_.dir(), "static_states.csv"));
  PetscFunctionReturn(0);
}

void HistoryReport::Texts(std::string *history, std::string *static_states) const
{
  std::ifstream      in(paths_.history());
  std::ostringstream text;
  text << in.rdbuf();
  *history = text.str();
  std::ifstream      states(paths_.static_states());
  std::ostringstream states_text;
  if (states) states_text << states.rdbuf();
  *static_states = states_text.str();
}

// history.csv and static_states.csv of a restart: the checkpoint's rows, to which this
// run's are appended. A last history row at the checkpoint step that is neither on the
// -output_interval grid nor a row by load (-output_history_rows) was the end-of-run row
// of the run that wrote it: the continuation writes its own rows. Columns that differ from the checkpoint's (a probe
// or load set added, failure switched on) keep the earlier rows: each value goes to its
// column by name, "nan" where the earlier run had no such column. A column this run
// does not write (a checkpoint of a bapd with other columns: a probe or load set
// cannot be taken away on a restart, its stored options would be unused) keeps its
// values with the rows as they were in history_to_step_N.csv (static_states_to_step_N.csv). Each file is written whole
// (WriteFileWhole), so a full disk leaves the previous one as it was.
PetscErrorCode HistoryReport::Restore(MPI_Comm comm, const CheckpointHeader &header)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // [errno, which file failed: 0 history.csv, 1 static_states.csv, 2 and 3 their copies of the earlier rows]
  int         error[2] = {0, 0};
  std::string notes; // rank 0: what changed, printed after the broadcast
  PetscInt    last_row = -1; // the step of history.csv's last row (rank 0, broadcast)
  if (rank == 0) {
    const std::string dir = paths_.dir() + "/"; // (as the notes print it)
    struct Text {
      const char  *name, *copy;
      std::string  stored, columns;
      bool         history;
      FILE       **stream;
    };
    Text texts[2] = {{"history.csv", "history", header.history, Header(), true, &history_},
                     {"static_states.csv", "static_states", header.static_states, StaticStatesHeader(), false, &static_states_}};
    for (int k = 0; k < 2 && !error[0]; ++k) {
      Text &t = texts[k];
      if (!t.history && t.stored.empty()) continue; // no static state yet: static_states.csv starts with the first one
      std::vector<std::string> lines;
      std::istringstream       in(t.stored);
      for (std::string line; std::getline(in, line);) lines.push_back(line);
      if (t.history && lines.size() > 1 && HistoryRowStep(lines.back()) == header.step && header.step % interval_ != 0) {
        // A row by load (-output_history_rows) stays: the step was the first at or past a
        // multiple of the period, i.e. past the first due time after the row before it
        // (every step in between was not due, or it would have written a row).
        const bool by_load = by_load_.period() > 0 && lines.size() > 2 &&
                             header.time >= by_load_.Next(HistoryRowTime(lines[lines.size() - 2]));
        if (!by_load) lines.pop_back();
      }
      if (t.history && lines.size() > 1) last_row = HistoryRowStep(lines.back());
      if (lines.empty()) lines.push_back(t.columns);
      if (lines.front() != t.columns) {
        std::vector<std::string> added, dropped;
        const std::vector<std::string> earlier = lines;
        lines = RemapColumns(earlier, t.columns, &added, &dropped);
        std::string note = Format("Note: %s has other columns than the checkpoint's: its %zu earlier row(s) are kept", t.name, earlier.size() - 1);
        if (!added.empty()) note += ", with nan in the new column(s) " + Joined(added);
        if (!dropped.empty()) {
          const std::string copy = paths_.rows_copy_name(t.copy, header.step);
          error[0] = WriteFileWhole(paths_.file(copy), [&](FILE *f) {
            for (const std::string &line : earlier) std::fprintf(f, "%s\n", line.c_str());
          });
          if (error[0]) {
            error[1] = 2 + k;
            break;
          }
          note += "; the column(s) " + Joined(dropped) + ", which this run does not write, are kept with those rows as they were in " + dir + copy;
        }
        notes += note + "\n";
      }
      if (*t.stream) std::fclose(*t.stream);
      *t.stream = nullptr;
      error[0] = WriteFileWhole(
        k == 0 ? paths_.history() : paths_.static_states(),
        [&](FILE *f) {
          for (const std::string &line : lines) std::fprintf(f, "%s\n", line.c_str());
        },
        t.stream);
      error[1] = k;
    }
  }
  PetscCallMPI(MPI_Bcast(error, 2, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&last_row, 1, MPIU_INT, 0, comm));
  last_step_ = last_row; // Run() writes the end-of-run row unless it is there
  static const char *const names[4] = {"history.csv", "static_states.csv", "history_to_step_N.csv", "static_states_to_step_N.csv"};
  PetscCheck(!error[0], comm, PETSC_ERR_FILE_WRITE,
             "Cannot write %s/%s: %s; the file is as it was before the restart: free some space or choose another -output_dir",
             paths_.dir().c_str(), names[error[1]], std::strerror(error[0]));
  if (!notes.empty()) PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s", notes.c_str()));
  PetscFunctionReturn(0);
}

} // namespace bapd
