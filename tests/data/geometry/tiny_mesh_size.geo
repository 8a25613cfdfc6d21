// A strip 10 mm long and 0.1 mm wide far from any test body, with a mesh size of 1e-9 m:
// meshed as given it would take Gmsh hours (bad_input.sh: the mesh size is floored, and
// the strip is reported as holding no lattice point). A strip, not a square: the floor
// is a fraction of the diagonal, so that a square's floored mesh (1e5 triangles) took
// seconds where the strip's (a few thousand) takes none.
lc = 1e-9;
Point(1) = {1, 1, 0, lc}; Point(2) = {1.01, 1, 0, lc}; Point(3) = {1.01, 1.0001, 0, lc}; Point(4) = {1, 1.0001, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
