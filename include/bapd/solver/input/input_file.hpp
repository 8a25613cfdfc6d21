#pragma once
// An input file that a reader can take to its end: a regular file. A device such as
// /dev/zero, or a pipe that no one closes, would be read forever (or until memory runs
// out) by the YAML parser, the point-cloud reader and Gmsh alike, so they are refused
// before a byte is read. Plain C++ (the scene file is checked before MPI starts).
#include <string>
#include <sys/stat.h>

namespace bapd {

// "" for a regular file (or one that does not exist: the caller's open says so), else
// the sentence that refuses it; `option` names where the path came from, for a caller
// whose message does not say it already.
inline std::string NotARegularFile(const std::string &file, const char *option = nullptr)
{
  struct stat info;
  if (::stat(file.c_str(), &info) != 0 || S_ISREG(info.st_mode)) return "";
  const char *kind = S_ISDIR(info.st_mode) ? "a directory" : S_ISFIFO(info.st_mode) ? "a pipe" : S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode) ? "a device" : "not a regular file";
  return "'" + file + "'" + (option ? std::string(" (") + option + ")" : std::string()) + " is " + kind + ", which a reader could read forever: give the path of a file";
}

} // namespace bapd
