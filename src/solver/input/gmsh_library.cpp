// Gmsh's library, loaded on the first Gmsh read instead of at every start.
//
// libgmsh brings OpenCASCADE and some seventy other libraries that PETSc does not
// need; the dynamic loader spent about 0.25 s of CPU on them at every start of bapd
// (and of every rank), more than twice the rest of a start, whether or not the scene
// names a .geo or .msh file. bapd is therefore not linked to libgmsh: the functions
// of Gmsh bapd calls (gmsh_session.hpp and the readers that use it) are defined here,
// each forwarding to the library's own, which is opened (dlopen) on the first call.
//
// Each definition keeps gmsh.h's signature (another one would leave the call sites
// unresolved at link time); the name looked up is that signature's mangled name in
// Gmsh 4.8's C++ API with GCC's ABI. A library that cannot be opened, or that lacks
// a function, does not stop a run that reads no Gmsh file: the first read fails in
// gmsh::open, inside WithGmshFile's try, and gmsh::logger::getLastError gives the
// reason, so the user sees the one "Gmsh cannot read" line with the cause and fix.
#include <gmsh.h>

#include <dlfcn.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#ifndef BAPD_GMSH_LIBRARY
#error "BAPD_GMSH_LIBRARY (the file name dlopen takes, e.g. libgmsh.so.4.8) is set by CMakeLists.txt"
#endif

namespace {

struct GmshLibrary {
  void       *handle = nullptr;
  std::string problem; // why a function cannot be called ("" while all is well)
};

// Opened once, kept open to the end of the process (Gmsh keeps state between sessions).
GmshLibrary &Library()
{
  static GmshLibrary library = [] {
    GmshLibrary opened;
    opened.handle = dlopen(BAPD_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!opened.handle) {
      const char *why = dlerror();
      opened.problem  = std::string("Gmsh's library ") + BAPD_GMSH_LIBRARY + " cannot be loaded (" + (why ? why : "no reason given") +
                       "): install Gmsh 4.8's library (scripts/install-deps.sh) or rebuild bapd against the Gmsh installed";
    }
    return opened;
  }();
  return library;
}

// The library's function `mangled` as a F*, or nullptr (Library().problem says why).
template <class F> F *Find(const char *mangled, const char *name)
{
  GmshLibrary &library = Library();
  if (!library.handle) return nullptr;
  void *symbol = dlsym(library.handle, mangled);
  if (!symbol && library.problem.empty())
    library.problem = std::string("Gmsh's library ") + BAPD_GMSH_LIBRARY + " has no " + name +
                      " with the signature bapd calls (Gmsh 4.8's C++ API, named in src/solver/input/gmsh_library.cpp): "
                      "install Gmsh 4.8 (scripts/install-deps.sh), or update those names for the Gmsh installed";
  return reinterpret_cast<F *>(symbol);
}

// As Find, for the calls a read cannot go on without: a missing one throws (WithGmshFile
// catches it and reports getLastError's text).
template <class F> F *Require(const char *mangled, const char *name)
{
  F *function = Find<F>(mangled, name);
  // (also when an earlier function was missing: the session around this call is not whole)
  if (!function || !Library().problem.empty()) throw std::runtime_error(Library().problem);
  return function;
}

} // namespace

// The session's set-up and tear-down (GmshSession) do nothing without the library:
// the open that follows them reports it.
void gmsh::initialize(int argc, char **argv, const bool readConfigFiles)
{
  static auto *f = Find<void(int, char **, bool)>("_ZN4gmsh10initializeEiPPcb", "gmsh::initialize");
  if (f) f(argc, argv, readConfigFiles);
}

void gmsh::finalize()
{
  static auto *f = Find<void()>("_ZN4gmsh8finalizeEv", "gmsh::finalize");
  if (f) f();
}

void gmsh::option::setNumber(const std::string &name, const double value)
{
  static auto *f = Find<void(const std::string &, double)>(
    "_ZN4gmsh6option9setNumberERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEd", "gmsh::option::setNumber");
  if (f) f(name, value);
}

void gmsh::open(const std::string &fileName)
{
  static auto *f = Require<void(const std::string &)>("_ZN4gmsh4openERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEE", "gmsh::open");
  f(fileName);
}

void gmsh::logger::getLastError(std::string &error)
{
  if (!Library().problem.empty()) {
    error = Library().problem;
    return;
  }
  static auto *f = Require<void(std::string &)>("_ZN4gmsh6logger12getLastErrorERNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEE",
                                                "gmsh::logger::getLastError");
  f(error);
}

