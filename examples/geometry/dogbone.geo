// A dogbone (tensile bar with fillets) for bapd: 20 mm x 60 mm overall, a 10 mm wide
// gauge 24 mm long, grip ends 20 mm wide, quarter-circle fillets of 5 mm radius. Units: metres.
// Used by examples/dogbone.yaml as -body_outline_type mesh: bapd keeps the lattice
// points inside the meshed surface.
w = 0.020; h = 0.060; g = 0.010; L = 0.024; r = (w - g) / 2; // fillet radius = the shoulder step
xl = (w - g) / 2; xr = w - xl;           // gauge edges
y0 = (h - L) / 2; y1 = y0 + L;           // gauge ends
Point(1) = {0, 0, 0};
Point(2) = {w, 0, 0};
Point(3) = {w, y0 - r, 0};
Point(4) = {xr, y0, 0};
Point(5) = {xr, y1, 0};
Point(6) = {w, y1 + r, 0};
Point(7) = {w, h, 0};
Point(8) = {0, h, 0};
Point(9) = {0, y1 + r, 0};
Point(10) = {xl, y1, 0};
Point(11) = {xl, y0, 0};
Point(12) = {0, y0 - r, 0};
// Fillet centres: quarter circles from the grip ends, tangent to the gauge edges.
Point(13) = {xr + r, y0, 0};
Point(14) = {xr + r, y1, 0};
Point(15) = {xl - r, y1, 0};
Point(16) = {xl - r, y0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Circle(3) = {3, 13, 4};
Line(4) = {4, 5};
Circle(5) = {5, 14, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 9};
Circle(9) = {9, 15, 10};
Line(10) = {10, 11};
Circle(11) = {11, 16, 12};
Line(12) = {12, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
Plane Surface(1) = {1};
Mesh.CharacteristicLengthMax = 0.001;
// The ends the grips hold (examples/dogbone.yaml: -load_S_region group, the points
// within the grip's depth of these lines), and the specimen.
Physical Curve("bottom_end") = {1};
Physical Curve("top_end") = {7};
Physical Surface("dogbone") = {1};
