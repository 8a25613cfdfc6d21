// A 6 x 4 x 3 mm box with its faces, its volume and a corner named (tests/solver/geometry3d/
// gmsh_groups_3d_test.cpp): the rectangle [0, 6] x [0, 4] mm extruded 3 mm along z,
// meshed with tetrahedra. Its faces lie on the 1 mm lattice's cell faces.
s = 0.001;
Mesh.MeshSizeMax = 1.5 * s;
Point(1) = {0, 0, 0};
Point(2) = {6 * s, 0, 0};
Point(3) = {6 * s, 4 * s, 0};
Point(4) = {0, 4 * s, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// out[0]: the face z = 3 mm, out[1]: the volume, out[2] to out[5]: the sides swept by
// lines 1 to 4 (y = 0, x = 6, y = 4, x = 0 mm).
out[] = Extrude {0, 0, 3 * s} { Surface{1}; };
Physical Surface("back") = {1};
Physical Surface("front") = {out[0]};
Physical Surface("bottom") = {out[2]};
Physical Surface("right") = {out[3]};
Physical Surface("top") = {out[4]};
Physical Surface("left") = {out[5]};
Physical Volume("body") = {out[1]};
Physical Curve("edge") = {4};
Physical Point("corner") = {3};
