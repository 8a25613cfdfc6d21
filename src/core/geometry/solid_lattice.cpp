// The cell-centred lattice of a 3D body (shape3d.hpp): the grid around the added
// solids, its points layer by layer, and the checks of a lattice body.
#include "bapd/core/geometry/shape3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace bapd::nd {

namespace {

using P3 = std::array<double, 3>;

bool solid_adds(const Solid &s) { return s.op == Solid::Op::add; }

// A box around the solid (cylinders: their end points widened by the radius).
void solid_bounds(const Solid &s, P3 &lo, P3 &hi)
{
  for (int r = 0; r < 3; ++r) switch (s.kind) {
    case Solid::Kind::box: lo[r] = std::min(s.lo[r], s.hi[r]), hi[r] = std::max(s.lo[r], s.hi[r]); break;
    case Solid::Kind::cylinder:
      lo[r] = std::min(s.a[r], s.b[r]) - s.radius, hi[r] = std::max(s.a[r], s.b[r]) + s.radius;
      break;
    case Solid::Kind::sphere: lo[r] = s.a[r] - s.radius, hi[r] = s.a[r] + s.radius; break;
    case Solid::Kind::mesh:
      lo[r] = s.mesh->lo[r], hi[r] = s.mesh->lo[r] + static_cast<double>(s.mesh->count[r]) * s.mesh->cell;
      break;
    }
}

// The grid's cells around the added solids: cell (i, j, k) of the range has its centre at
// origin + (first + (i, j, k) + 0.5) dx.
struct Grid {
  std::array<int64_t, 3> first{}, count{};
  int64_t                cells() const { return count[0] * count[1] * count[2]; }
};

Grid body_grid(const Body<3> &body)
{
  P3   lo{}, hi{};
  bool any = false;
  for (const Solid &s : body.solids) {
    if (!solid_adds(s)) continue;
    P3 a{}, b{};
    solid_bounds(s, a, b);
    for (int r = 0; r < 3; ++r) lo[r] = any ? std::min(lo[r], a[r]) : a[r], hi[r] = any ? std::max(hi[r], b[r]) : b[r];
    any = true;
  }
  Grid g;
  for (int r = 0; r < 3; ++r) {
    // Centres within [lo, hi], one cell of margin for round-off (the solids decide).
    const double i0 = std::floor((lo[r] - body.origin[r]) / body.dx - 0.5) - 1;
    const double i1 = std::ceil((hi[r] - body.origin[r]) / body.dx - 0.5) + 1;
    if (!(i1 - i0 < 2e9)) throw std::invalid_argument("3D body: more than 2^31 cells along one axis; make dx larger");
    g.first[r] = static_cast<int64_t>(i0), g.count[r] = static_cast<int64_t>(i1 - i0) + 1;
  }
  return g;
}


// The centre of cell (i, j, k) of the grid's range: one expression for the points and
// for the pass that only counts them, so that both see the same bits.
P3 cell_centre(const Body<3> &body, const Grid &g, int64_t i, int64_t j, int64_t k)
{
  return {body.origin[0] + (static_cast<double>(g.first[0] + i) + 0.5) * body.dx,
          body.origin[1] + (static_cast<double>(g.first[1] + j) + 0.5) * body.dx,
          body.origin[2] + (static_cast<double>(g.first[2] + k) + 0.5) * body.dx};
}

std::string with_spacing(const char *fmt, double dx)
{
  char text[240];
  std::snprintf(text, sizeof text, fmt, dx);
  return text;
}

// The checks of a lattice body that need no point (shape3d.hpp, make_solid_points):
// the spacing, the origin, each solid and notch, a solid that adds, the grid's size.
Grid checked_grid(const Body<3> &body)
{
  if (!(body.dx > 0) || !std::isfinite(body.dx))
    throw std::invalid_argument(with_spacing("3D body: the lattice spacing dx must be > 0 (got %g)", body.dx));
  for (int r = 0; r < 3; ++r)
    if (!std::isfinite(body.origin[r])) throw std::invalid_argument("3D body: the lattice origin must be finite numbers");
  bool adds = false;
  for (std::size_t k = 0; k < body.solids.size(); ++k) {
    const std::string problem = solid_problem(body.solids[k]);
    if (!problem.empty())
      throw std::invalid_argument("3D body: solid " + std::to_string(k + 1) + " (" + to_string(body.solids[k].kind) +
                                  "): " + problem);
    adds = adds || solid_adds(body.solids[k]);
  }
  if (!adds)
    throw std::invalid_argument("3D body: no solid adds material (the body starts empty); list a box, cylinder or "
                                "sphere with op add first");
  for (std::size_t k = 0; k < body.notches.size(); ++k) {
    const std::string problem = planar_polygon_problem(body.notches[k]);
    if (!problem.empty()) throw std::invalid_argument("3D body: notch " + std::to_string(k + 1) + ": " + problem);
  }
  const Grid g = body_grid(body);
  if (static_cast<double>(g.count[0]) * static_cast<double>(g.count[1]) * static_cast<double>(g.count[2]) > 2147483647.0)
    throw std::invalid_argument(with_spacing("3D body: the lattice around the solids has more than 2^31 cells at dx = %g; "
                                             "make dx larger",
                                             body.dx));
  return g;
}

// The pieces met so far by the layer-by-layer pass (Hoshen-Kopelman labelling): a
// union-find over labels whose roots hold their piece's size and first point (the
// lowest natural id, where body_pieces's search in natural order starts the piece).
struct PieceLabels {
  std::vector<int64_t> parent, size, first;
  std::vector<P3>      at;

