// A 10 x 16 mm sheet in three surfaces: a 3 mm tab at each end (physical surfaces
// grip_bottom and grip_top, 6 lattice rows at dx = 0.5 mm: two horizons) and the 10 mm
// square between them. tests/solver/input/region_grips.sh grips the tabs by group with the
// affine grip field and compares with the 10 mm square gripped outside by its edges.
Point(1) = {0, 0, 0};
Point(2) = {0.01, 0, 0};
Point(3) = {0.01, 0.003, 0};
Point(4) = {0.01, 0.013, 0};
Point(5) = {0.01, 0.016, 0};
Point(6) = {0, 0.016, 0};
Point(7) = {0, 0.013, 0};
Point(8) = {0, 0.003, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 8};
Line(4) = {8, 1};
Line(5) = {3, 4};
Line(6) = {4, 7};
Line(7) = {7, 8};
Line(8) = {4, 5};
Line(9) = {5, 6};
Line(10) = {6, 7};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {-3, 5, 6, 7};
Curve Loop(3) = {-6, 8, 9, 10};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Plane Surface(3) = {3};
Physical Surface("grip_bottom") = {1};
Physical Surface("gauge") = {2};
Physical Surface("grip_top") = {3};
