#include "bapd/solver/driver/errors.hpp"

#include "bapd/solver/io/checkpoint.hpp"

#include <cctype>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>

namespace bapd {

namespace {

// What this process has reported, for FinishRun.
struct ErrorState {
  MPI_Comm    agree    = MPI_COMM_NULL; // a private duplicate of the world: FinishRun's
                                        // reduction never meets another collective
  bool        printed  = false;         // this process printed a message
  std::string deferred;                 // a message this process saw alone and kept
};

ErrorState &State()
{
  static ErrorState state;
  return state;
}

// The options database as "-name value" pairs: the name whose value is `value`
// ("" when none or several hold it). Used to name the option in PETSc's own parser
// messages, which quote only the value.
std::string OptionHolding(const std::string &value)
{
  char *all = nullptr;
  if (value.empty() || PetscOptionsGetAll(nullptr, &all) || !all) return "";
  std::string found, previous;
  int         matches = 0;
  const char *p       = all;
  while (*p) {
    while (*p == ' ') ++p;
    const char *start = p;
    while (*p && *p != ' ') ++p;
    const std::string token(start, p);
    if (token.empty()) break;
    const bool is_name = token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1]));
    if (!is_name && !previous.empty() && token == value) {
      found = previous;
      ++matches;
    }
    previous = is_name ? token : "";
  }
  PetscFree(all);
  return matches == 1 ? found : "";
}

// PETSc's messages for a value it cannot parse quote the value only; name the option.
std::string Explain(const char *message)
{
  std::string text = message ? message : "(no message)";
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  struct Pattern {
    const char *head, *tail, *fix;
  };
  static const Pattern patterns[] = {
    {"Input string ", " has no numeric value", "give a number"},
    {"Input string ", " has no integer value", "give a whole number"},
    {"Unknown logical value: ", "", "give true or false (or 1 or 0)"},
    {"Unknown TS type: ", "", "choose one that -help all lists (e.g. basicsymplectic, rk, euler)"},
  };
  for (const Pattern &pattern : patterns) {
    const std::size_t lh = std::strlen(pattern.head), lt = std::strlen(pattern.tail);
    if (text.compare(0, lh, pattern.head) != 0) continue;
    const std::size_t end = lt ? text.find(pattern.tail, lh) : text.size();
    if (end == std::string::npos) continue;
    const std::string value  = text.substr(lh, end - lh);
    const std::string option = OptionHolding(value);
    if (option.empty()) return text + ": " + pattern.fix + " (run with -help to list every option and its type)";
    return option + " '" + value + "' is not valid: " + pattern.fix + " (PETSc: " + text + ")";
  }
  return text;
}

void Print(const std::string &message)
{
  std::fprintf(stderr, "bapd: error: %s\n", message.c_str());
  std::fflush(stderr);
  State().printed = true;
}

PetscErrorCode UserErrorHandler(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n,
                                PetscErrorType p, const char *mess, void *ctx)
{
  if (!IsUserError(n)) return PetscTraceBackErrorHandler(comm, line, func, file, n, p, mess, ctx);
  if (p != PETSC_ERROR_INITIAL) return n; // only the first report carries the message
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  int rank = 0, size = 1, world_rank = 0, world_size = 1;
  if (initialized && !finalized) {
    if (comm != MPI_COMM_NULL) {
      MPI_Comm_rank(comm, &rank);
      MPI_Comm_size(comm, &size);
    }
    MPI_Comm_rank(PETSC_COMM_WORLD, &world_rank);
    MPI_Comm_size(PETSC_COMM_WORLD, &world_size);
  }
  const std::string message = Explain(mess);
  if (size == world_size) { // raised by every rank together: its first rank speaks
    if (rank == 0) Print(message);
  } else if (world_rank == 0) Print(message);
  else if (State().deferred.empty()) State().deferred = message;
  return n;
}

} // namespace

bool IsUserError(PetscErrorCode code)
{
  switch (code) {
  case PETSC_ERR_USER:
  case PETSC_ERR_USER_INPUT:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_INCOMP:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:
  case PETSC_ERR_ARG_BADPTR:
  case PETSC_ERR_FILE_OPEN:
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_WRITE:
  case PETSC_ERR_FILE_UNEXPECTED:
  case PETSC_ERR_NOT_CONVERGED:
  case PETSC_ERR_FP:
    return true;
  default:
    return false;
  }
}

PetscErrorCode PushUserErrorHandler()
{
  PetscFunctionBegin;
  if (State().agree == MPI_COMM_NULL) PetscCallMPI(MPI_Comm_dup(PETSC_COMM_WORLD, &State().agree));
  PetscCall(PetscPushErrorHandler(UserErrorHandler, nullptr));
  // In place of PETSc's signal handlers and their stack: a crash or a stop signal
  // from the start (a stop during the set-up ends the run within seconds).
  InstallFatalSignalHandlers();
  InstallInterruptHandlers();
  PetscFunctionReturn(0);
}

int FinishRun(PetscErrorCode status, double wait_seconds)
{
  ErrorState &state  = State();
  const int   failed = status != 0;
  if (state.agree == MPI_COMM_NULL) return failed;
  int rank = 0, size = 1;
  MPI_Comm_rank(state.agree, &rank);
  MPI_Comm_size(state.agree, &size);
  // [any rank failed, any rank printed, lowest rank holding a kept message (as size - rank)]
  int local[3] = {failed, state.printed ? 1 : 0, state.deferred.empty() ? 0 : size - rank}, global[3] = {0, 0, 0};
  MPI_Request request;
  MPI_Iallreduce(local, global, 3, MPI_INT, MPI_MAX, state.agree, &request);
  const double deadline = MPI_Wtime() + wait_seconds;
  int          done     = 0;
  while (!done) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    // A rank that did not fail waits as long as it takes: the failed ones decide.
    if (failed && MPI_Wtime() > deadline) {
      if (!state.deferred.empty()) {
        std::fprintf(stderr, "bapd: error: %s (on rank %d; stopping every rank)\n", state.deferred.c_str(), rank);
        std::fflush(stderr);
      }
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    usleep(1000);
  }
  if (global[0] && !global[1] && global[2] == size - rank && !state.deferred.empty()) Print(state.deferred);
  MPI_Comm_free(&state.agree);
  return global[0] ? 1 : 0;
}

} // namespace bapd
