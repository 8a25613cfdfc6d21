// bapd: large deformation and fracture of soft materials by bond-associated
// non-ordinary state-based peridynamics (Chen, Yang, Liu; docs/method.md).
//
//   mpiexec -n 4 bapd -options_file_yaml examples/plate_hole.yaml [options]
//
// Every option is listed by -help; the scene file only sets defaults that later
// command-line options override.
#include <petscsys.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <utility>

#include <pthread.h>
#include <unistd.h>

#include "bapd/solver/driver/errors.hpp"
#include "bapd/solver/input/help.hpp"
#include "bapd/solver/input/scene_file.hpp"
#include "bapd/solver/driver/simulation.hpp"
#include "bapd/version.hpp"

static const char help[] = "bapd: bond-associated NOSB peridynamics for hydrogels (six laws; 2D plane stress or strain, 3D).\n"
                           "Usage: mpiexec -n N bapd -options_file_yaml SCENE.yaml [-option value ...]\n\n";

// operator new found no memory (a process limit, or a machine that overcommitted less
// than the set-up's check assumed): one line instead of std::bad_alloc's backtrace and
// SIGABRT, then the whole job stops. No allocation here: the message is fixed text.
[[noreturn]] static void OutOfMemory()
{
  static const char text[] = "bapd: error: out of memory: this rank could not allocate what the run needs (the machine's memory, or the "
                             "process limit of ulimit -v / a batch system): use a coarser -body_dx, more machines, or raise the limit\n";
  const ssize_t written = write(STDERR_FILENO, text, sizeof(text) - 1);
  (void)written;
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::_Exit(1);
}

// The MPI library's own description, first line (MPI_Get_library_version may be called
// before MPI_Init): "Open MPI v4.1.4, package: Debian OpenMPI, ...".
static std::string MpiLibrary()
{
  char library[MPI_MAX_LIBRARY_VERSION_STRING] = "";
  int  length                                  = 0;
  if (MPI_Get_library_version(library, &length) != MPI_SUCCESS) return "unknown";
  std::string text(library, (std::size_t)std::max(length, 0));
  text = text.substr(0, text.find('\n'));
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

// The PETSc library bapd runs with (its own numbers, not the headers').
static std::string PetscLibrary()
{
  PetscInt major = 0, minor = 0, subminor = 0, release = 0;
  if (PetscGetVersionNumber(&major, &minor, &subminor, &release)) return "unknown";
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(subminor) + (release ? "" : " (development)");
}

// -version (or --version): what this bapd is, for a bug report or a paper's methods
// section; printed once, before MPI starts, and the run stops with exit code 0.
static bool TakeVersionArgument(int argc, char **argv)
{
  for (int a = 1; a < argc; ++a)
    if (std::strcmp(argv[a], "-version") == 0 || std::strcmp(argv[a], "--version") == 0) return true;
  return false;
}

template <int D> static PetscErrorCode RunDriver(bapd::Scene scene)
{
  PetscFunctionBegin;
  bapd::SimulationD<D> simulation(PETSC_COMM_WORLD);
  PetscCall(simulation.Setup(std::move(scene)));
  PetscCall(simulation.Run());
  PetscFunctionReturn(0);
}

// The scene is read first; its dimension chooses the driver, once (a plane sheet, or
// a solid body: -body_dimension 3 or a 3D shape).
static PetscErrorCode RunScene()
{
  bapd::Scene scene;

  PetscFunctionBegin;
  PetscCall(bapd::ReadScene(PETSC_COMM_WORLD, &scene));
  if (!scene.help_only) {
    // The first line of a run's output: which bapd, on what (kept in any saved log).
    PetscMPIInt       ranks = 0;
    const std::string mpi   = MpiLibrary();
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &ranks));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "bapd %s, PETSc %s, %s, %d rank(s)\n", bapd::VersionText().c_str(), PetscLibrary().c_str(),
                          mpi.substr(0, mpi.find(',')).c_str(), ranks));
  }
  if (scene.body.dimension == 3) PetscCall(RunDriver<3>(std::move(scene)));
  else PetscCall(RunDriver<2>(std::move(scene)));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  if (TakeVersionArgument(argc, argv)) {
    const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank || std::atoi(rank) == 0)
      std::printf("bapd %s\nPETSc %s\nMPI: %s\n", bapd::VersionText().c_str(), PetscLibrary().c_str(), MpiLibrary().c_str());
    return 0;
  }
  // -help, -h, --help: bapd's options alone; -help all: PETSc's too (help.hpp).
  bapd::TakeHelpArguments(&argc, &argv);
  // A missing or malformed scene (or a stray word on the command line) is reported
  // before MPI and PETSc start, so the user sees one line instead of an error stack
  // from inside PetscInitialize.
  const std::string problem = bapd::CheckArguments(argc, argv);
  if (!problem.empty()) {
    const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank || std::atoi(rank) == 0) std::fprintf(stderr, "bapd: error: %s\n", problem.c_str());
    return 1;
  }
  // A stop signal before bapd's handlers are in place (a Ctrl-C in the first second,
  // which run_mpi.sh passes on as SIGUSR2, ended the process by its default action)
  // waits, blocked through MPI's and PETSc's start, and reaches the handlers once set.
  sigset_t stops;
  sigemptyset(&stops);
  for (int s : {SIGTERM, SIGINT, SIGQUIT, SIGHUP, SIGUSR1, SIGUSR2}) sigaddset(&stops, s);
  pthread_sigmask(SIG_BLOCK, &stops, nullptr);
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  PetscCall(bapd::PushUserErrorHandler());
  pthread_sigmask(SIG_UNBLOCK, &stops, nullptr);
  std::set_new_handler(OutOfMemory);
  PetscCall(bapd::BeginHelp(PETSC_COMM_WORLD));
  const PetscErrorCode ierr = RunScene();
  // Every rank agrees on the outcome before finalising; a rank that failed alone
  // (the others wait for it in a collective call) stops the job instead of hanging.
  const int exit_code = bapd::FinishRun(ierr);
  PetscCall(PetscFinalize());
  return exit_code;
}
