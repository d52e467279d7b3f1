// Cylindrical panel for test_gmsh_reader: the surface x^2 + y^2 = R^2, 0 <= polar angle <= theta,
// 0 <= z <= L. Exact area R*theta*L = 1.5 * (Pi/3) * 2 = Pi.
// Meshed at test time with: gmsh -2 -order 2 -nt 1 -format msh22|msh41 [-bin] cylinder_panel.geo -o out.msh
R = 1.5;
theta = Pi / 3;
L = 2.0;
h = 0.35;  // target edge length

Point(1) = {0, 0, 0, h};  // centre of the z = 0 arc (not part of the mesh)
Point(6) = {0, 0, L, h};  // centre of the z = L arc
Point(2) = {R, 0, 0, h};
Point(3) = {R * Cos(theta), R * Sin(theta), 0, h};
Point(4) = {R, 0, L, h};
Point(5) = {R * Cos(theta), R * Sin(theta), L, h};
Circle(1) = {2, 1, 3};  // z = 0 arc
Circle(2) = {4, 6, 5};  // z = L arc
Line(3) = {2, 4};       // straight generator at angle 0
Line(4) = {3, 5};       // straight generator at angle theta
Curve Loop(1) = {1, 4, -2, -3};
Surface(1) = {1};  // transfinite (Coons) patch: exactly the cylinder for these boundaries

Physical Surface("skin", 10) = {1};
Physical Curve("bottom", 1) = {1};
Physical Curve("top", 2) = {2};
Physical Curve("side_a", 3) = {3};
Physical Curve("side_b", 4) = {4};
Physical Point("corner", 1) = {2};