void gmsh::option::getNumber(const std::string &name, double &value)
{
  static auto *f = Require<void(const std::string &, double &)>(
    "_ZN4gmsh6option9getNumberERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERd", "gmsh::option::getNumber");
  f(name, value);
}

void gmsh::model::getEntities(gmsh::vectorpair &dimTags, const int dim)
{
  static auto *f = Require<void(gmsh::vectorpair &, int)>("_ZN4gmsh5model11getEntitiesERSt6vectorISt4pairIiiESaIS3_EEi",
                                                          "gmsh::model::getEntities");
  f(dimTags, dim);
}

void gmsh::model::getBoundingBox(const int dim, const int tag, double &xmin, double &ymin, double &zmin, double &xmax, double &ymax,
                                 double &zmax)
{
  static auto *f = Require<void(int, int, double &, double &, double &, double &, double &, double &)>(
    "_ZN4gmsh5model14getBoundingBoxEiiRdS1_S1_S1_S1_S1_", "gmsh::model::getBoundingBox");
  f(dim, tag, xmin, ymin, zmin, xmax, ymax, zmax);
}

void gmsh::model::getPhysicalName(const int dim, const int tag, std::string &name)
{
  static auto *f = Require<void(int, int, std::string &)>(
    "_ZN4gmsh5model15getPhysicalNameEiiRNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEE", "gmsh::model::getPhysicalName");
  f(dim, tag, name);
}

void gmsh::model::getPhysicalGroups(gmsh::vectorpair &dimTags, const int dim)
{
  static auto *f = Require<void(gmsh::vectorpair &, int)>("_ZN4gmsh5model17getPhysicalGroupsERSt6vectorISt4pairIiiESaIS3_EEi",
                                                          "gmsh::model::getPhysicalGroups");
  f(dimTags, dim);
}

void gmsh::model::getEntitiesForPhysicalGroup(const int dim, const int tag, std::vector<int> &tags)
{
  static auto *f = Require<void(int, int, std::vector<int> &)>("_ZN4gmsh5model27getEntitiesForPhysicalGroupEiiRSt6vectorIiSaIiEE",
                                                               "gmsh::model::getEntitiesForPhysicalGroup");
  f(dim, tag, tags);
}

void gmsh::model::mesh::generate(const int dim)
{
  static auto *f = Require<void(int)>("_ZN4gmsh5model4mesh8generateEi", "gmsh::model::mesh::generate");
  f(dim);
}

void gmsh::model::mesh::getElements(std::vector<int> &elementTypes, std::vector<std::vector<std::size_t>> &elementTags,
                                    std::vector<std::vector<std::size_t>> &nodeTags, const int dim, const int tag)
{
  using Tags     = std::vector<std::vector<std::size_t>>;
  static auto *f = Require<void(std::vector<int> &, Tags &, Tags &, int, int)>(
    "_ZN4gmsh5model4mesh11getElementsERSt6vectorIiSaIiEERS2_IS2_ImSaImEESaIS7_EESA_ii", "gmsh::model::mesh::getElements");
  f(elementTypes, elementTags, nodeTags, dim, tag);
}

void gmsh::model::mesh::getElementProperties(const int elementType, std::string &elementName, int &dim, int &order, int &numNodes,
                                             std::vector<double> &localNodeCoord, int &numPrimaryNodes)
{
  static auto *f = Require<void(int, std::string &, int &, int &, int &, std::vector<double> &, int &)>(
    "_ZN4gmsh5model4mesh20getElementPropertiesEiRNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERiS9_S9_RSt6vectorIdSaIdEES9_",
    "gmsh::model::mesh::getElementProperties");
  f(elementType, elementName, dim, order, numNodes, localNodeCoord, numPrimaryNodes);
}

void gmsh::model::mesh::getNodes(std::vector<std::size_t> &nodeTags, std::vector<double> &coord, std::vector<double> &parametricCoord,
                                 const int dim, const int tag, const bool includeBoundary, const bool returnParametricCoord)
{
  static auto *f = Require<void(std::vector<std::size_t> &, std::vector<double> &, std::vector<double> &, int, int, bool, bool)>(
    "_ZN4gmsh5model4mesh8getNodesERSt6vectorImSaImEERS2_IdSaIdEES8_iibb", "gmsh::model::mesh::getNodes");
  f(nodeTags, coord, parametricCoord, dim, tag, includeBoundary, returnParametricCoord);
}
