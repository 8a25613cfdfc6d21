#include "bapd/solver/input/scene_file.hpp"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>
#include <yaml.h>

#include "bapd/solver/input/input_file.hpp"

namespace bapd {

namespace {

// A scene nests sections at most three deep (body: shapes: left: type); PETSc's reader
// stops at 25 prefixes with an error stack, so deeper nesting is refused here first.
constexpr int kMaxSceneDepth = 8;
// A scene is a few kilobytes: points and meshes come from their own files. The cap
// keeps a runaway file (a generated list, the wrong file) from being parsed for minutes.
constexpr long kMaxSceneBytes = 1L << 20;
// The values a scene may expand to through YAML aliases (*name), which repeat a node
// without copying it: nine aliases of nine aliases ... is a billion values.
constexpr std::size_t kMaxSceneValues = 100000;

// One pass over the parser's events, before the document is loaded: libyaml's cost grows
// with the square of the nesting depth ('[[[[...' of 1e5 brackets: minutes), so the depth
// is checked as the events come and the parse stops at the first level too deep.
std::string CheckNesting(FILE *fd)
{
  yaml_parser_t parser;
  yaml_parser_initialize(&parser);
  yaml_parser_set_input_file(&parser, fd);
  std::string err;
  int         depth = 0;
  for (bool done = false; !done && err.empty();) {
    yaml_event_t event;
    if (!yaml_parser_parse(&parser, &event)) break; // the loader reports syntax errors with their place
    switch (event.type) {
    case YAML_MAPPING_START_EVENT:
    case YAML_SEQUENCE_START_EVENT:
      if (++depth > kMaxSceneDepth)
        err = "sections are nested more than " + std::to_string(kMaxSceneDepth) + " levels deep at line " + std::to_string(event.start_mark.line + 1) +
              ": a scene nests sections (body: shapes: NAME: type: circle) and lists of numbers or names only";
      break;
    case YAML_MAPPING_END_EVENT:
    case YAML_SEQUENCE_END_EVENT: --depth; break;
    case YAML_STREAM_END_EVENT: done = true; break;
    default: break;
    }
    yaml_event_delete(&event);
  }
  yaml_parser_delete(&parser);
  return err;
}

std::string CheckNode(yaml_document_t *doc, yaml_node_t *node, const std::string &path, std::size_t &values)
{
  if (!node) return "";
  if (++values > kMaxSceneValues)
    return "it expands to more than " + std::to_string(kMaxSceneValues) + " values through its aliases (*name): write the values out";
  if (node->type == YAML_MAPPING_NODE) {
    // libyaml keeps both of two equal keys and PETSc would silently take the last.
    std::vector<std::pair<std::string, std::size_t>> seen; // key, line
    for (yaml_node_pair_t *pair = node->data.mapping.pairs.start; pair < node->data.mapping.pairs.top; ++pair) {
      yaml_node_t *key = yaml_document_get_node(doc, pair->key);
      yaml_node_t *val = yaml_document_get_node(doc, pair->value);
      if (!key || key->type != YAML_SCALAR_NODE) return "a mapping key under '" + path + "' is not a plain name";
      const std::string name = (const char *)key->data.scalar.value;
      const std::size_t line = key->start_mark.line + 1;
      for (const auto &[other, other_line] : seen)
        if (other == name)
          return "key '" + name + "' is given twice " + (path.empty() ? std::string("at the top level") : "under '" + path + "'") +
                 " (lines " + std::to_string(other_line) + " and " + std::to_string(line) + "): give each key once";
      seen.emplace_back(name, line);
      std::string       err  = CheckNode(doc, val, path.empty() ? name : path + "_" + name, values);
      if (!err.empty()) return err;
    }
  } else if (node->type == YAML_SEQUENCE_NODE) {
    for (yaml_node_item_t *item = node->data.sequence.items.start; item < node->data.sequence.items.top; ++item) {
      yaml_node_t *it = yaml_document_get_node(doc, *item);
      if (!it || it->type != YAML_SCALAR_NODE)
        return "the list '" + path + "' may only hold numbers or names (line " + std::to_string(node->start_mark.line + 1) + ")";
    }
  }
  return "";
}

// PETSc's rule for an option name (PetscOptionsValidKey): one or two dashes, then a
// letter, and not a number such as -inf.
bool IsOptionName(const char *arg)
{
  if (arg[0] != '-') return false;
  const char *key = arg[1] == '-' ? arg + 1 : arg;
  if (!std::isalpha(static_cast<unsigned char>(key[1]))) return false;
  char *end = nullptr;
  (void)std::strtod(key, &end);
  return end == key || *end == '_' || std::isalnum(static_cast<unsigned char>(*end));
}

} // namespace

std::string CheckArguments(int argc, char **argv)
{
  // PETSc takes "-name [value]" pairs and silently skips any other word: a second
  // word after a value (a scene file without -options_file_yaml, a value with a
  // space in it) would be ignored, and the run would go on without it.
  bool after_name = false;
  for (int a = 1; a < argc; ++a) {
    if (IsOptionName(argv[a])) after_name = true;
    else if (after_name) after_name = false;
    else
      return std::string("unexpected argument '") + argv[a] + "'" + (a > 1 ? std::string(" after '") + argv[a - 1] + "'" : "") +
             ": options are -name value pairs (one value each; lists are comma-separated without spaces, e.g. -body_holes "
             "0.04,0.08,0.01) and a scene file is given as -options_file_yaml FILE";
  }
  return CheckSceneFileArgument(argc, argv);
}

std::string CheckSceneFileArgument(int argc, char **argv)
{
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "-options_file") == 0) {
      // A plain PETSc options file: PETSc reads it; only its absence is checked here.
      if (a + 1 >= argc) return "-options_file needs a file name";
      if (std::string why = NotARegularFile(argv[a + 1], "-options_file"); !why.empty()) return why;
      FILE *fd = std::fopen(argv[a + 1], "rb");
      if (!fd) return std::string("cannot open options file '") + argv[a + 1] + "': " + std::strerror(errno) + " (check the path given to -options_file)";
      std::fclose(fd);
      continue;
    }
    if (std::strcmp(argv[a], "-options_file_yaml") != 0) continue;
    if (a + 1 >= argc) return "-options_file_yaml needs a file name";
    const char *file = argv[a + 1];
    if (std::string why = NotARegularFile(file, "-options_file_yaml"); !why.empty()) return why;
    FILE       *fd   = std::fopen(file, "rb");
    if (!fd) return std::string("cannot open scene file '") + file + "': " + std::strerror(errno) + " (check the path given to -options_file_yaml)";
    std::string err;
    if (std::fseek(fd, 0, SEEK_END) == 0 && std::ftell(fd) > kMaxSceneBytes) {
      err = std::string("scene file '") + file + "' holds " + std::to_string(std::ftell(fd)) + " bytes, more than a scene's " + std::to_string(kMaxSceneBytes) +
            ": is it the right file? (point clouds and meshes are files of their own: -body_cloud, -body_S_file)";
      std::fclose(fd);
      return err;
    }
    std::rewind(fd);
    if (err = CheckNesting(fd); !err.empty()) {
      std::fclose(fd);
      return std::string("scene file '") + file + "': " + err;
    }
    std::rewind(fd);
    yaml_parser_t   parser;
    yaml_document_t doc;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_file(&parser, fd);
    if (!yaml_parser_load(&parser, &doc)) {
      err = std::string("scene file '") + file + "' is not valid YAML: " + (parser.problem ? parser.problem : "syntax error") +
            " at line " + std::to_string(parser.problem_mark.line + 1) + ", column " + std::to_string(parser.problem_mark.column + 1);
    } else {
      yaml_node_t *root = yaml_document_get_root_node(&doc);
      if (root && root->type != YAML_MAPPING_NODE) err = std::string("scene file '") + file + "' must be a mapping of option names to values";
      else {
        std::size_t values = 0;
        err                = CheckNode(&doc, root, "", values);
      }
      if (!err.empty() && err.rfind("scene file", 0) != 0) err = std::string("scene file '") + file + "': " + err;
      yaml_document_delete(&doc);
    }
    yaml_parser_delete(&parser);
    std::fclose(fd);
    if (!err.empty()) return err;
  }
  return "";
}

} // namespace bapd
