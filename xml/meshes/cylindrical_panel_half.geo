// Half of the impulsively loaded cylindrical panel of Talamini & Radovitzky (2016) §6.1, Fig. 10
// (Balmer & Witmer / Morino, Leech & Witmer; docs/verification.md §1): R = 2.9375 in, L = 12.56 in, 120 degrees.
// Axis along x; the point at angle theta is (x, R sin(theta), R cos(theta)), so the crown is the +z line
// and the loaded patch's centre is (L/2, 0, R). The model is the half theta in [0, 60 deg]; y = 0 is the
// symmetry plane.
// Mesh: 6 circumferential x 16 axial cells (the paper's count), each cell split into two 6-node triangles,
// with element edges on the boundary of the loaded patch (60 deg x 10.205 in, centred):
//   theta: 3 cells in [0, 30] (patch) + 3 cells in [30, 60];
//   x:     2 cells in [0, 1.1775], 6 + 6 in the patch [1.1775, 11.3825] (split at the centre), 2 in [11.3825, L].
// Physical groups: surface "panel" (block) and "patch" (element set: the loaded region); curves "x_min",
// "x_max" (curved ends), "theta_max" (the straight edge at 60 deg), "symmetry" (y = 0); point "centre".
// Regenerate: gmsh cylindrical_panel_half.geo -2 -order 2 -format msh41 -o cylindrical_panel_half.msh
R = 2.9375; L = 12.56; a = 10.205;
xs[] = {0, (L - a) / 2, L / 2, (L + a) / 2, L};
nx[] = {2, 6, 6, 2};
ts[] = {0, Pi / 6, Pi / 3};
For i In {0:4}
  Point(100 + i) = {xs[i], 0, 0};
  For j In {0:2}
    Point(1 + 3 * i + j) = {xs[i], R * Sin(ts[j]), R * Cos(ts[j])};
  EndFor
EndFor
// arcs at station i between theta_j and theta_j+1: tag 200 + 2 i + j; axial lines at theta_j between
// x_i and x_i+1: tag 300 + 3 i + j
For i In {0:4}
  For j In {0:1}
    Circle(200 + 2 * i + j) = {1 + 3 * i + j, 100 + i, 1 + 3 * i + j + 1};
    Transfinite Curve{200 + 2 * i + j} = 4;
  EndFor
EndFor
For i In {0:3}
  For j In {0:2}
    Line(300 + 3 * i + j) = {1 + 3 * i + j, 1 + 3 * (i + 1) + j};
    Transfinite Curve{300 + 3 * i + j} = nx[i] + 1;
  EndFor
EndFor
// surfaces: loop x first, then theta, so that all normals point away from the axis
For i In {0:3}
  For j In {0:1}
    Curve Loop(400 + 2 * i + j) = {300 + 3 * i + j, 200 + 2 * (i + 1) + j, -(300 + 3 * i + j + 1), -(200 + 2 * i + j)};
    Surface(400 + 2 * i + j) = {400 + 2 * i + j};
    Transfinite Surface{400 + 2 * i + j} Alternate;
  EndFor
EndFor
Physical Surface("panel", 1) = {400:407};
Physical Surface("patch", 2) = {402, 404};
Physical Curve("x_min", 1) = {200, 201};
Physical Curve("x_max", 2) = {208, 209};
Physical Curve("theta_max", 3) = {302, 305, 308, 311};
Physical Curve("symmetry", 4) = {300, 303, 306, 309};
Physical Point("centre", 10) = {7};
