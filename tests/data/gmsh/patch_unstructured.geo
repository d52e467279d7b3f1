// Unstructured flat patch for test_static_verification_patch (membrane and bending patch tests on a genuinely
// unstructured mesh): the rectangle [0, 2] x [0, 1] in z = 0, meshed by Gmsh's Delaunay algorithm with a
// mesh size that varies from corner to corner (0.22 .. 0.45), so that no two elements are congruent and
// vertex valences vary. P1 triangles; the test promotes them to P2 (straight edges).
// Regenerate with:  gmsh -2 -algo del2d -format msh22 patch_unstructured.geo -o patch_unstructured.msh
Point(1) = {0, 0, 0, 0.22};
Point(2) = {2, 0, 0, 0.45};
Point(3) = {2, 1, 0, 0.30};
Point(4) = {0, 1, 0, 0.40};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};  // counter-clockwise seen from +z: element normals +z
Plane Surface(1) = {1};
Physical Surface("patch", 1) = {1};
Physical Curve("y_min", 1) = {1};
Physical Curve("x_max", 2) = {2};
Physical Curve("y_max", 3) = {3};
Physical Curve("x_min", 4) = {4};
