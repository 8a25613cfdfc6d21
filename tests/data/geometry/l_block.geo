// An L-shaped block (tests/solver/geometry3d/gmsh_volume_3d_test.cpp): the polygon 0,0 8,0 8,3
// 3,3 3,8 0,8 (mm) extruded 4 mm along z, meshed with tetrahedra. Its faces lie on the
// 1 mm lattice's cell faces, never on a cell centre.
s = 0.001;
Mesh.MeshSizeMax = 1.5 * s;
Point(1) = {0, 0, 0};
Point(2) = {8 * s, 0, 0};
Point(3) = {8 * s, 3 * s, 0};
Point(4) = {3 * s, 3 * s, 0};
Point(5) = {3 * s, 8 * s, 0};
Point(6) = {0, 8 * s, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Extrude {0, 0, 4 * s} { Surface{1}; }
