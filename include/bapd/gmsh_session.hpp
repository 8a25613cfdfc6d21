#pragma once
// One Gmsh read, shared by the 2D shapes and groups (gmsh_shape.cpp) and the 3D volumes
// (gmsh_volume3d.cpp): the file checked, a Gmsh session initialised and finalised on
// every path, the file opened, and any Gmsh failure turned into one sentence.
// Include only from a .cpp that links Gmsh.
#include <gmsh.h>

#include <cstdio>
#include <string>

namespace bapd {

// gmsh::initialize / finalize around one read, on every path.
struct GmshSession {
  GmshSession()
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession &)            = delete;
  GmshSession &operator=(const GmshSession &) = delete;
};

// Opens `file` in a Gmsh session of its own and returns read() (what went wrong, or "")
// on the open model; a file that is missing or that Gmsh cannot read is reported.
template <class Read> std::string WithGmshFile(const std::string &file, Read read)
{
  if (std::FILE *f = std::fopen(file.c_str(), "rb")) std::fclose(f);
  else return "cannot open '" + file + "' (check the path; it is read relative to the directory bapd runs in)";
  GmshSession session; // finalised on every return below
  try {
    gmsh::open(file);
    return read();
  } catch (...) {
    std::string last;
    try {
      gmsh::logger::getLastError(last);
    } catch (...) {
    }
    return "Gmsh cannot read '" + file + "'" + (last.empty() ? std::string(" (not a .geo or .msh file?)") : ": " + last);
  }
}

} // namespace bapd
