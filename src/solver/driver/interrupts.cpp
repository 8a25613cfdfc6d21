// Signals (checkpoint.hpp): SIGTERM / SIGINT / SIGQUIT / SIGHUP / SIGUSR2 ask for a
// checkpoint and a stop, SIGUSR1 for a checkpoint and going on; SIGXFSZ is ignored. The
// handlers only record the signal; the driver asks once per step, collectively
// (SimulationD::Report, simulation_report.cpp). A stop that the driver has not taken within
// kInterruptGraceSeconds (a signal during the set-up, or inside a long step) ends the
// process from SIGALRM's handler. SIGSEGV, SIGBUS, SIGILL, SIGFPE end it with one line
// naming the signal and the rank. Everything a handler does is async-signal-safe:
// write(2), alarm(2), nanosleep(2), _exit(2).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <mpi.h>
#include <string>
#include <time.h>
#include <unistd.h>

#include "bapd/solver/io/checkpoint.hpp"

namespace bapd {

namespace {

// Seconds a stop may wait for the end of the step (or of the set-up) before the
// process ends without a new checkpoint.
constexpr unsigned kInterruptGraceSeconds = 10;

volatile std::sig_atomic_t interrupt_signal = 0, checkpoint_requests = 0;
volatile std::sig_atomic_t first_interrupt_second = 0; // CLOCK_MONOTONIC, whole seconds
volatile std::sig_atomic_t stepping               = 0; // the driver asked once: the time stepping runs
volatile std::sig_atomic_t world_rank             = -1;
char                       signal_file[512]       = ""; // $BAPD_SIGNAL_FILE, read at installation
struct sigaction           previous_term, previous_int, previous_quit, previous_hup, previous_usr1, previous_usr2, previous_xfsz,
    previous_alrm;
int installed = 0;

// Seconds on the monotonic clock; clock_gettime is async-signal-safe (POSIX).
long MonotonicSecond()
{
  struct timespec now;
  return clock_gettime(CLOCK_MONOTONIC, &now) == 0 ? (long)now.tv_sec : 0;
}

// A line built in a fixed buffer, without allocating (a signal handler's message).
struct SafeLine {
  char        text[1024];
  std::size_t length = 0;
  SafeLine   &operator<<(const char *s)
  {
    while (s && *s && length + 1 < sizeof text) text[length++] = *s++;
    return *this;
  }
  SafeLine &operator<<(long n)
  {
    char digits[24];
    int  k = 0;
    if (n < 0) *this << "-", n = -n;
    do digits[k++] = (char)('0' + n % 10), n /= 10;
    while (n && k < 23);
    while (k && length + 1 < sizeof text) text[length++] = digits[--k];
    return *this;
  }
  void Write()
  {
    text[length++] = '\n';
    for (std::size_t done = 0; done < length;) {
      const ssize_t n = ::write(STDERR_FILENO, text + done, length - done);
      if (n <= 0) break;
      done += (std::size_t)n;
    }
  }
};

const char *SignalName(int signal)
{
  switch (signal) {
  case SIGTERM: return "SIGTERM";
  case SIGINT: return "SIGINT";
  case SIGQUIT: return "SIGQUIT";
  case SIGHUP: return "SIGHUP";
  case SIGUSR1: return "SIGUSR1";
  case SIGUSR2: return "SIGUSR2";
  case SIGSEGV: return "SIGSEGV";
  case SIGBUS: return "SIGBUS";
  case SIGILL: return "SIGILL";
  case SIGFPE: return "SIGFPE";
  default: return "a signal";
  }
}

// Ranks other than 0 speak after rank 0 has had time to: when every rank got the
// signal, rank 0's line is the only one (its exit makes mpiexec stop the others).
void LetRankZeroSpeakFirst()
{
  if (world_rank <= 0) return;
  struct timespec wait = {3, 0};
  nanosleep(&wait, nullptr);
}

extern "C" void OnInterrupt(int signal)
{
  if (!interrupt_signal) {
    interrupt_signal       = signal;
    first_interrupt_second = (std::sig_atomic_t)MonotonicSecond();
    alarm(kInterruptGraceSeconds); // PendingInterrupt() cancels it at the step's end
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

// The stop was not taken at a step's end within the grace time: the set-up, or a step,
// outlasted it. The run ends here; what was written before stays (history.csv's rows
// are whole, the last checkpoint was renamed into place whole).
extern "C" void OnInterruptGraceOver(int)
{
  if (!interrupt_signal) return;
  LetRankZeroSpeakFirst();
  // SIGUSR2 stands for the signal run_mpi.sh got, named in $BAPD_SIGNAL_FILE (open
  // and read are async-signal-safe).
  char name[16] = "";
  if (interrupt_signal == SIGUSR2 && signal_file[0]) {
    const int fd = ::open(signal_file, O_RDONLY);
    if (fd >= 0) {
      const ssize_t n = ::read(fd, name, sizeof name - 1);
      name[n > 0 ? n : 0] = '\0';
      ::close(fd);
    }
    for (char *c = name; *c; ++c)
      if (*c == '\n' || *c == ' ') *c = '\0';
  }
  SafeLine line;
  line << "bapd: error: interrupted by " << (std::strncmp(name, "SIG", 3) == 0 ? name : SignalName(interrupt_signal));
  line << " on rank " << (long)world_rank;
  if (stepping)
    line << " inside a step that had not ended " << (long)kInterruptGraceSeconds
         << " s later: the run stops without a new checkpoint; history.csv keeps its rows up to the last one written, and the "
            "last checkpoint written (<output_dir>/checkpoint.h5, with -checkpoint_interval) continues the run with -restart";
  else
    line << " during the set-up (before the first step), which had not ended " << (long)kInterruptGraceSeconds
         << " s later: the run stops before writing any result; run it again to start over";
  line.Write();
  _exit(1);
}

extern "C" void OnCheckpointRequest(int) { checkpoint_requests = checkpoint_requests + 1; }

// A crash (or such a signal sent by kill): one line naming it and the rank, then an
// exit without MPI_Finalize, which makes mpiexec stop the other ranks. Exit code 1,
// not 128 + the signal: the line is the report (run_mpi.sh adds its own for a rank
// that died by a signal without a word).
extern "C" void OnFatalSignal(int signal, siginfo_t *info, void *)
{
  const bool sent = info && info->si_code <= 0; // SI_USER, SI_QUEUE, SI_TKILL: kill(2), not a fault
  LetRankZeroSpeakFirst(); // (every signal is blocked meanwhile: mpiexec's SIGTERM waits)
  SafeLine line;
  line << "bapd: error: rank " << (long)world_rank << " stopped by " << SignalName(signal);
  if (sent)
    line << ", sent by process " << (long)info->si_pid << " (not a fault of bapd's)";
  else if (signal == SIGBUS)
    line << " (a bus error: a memory-mapped file cut short, or the memory of a full /dev/shm; a bug otherwise)";
  else
    line << " (a crash in bapd or a library it uses: please report it with the scene and the command line)";
  line << ": every rank stops; the output directory keeps what was written before (the last checkpoint continues the run "
          "with -restart <output_dir>/checkpoint.h5)";
  line.Write();
  _exit(1);
}

} // namespace

void InstallInterruptHandlers()
{
  if (installed++) return;
  int initialized = 0, finalized = 0, rank = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (initialized && !finalized) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  world_rank = rank;
  const char *file = std::getenv("BAPD_SIGNAL_FILE");
  std::snprintf(signal_file, sizeof signal_file, "%s", file && std::strlen(file) < sizeof signal_file ? file : "");
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = OnInterrupt;
  action.sa_flags   = SA_RESTART;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, &previous_term);
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGQUIT, &action, &previous_quit);
  sigaction(SIGHUP, &action, &previous_hup);
  sigaction(SIGUSR2, &action, &previous_usr2);
  action.sa_handler = OnInterruptGraceOver;
  sigaction(SIGALRM, &action, &previous_alrm);
  action.sa_handler = OnCheckpointRequest;
  sigaction(SIGUSR1, &action, &previous_usr1);
  // A file-size limit (ulimit -f, a batch system's) then fails the write with EFBIG,
  // which bapd reports naming the file, instead of killing the process unexplained.
  action.sa_handler = SIG_IGN;
  sigaction(SIGXFSZ, &action, &previous_xfsz);
  // A stop run_mpi.sh took before this process had started (mpiexec had no rank to
  // pass the SIGUSR2 on to): its name is in the file already. It acts as if just sent.
  if (signal_file[0] && InterruptName(SIGUSR2) != "SIGUSR2") OnInterrupt(SIGUSR2);
}

void RestoreInterruptHandlers()
{
  if (installed == 0 || --installed) return;
  alarm(0);
  sigaction(SIGTERM, &previous_term, nullptr);
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGQUIT, &previous_quit, nullptr);
  sigaction(SIGHUP, &previous_hup, nullptr);
  sigaction(SIGUSR1, &previous_usr1, nullptr);
  sigaction(SIGUSR2, &previous_usr2, nullptr);
  sigaction(SIGALRM, &previous_alrm, nullptr);
  sigaction(SIGXFSZ, &previous_xfsz, nullptr);
}

void InstallFatalSignalHandlers()
{
  int initialized = 0, finalized = 0, rank = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (initialized && !finalized) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  world_rank = rank;
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_sigaction = OnFatalSignal;
  action.sa_flags     = SA_SIGINFO | SA_RESETHAND;
  sigfillset(&action.sa_mask);
  for (int signal : {SIGSEGV, SIGBUS, SIGILL, SIGFPE}) sigaction(signal, &action, nullptr);
}

int PendingInterrupt()
{
  stepping = 1;
  // Asked at a step's end: the driver takes the stop now, within the grace time.
  if (interrupt_signal) alarm(0);
  return (int)interrupt_signal;
}

std::string InterruptName(int signal)
{
  if (signal != SIGUSR2) return signal == SIGTERM || signal == SIGINT || signal == SIGQUIT || signal == SIGHUP
                                    ? std::string(SignalName(signal))
                                    : "signal " + std::to_string(signal);
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

int CheckpointRequestsReceived() { return (int)checkpoint_requests; }

} // namespace bapd
