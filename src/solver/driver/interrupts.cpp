// Signals (checkpoint.hpp): SIGTERM / SIGINT / SIGUSR2 ask for a checkpoint and a
// stop, SIGUSR1 for a checkpoint and going on; SIGXFSZ is ignored. The handlers only record the signal;
// the driver asks once per step, collectively (Simulation::OutputAfterStep).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <time.h>

#include "bapd/solver/io/checkpoint.hpp"

namespace bapd {

namespace {

volatile std::sig_atomic_t interrupt_signal = 0, checkpoint_requests = 0;
volatile std::sig_atomic_t first_interrupt_second = 0; // CLOCK_MONOTONIC, whole seconds
struct sigaction           previous_term, previous_int, previous_usr1, previous_usr2, previous_xfsz;
int                        installed = 0;

// Seconds on the monotonic clock; clock_gettime is async-signal-safe (POSIX).
long MonotonicSecond()
{
  struct timespec now;
  return clock_gettime(CLOCK_MONOTONIC, &now) == 0 ? (long)now.tv_sec : 0;
}

extern "C" void OnInterrupt(int signal)
{
  if (!interrupt_signal) {
    interrupt_signal       = signal;
    first_interrupt_second = (std::sig_atomic_t)MonotonicSecond();
    return;
  }
  // One request often arrives twice within a moment: `timeout` passes its signal to
  // run_mpi.sh and to its process group (which holds run_mpi.sh as well), and run_mpi.sh
  // passes each on as SIGUSR2. Only a second signal 2 s or more after the first is a
  // user asking to stop now; it ends the process the default way.
  if (MonotonicSecond() - (long)first_interrupt_second < 2) return;
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

extern "C" void OnCheckpointRequest(int) { checkpoint_requests = checkpoint_requests + 1; }

} // namespace

void InstallInterruptHandlers()
{
  if (installed++) return;
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = OnInterrupt;
  action.sa_flags   = SA_RESTART;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, &previous_term);
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGUSR2, &action, &previous_usr2);
  action.sa_handler = OnCheckpointRequest;
  sigaction(SIGUSR1, &action, &previous_usr1);
  // A file-size limit (ulimit -f, a batch system's) then fails the write with EFBIG,
  // which bapd reports naming the file, instead of killing the process unexplained.
  action.sa_handler = SIG_IGN;
  sigaction(SIGXFSZ, &action, &previous_xfsz);
}

void RestoreInterruptHandlers()
{
  if (installed == 0 || --installed) return;
  sigaction(SIGTERM, &previous_term, nullptr);
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGUSR1, &previous_usr1, nullptr);
  sigaction(SIGUSR2, &previous_usr2, nullptr);
  sigaction(SIGXFSZ, &previous_xfsz, nullptr);
}

int PendingInterrupt() { return (int)interrupt_signal; }

std::string InterruptName(int signal)
{
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  if (signal != SIGUSR2) return "signal " + std::to_string(signal);
  // run_mpi.sh turns SIGINT / SIGTERM into SIGUSR2 (which mpiexec passes on at once)
  // and writes the signal it got to $BAPD_SIGNAL_FILE.
  const char *file = std::getenv("BAPD_SIGNAL_FILE");
  char        name[32] = "";
  if (FILE *f = file ? std::fopen(file, "r") : nullptr) {
    if (!std::fgets(name, sizeof name, f)) name[0] = '\0';
    std::fclose(f);
  }
  name[std::strcspn(name, " \n")] = '\0';
  return std::strncmp(name, "SIG", 3) == 0 ? std::string(name) : "SIGUSR2";
}

bool TakeCheckpointRequest()
{
  if (!checkpoint_requests) return false;
  checkpoint_requests = 0;
  return true;
}

} // namespace bapd