  int64_t add(int64_t id, const P3 &x, int64_t points)
  {
    parent.push_back(static_cast<int64_t>(parent.size()));
    size.push_back(points), first.push_back(id), at.push_back(x);
    return parent.back();
  }
  int64_t find(int64_t a)
  {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  // One piece of the two; its root the one with the lower first point.
  int64_t join(int64_t a, int64_t b)
  {
    a = find(a), b = find(b);
    if (a == b) return a;
    if (first[b] < first[a]) std::swap(a, b);
    parent[b] = a, size[a] += size[b];
    return a;
  }
};

// A piece no later layer can reach: counted, and kept when it is the smallest (of equal
// sizes the one with the lower first point, the one body_pieces meets first).
void close_piece(const PieceLabels &labels, int64_t root, SolidPieces *pieces, int64_t *smallest_first)
{
  const int64_t size = labels.size[root], first = labels.first[root];
  if (pieces->count++ == 0 || size < pieces->smallest_points || (size == pieces->smallest_points && first < *smallest_first))
    pieces->smallest_points = size, pieces->smallest_at = labels.at[root], *smallest_first = first;
}

// After a layer: the pieces that reach it are relabelled 0, 1, ... in `layer` (so that
// the labels held stay those of one layer); the others are closed.
void close_layer(std::vector<int64_t> &layer, PieceLabels &labels, std::vector<int64_t> &renumber, SolidPieces *pieces,
                 int64_t *smallest_first)
{
  PieceLabels open;
  renumber.assign(labels.parent.size(), -1);
  for (int64_t &label : layer) {
    if (label < 0) continue;
    const int64_t root = labels.find(label);
    if (renumber[root] < 0) renumber[root] = open.add(labels.first[root], labels.at[root], labels.size[root]);
    label = renumber[root];
  }
  for (std::size_t root = 0; root < labels.parent.size(); ++root)
    if (labels.parent[root] == static_cast<int64_t>(root) && renumber[root] < 0)
      close_piece(labels, static_cast<int64_t>(root), pieces, smallest_first);
  labels = std::move(open);
}

} // namespace

SolidPieces body_pieces(const Body<3> &body, const PointCloud &points)
{
  SolidPieces       pieces;
  const std::size_t n = points.size();
  if (n == 0) return pieces;
  // Integer cell coordinates of every point, and the points sorted by them (z, y, x),
  // so that a face neighbour is found by binary search: no dense cell array.
  std::vector<std::array<int64_t, 3>> cell(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r)
      cell[i][r] = std::llround((points.x[3 * i + r] - body.origin[r]) / body.dx - 0.5);
  auto key = [](const std::array<int64_t, 3> &c) { return std::array<int64_t, 3>{c[2], c[1], c[0]}; };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return key(cell[p]) < key(cell[q]); });
  auto find = [&](const std::array<int64_t, 3> &c) -> std::ptrdiff_t {
    const auto it = std::lower_bound(order.begin(), order.end(), key(c),
                                     [&](std::size_t p, const std::array<int64_t, 3> &k) { return key(cell[p]) < k; });
    return it != order.end() && cell[*it] == c ? static_cast<std::ptrdiff_t>(*it) : -1;
  };
  const BondCut            cut = polygon_notches(body.notches);
  std::vector<char>        reached(n, 0);
  std::vector<std::size_t> stack;
  pieces.smallest_points = static_cast<int64_t>(n) + 1;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (reached[seed]) continue;
    int64_t size  = 0;
    reached[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      ++size;
      for (int r = 0; r < 3; ++r)
        for (int step = -1; step <= 1; step += 2) {
          std::array<int64_t, 3> c = cell[i];
          c[r] += step;
          const std::ptrdiff_t j = find(c);
          if (j < 0 || reached[static_cast<std::size_t>(j)]) continue;
          if (cut && cut(&points.x[3 * i], &points.x[3 * static_cast<std::size_t>(j)])) continue;
          reached[static_cast<std::size_t>(j)] = 1;
          stack.push_back(static_cast<std::size_t>(j));
        }
    }
    ++pieces.count;
    if (size < pieces.smallest_points)
      pieces.smallest_points = size,
      pieces.smallest_at     = {points.x[3 * seed], points.x[3 * seed + 1], points.x[3 * seed + 2]};
  }
  return pieces;
}

