#pragma once
// What the scene tests share: options given as (name, value) pairs read into a Scene with
// SceneFromOptions, errors returned to the test instead of printing a stack and
// aborting, and the message of a rejection.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstdarg>
#include <cstdio>
#include <string>

#include "bapd/solver/input/scene.hpp"

namespace bapd::test {

// "-name value -flag ..." for PetscOptionsInsertString; Options: a container of
// (name, value) pairs ("" for a flag without a value).
template <class Options> std::string JoinOptions(const Options &options)
{
  std::string line;
  for (const auto &[name, value] : options) line += name + (value.empty() ? "" : " " + value) + " ";
  return line;
}

// The message of the error that started the last failure (PETSc keeps it).
inline std::string UserErrorText()
{
  const char *generic  = nullptr;
  char       *specific = nullptr;
  PetscErrorMessage(PETSC_ERR_USER, &generic, &specific);
  return specific ? specific : "";
}

// What -help prints while `read` runs: PetscHelpPrintf is pointed at a string for it.
// PETSc lists a block only the first time the process opens it, so a test that reads
// the help must come before any other reading in its file (gtest keeps file order).
inline std::string *&HelpSink()
{
  static std::string *sink = nullptr;
  return sink;
}
inline PetscErrorCode AppendHelp(MPI_Comm, const char format[], ...)
{
  char    buffer[4096];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  if (HelpSink()) *HelpSink() += buffer;
  return 0;
}
template <class Read> PetscErrorCode CaptureHelp(const Read &read, std::string *text)
{
  HelpSink()      = text;
  auto saved      = PetscHelpPrintf;
  PetscHelpPrintf = AppendHelp;
  const PetscErrorCode ierr = read();
  PetscHelpPrintf = saved;
  HelpSink()      = nullptr;
  return ierr;
}

template <class Options> class SceneReading : public ::testing::Test {
protected:
  void SetUp() override
  {
    ASSERT_EQ(PetscOptionsClear(nullptr), 0);
    ASSERT_EQ(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), 0);
  }
  void TearDown() override
  {
    PetscPopErrorHandler();
    PetscOptionsClear(nullptr);
  }

  PetscErrorCode Read(const Options &options, Scene *scene)
  {
    PetscOptionsClear(nullptr);
    if (PetscOptionsInsertString(nullptr, JoinOptions(options).c_str())) return PETSC_ERR_LIB;
    return SceneFromOptions(PETSC_COMM_WORLD, scene);
  }

  // Reads the options, expects a user error, returns its message.
  std::string Rejection(const Options &options)
  {
    Scene                scene;
    const PetscErrorCode ierr = Read(options, &scene);
    EXPECT_EQ(ierr, PETSC_ERR_USER) << "accepted: " << JoinOptions(options);
    return UserErrorText();
  }
};

} // namespace bapd::test
