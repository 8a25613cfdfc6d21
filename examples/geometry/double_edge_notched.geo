// A double-edge-notched tension sheet for bapd (examples/double_edge_notched.yaml):
// 20 mm x 40 mm, two U-notches 5 mm deep and 1 mm wide (semicircular tips of radius
// 0.5 mm) cut into the sides at mid-height, leaving a 10 mm ligament. Three surfaces:
// the grip tabs at each end (1.5 mm: 3 rows of the 0.5 mm lattice) and the specimen
// between them; the physical surfaces name them, so the scene grips the tabs by name.
// Units: metres.
w = 0.020; h = 0.040; a = 0.005; r = 0.0005; g = 0.0015;
lc = 0.001; lt = 0.0002;                 // mesh size, and at the notch tips
ym = h / 2; xt = a - r;                  // mid-height; x of the left tip's centre
Point(1) = {0, 0, 0, lc};
Point(2) = {w, 0, 0, lc};
Point(3) = {w, g, 0, lc};
Point(4) = {0, g, 0, lc};
Point(5) = {w, h - g, 0, lc};
Point(6) = {0, h - g, 0, lc};
Point(7) = {w, h, 0, lc};
Point(8) = {0, h, 0, lc};
// Right notch: mouth, flank, tip (two quarter arcs about 13), flank, mouth.
Point(10) = {w, ym - r, 0, lc};
Point(11) = {w - xt, ym - r, 0, lt};
Point(12) = {w - xt, ym + r, 0, lt};
Point(13) = {w - xt, ym, 0, lt};
Point(14) = {w, ym + r, 0, lc};
Point(15) = {w - a, ym, 0, lt};          // the tip (an arc must be less than half a circle)
// Left notch.
Point(20) = {0, ym + r, 0, lc};
Point(21) = {xt, ym + r, 0, lt};
Point(22) = {xt, ym - r, 0, lt};
Point(23) = {xt, ym, 0, lt};
Point(24) = {0, ym - r, 0, lc};
Point(25) = {a, ym, 0, lt};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 10};
Line(6) = {10, 11};
Circle(7) = {11, 13, 15};
Circle(19) = {15, 13, 12};
Line(8) = {12, 14};
Line(9) = {14, 5};
Line(10) = {5, 6};
Line(11) = {6, 20};
Line(12) = {20, 21};
Circle(13) = {21, 23, 25};
Circle(20) = {25, 23, 22};
Line(14) = {22, 24};
Line(15) = {24, 4};
Line(16) = {5, 7};
Line(17) = {7, 8};
Line(18) = {8, 6};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7, 19, 8, 9, 10, 11, 12, 13, 20, 14, 15};
Plane Surface(2) = {2};
Curve Loop(3) = {-10, 16, 17, 18};
Plane Surface(3) = {3};
Physical Surface("grip_bottom") = {1};
Physical Surface("specimen") = {2};
Physical Surface("grip_top") = {3};
Physical Curve("notch_left") = {12, 13, 20, 14};
Physical Curve("notch_right") = {6, 7, 19, 8};
