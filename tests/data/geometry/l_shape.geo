// An L-shaped plate (tests/solver/scene/gmsh_shape_test.cpp): the same outline as the polygon
// 0,0 8,0 8,3 3,3 3,8 0,8 (mm), corners off the 0.5 mm lattice's cell centres.
s = 0.001;
Point(1) = {0.0001, 0.0001, 0};
Point(2) = {8 * s - 0.0001, 0.0001, 0};
Point(3) = {8 * s - 0.0001, 3 * s + 0.0001, 0};
Point(4) = {3 * s + 0.0001, 3 * s + 0.0001, 0};
Point(5) = {3 * s + 0.0001, 8 * s - 0.0001, 0};
Point(6) = {0.0001, 8 * s - 0.0001, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
