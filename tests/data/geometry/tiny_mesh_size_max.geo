// A strip 10 mm long and 0.1 mm wide far from any test body whose point sizes are sound
// but whose Mesh.MeshSizeMax is 1e-7 m: Gmsh applies the maximum after the minimum, so
// without more it meshed for ever (bad_input.sh: the maximum is raised to the floor as
// well). A strip, not a square, as in tiny_mesh_size.geo: its floored mesh is small.
Mesh.MeshSizeMax = 1e-7;
lc = 1e-3;
Point(1) = {1, 1, 0, lc}; Point(2) = {1.01, 1, 0, lc}; Point(3) = {1.01, 1.0001, 0, lc}; Point(4) = {1, 1.0001, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
