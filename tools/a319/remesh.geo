// Remeshes the A319 skin from a first mesh of its CAD faces (tools/a319/mesh.sh runs this; Gmsh 4.8.4).
//
// The first mesh (A319.brep meshed as it is, in millimetres, with the line elements of its 375 CAD curves) is
// read as discrete entities. ClassifySurfaces rebuilds the topology from it: each surface stays one CAD face
// (their common curves carry line elements, so they stay boundaries), but the curves between two faces are
// rebuilt as the chains of line elements shared by the same pair of faces, so the CAD vertices and the short
// CAD edges along such a chain vanish (375 curves and 287 points become 191 and 110). CreateGeometry
// reparametrizes the discrete surfaces and curves, and the 2-D mesh is made anew on them: no curve is shorter
// than about 21 mm any more, against 7 mm in the CAD, which set the thin triangles of a direct mesh.
// The new nodes lie on the first mesh's facets: with a first mesh at 50 mm the skin's area is 0.008 % below
// the direct 100 mm mesh's.
//
//   gmsh remesh.geo -2 -nt 1 -format msh41 -setstring base FIRST.msh -setnumber size 100 -o OUT.msh
DefineConstant[
  base = {"a319_base.msh", Name "Parameters/First mesh (msh, millimetres)"},
  size = {100, Name "Parameters/Target element size (mm)"},
  angle = {40, Name "Parameters/Angle above which a mesh edge is a sharp feature (deg)"},
  curveAngle = {180, Name "Parameters/Angle above which a curve is split (deg)"},
  algorithm = {6, Name "Parameters/Gmsh 2-D algorithm (1 MeshAdapt, 5 Delaunay, 6 Frontal-Delaunay)"},
  scaling = {0.001, Name "Parameters/Factor applied to the saved mesh (0.001: millimetres to metres)"}
];

Merge StrCat(base);
// Triangles meeting at more than 'angle' are split too; the CAD curves already bound every such edge of
// this skin, so any angle from 40 to 150 degrees gives the same surfaces. Patches are made parametrizable.
ClassifySurfaces{angle * Pi / 180, 1, 1, curveAngle * Pi / 180};
CreateGeometry;

Mesh.MeshSizeMax = size;
Mesh.Algorithm = algorithm;
Mesh.ScalingFactor = scaling;
