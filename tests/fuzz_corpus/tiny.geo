// Tiny patch: a handful of triangles, every kind of physical group (surface, curve, point).
Point(1) = {0, 0, 0, 0.6};
Point(2) = {1, 0, 0, 0.6};
Point(3) = {1, 1, 0, 0.6};
Point(4) = {0, 1, 0, 0.6};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("plate", 1) = {1};
Physical Curve("bottom", 1) = {1};
Physical Curve("left", 2) = {4};
Physical Point("origin", 3) = {1};
