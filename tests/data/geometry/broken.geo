Point(1) = {0, 0, 0;
this is not gmsh