int64_t solid_layers(const Body<3> &body)
{
  bool adds = false;
  for (const Solid &s : body.solids) adds = adds || solid_adds(s);
  return adds && body.dx > 0 ? body_grid(body).count[2] : 0;
}

void append_solid_layers(const Body<3> &body, int64_t layer_begin, int64_t layer_end, PointCloud *cloud,
                         std::vector<int64_t> *layer_counts)
{
  const Grid g = body_grid(body);
  layer_begin  = std::max<int64_t>(layer_begin, 0);
  layer_end    = std::min<int64_t>(layer_end, g.count[2]);
  PointCloud &c = *cloud;
  for (int64_t k = layer_begin; k < layer_end; ++k) {
    const std::size_t first = c.size();
    for (int64_t j = 0; j < g.count[1]; ++j)
      for (int64_t i = 0; i < g.count[0]; ++i) {
        const P3 p = cell_centre(body, g, i, j, k);
        if (!body_contains(body.solids, p.data())) continue;
        c.x.insert(c.x.end(), p.begin(), p.end());
        c.natural_id.push_back(static_cast<int64_t>(c.volume.size()));
        c.volume.push_back(body.dx * body.dx * body.dx);
      }
    if (layer_counts) layer_counts->push_back(static_cast<int64_t>(c.size() - first));
  }
}

SolidLattice solid_lattice(const Body<3> &body)
{
  const Grid           g   = checked_grid(body);
  const BondCut        cut = polygon_notches(body.notches);
  const int64_t        nx = g.count[0], ny = g.count[1];
  std::vector<int64_t> below(static_cast<std::size_t>(nx * ny), -1), layer(below.size(), -1), renumber;
  PieceLabels          labels;
  int64_t              smallest_first = 0;
  SolidLattice         s;
  s.lo.fill(std::numeric_limits<double>::max());
  s.hi.fill(-std::numeric_limits<double>::max());
  const double h = 0.5 * body.dx;
  for (int64_t k = 0; k < g.count[2]; ++k) {
    for (int64_t j = 0, c = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i, ++c) {
        layer[c]   = -1;
        const P3 p = cell_centre(body, g, i, j, k);
        if (!body_contains(body.solids, p.data())) continue;
        for (int r = 0; r < 3; ++r) s.lo[r] = std::min(s.lo[r], p[r] - h), s.hi[r] = std::max(s.hi[r], p[r] + h);
        // Its face links to the points met before it (x-, y-, z-: the others meet it
        // later), each unless a notch cuts it (body_pieces's links).
        int64_t label = -1;
        auto    link  = [&](int64_t other, int64_t oi, int64_t oj, int64_t ok) {
          if (other < 0 || (cut && cut(p.data(), cell_centre(body, g, oi, oj, ok).data()))) return;
          label = label < 0 ? labels.find(other) : labels.join(label, other);
        };
        if (i > 0) link(layer[c - 1], i - 1, j, k);
        if (j > 0) link(layer[c - nx], i, j - 1, k);
        link(below[c], i, j, k - 1);
        if (label < 0) label = labels.add(s.points, p, 0);
        ++labels.size[label];
        layer[c] = label;
        ++s.points;
      }
    close_layer(layer, labels, renumber, &s.pieces, &smallest_first);
    std::swap(layer, below);
  }
  for (std::size_t root = 0; root < labels.parent.size(); ++root)
    close_piece(labels, static_cast<int64_t>(root), &s.pieces, &smallest_first);
  return s;
}

SolidLattice checked_solid_lattice(const Body<3> &body)
{
  const SolidLattice s = solid_lattice(body);
  if (s.points == 0)
    throw std::invalid_argument(with_spacing("3D body: the solids keep no lattice point (no cell centre at dx = %g lies in "
                                             "the body); make dx smaller or the solids larger",
                                             body.dx));
  const SolidPieces &pieces = s.pieces;
  if (pieces.count > 1) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "3D body: the body falls apart into %lld pieces (the smallest, %lld points, holds the point (%g, %g, "
                  "%g)); join them, remove the stray piece, or end a notch inside the body",
                  static_cast<long long>(pieces.count), static_cast<long long>(pieces.smallest_points), pieces.smallest_at[0],
                  pieces.smallest_at[1], pieces.smallest_at[2]);
    throw std::invalid_argument(text);
  }
  return s;
}

PointCloud make_solid_points(const Body<3> &body)
{
  checked_solid_lattice(body);
  PointCloud c;
  append_solid_layers(body, 0, solid_layers(body), &c, nullptr);
  return c;
}

} // namespace bapd::nd
