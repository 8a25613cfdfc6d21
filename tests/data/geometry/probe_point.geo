// A 10 mm square with a physical point, for a probe placed by name
// (tests/solver/input/probe_group.sh, -probe_NAME_group). The point is not embedded in the
// surface: Gmsh gives it a node of its own, and the surface's mesh is the square's.
Point(1) = {0, 0, 0};
Point(2) = {0.01, 0, 0};
Point(3) = {0.01, 0.01, 0};
Point(4) = {0, 0.01, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(5) = {0.0071, 0.0033, 0};
Physical Point("gauge") = {5};
Physical Curve("top_edge") = {3};
Physical Surface("square") = {1};
