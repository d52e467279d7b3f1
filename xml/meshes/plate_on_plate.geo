// A striker plate on a target plate (xml/plate_on_plate.xml; docs/theory.md §12.5): the target, 100 x 100 mm in
// z = 0, 24 x 24 cells with alternating diagonals; the striker, 40 x 40 mm, turned 20 degrees about z and centred
// over the target at z = 3.2 mm (its mid-surface; 0.2 mm between the faces of the 2 mm target and the 4 mm
// striker), meshed with unstructured triangles of about 5 mm, so that its nodes do not line up with the target's.
// Physical groups: surfaces "target" and "striker" (blocks); curve "clamped" (the target's four edges).
// Regenerate: gmsh plate_on_plate.geo -2 -format msh41 -o plate_on_plate.msh
L = 0.1; n = 24; a = 0.04; zs = 3.2e-3; turn = 20 * Pi / 180;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Transfinite Curve{1:4} = n + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1} Alternate;
c = Cos(turn); s = Sin(turn);
For k In {0:3}
  u = (k == 1 || k == 2) ? a / 2 : -a / 2;
  v = (k >= 2) ? a / 2 : -a / 2;
  Point(11 + k) = {L / 2 + c * u - s * v, L / 2 + s * u + c * v, zs, a / 8};
EndFor
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};
Physical Surface("target", 1) = {1};
Physical Surface("striker", 2) = {2};
Physical Curve("clamped", 1) = {1, 2, 3, 4};
