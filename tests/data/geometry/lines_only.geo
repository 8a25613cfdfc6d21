// A closed curve without a surface: nothing to mesh in 2D (bad input).
Point(1) = {0, 0, 0};
Point(2) = {0.005, 0, 0};
Point(3) = {0.005, 0.005, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
