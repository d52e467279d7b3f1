// Mode III tearing of a notched 6061-T6 plate: Talamini & Radovitzky (2016) §6.2, Fig. 12, Table 2
// (experiments of Li et al., Int. J. Fract. 168 (2011); docs/verification.md §3). Units: m.
// Interpretation of Fig. 12 (the figure gives only 28.6 mm, 63.5 mm, 76.2 mm and "1 mm"; the text gives the
// ligament b = 33.1 mm):
//   * plate width 76.2 mm along x, the crack direction;
//   * the notch is a 1 mm wide slit centred on y = 0 from the free edge x = 0 to x = a = 76.2 - 33.1 = 43.1 mm;
//     its last 1 mm is a taper that closes it to a sharp tip at (a, 0) (a square end would put 0.5 mm edges there
//     and halve the stable time step); the ligament is the line y = 0, x in [43.1, 76.2] mm (33.1 mm);
//   * the meshed band is 28.6 mm high (y in [-14.3, 14.3] mm); the 63.5 mm is the total height of the specimen
//     including the clamped strips, which are not meshed (paper: "the parts of the plate fixed within the clamps
//     ... is not meshed");
//   * "the halves of the plate above and below the notch are clamped" (paper §6.2): the clamps act on the lines
//     y = +-14.3 mm over the notch, x in [0, a] (curves clamp_top, clamp_bottom); the band edges ahead of the notch
//     tip, x in [a, W], are free. The curves clamp_top_full and clamp_bottom_full (x in [0, W]) serve the other
//     reading, clamps over the full width (deck mode3_tearing_fullwidth_G050.xml; docs/mode3_tearing.md).
// The mesh is aligned with the crack path: the two halves (above and below the slit) are separate surfaces that
// share the ligament line, which has 22 equal edges (1.5045 mm). The size grows from lc0 = 1.5 mm at the ligament and
// the slit tip to 3 mm away from it (948 TRI6). lc0 = 1 mm (33 edges) would be the finer choice, but costs about
// 3.5x more (more elements, and a 2.4x smaller time step): see docs/mode3_tearing.md.
// Physical groups: surface "plate" (block); curves "clamp_top" (y = +14.3 mm, x <= a), "clamp_bottom" (y = -14.3 mm,
// x <= a), "clamp_top_full" and "clamp_bottom_full" (the same lines over the full width),
// "ligament" (interior line: side set with both adjacent triangles, and node set); point "notch_tip" (x = a, y = 0).
// Regenerate (from xml/meshes):
//   gmsh mode3_tearing.geo -2 -order 2 -format msh41 -o mode3_tearing.msh   (Gmsh 4.8.4)
mm = 1e-3;
W = 76.2 * mm;       // plate width (crack direction x)
b = 33.1 * mm;       // ligament
a = W - b;           // notch length 43.1 mm
H = 14.3 * mm;       // half height of the free band (28.6 mm between the clamps)
s = 0.5 * mm;        // half width of the 1 mm slit
t = 1.0 * mm;        // length of the taper that closes the slit at the tip
f = 9.0 * mm;        // length of slit face next to the taper with uniform edges
lc0 = 1.5 * mm;      // size at the ligament
lc1 = 3.0 * mm;      // size far from it
nlig = 22;           // ligament edges (1.5045 mm)

Point(1) = {a, 0, 0, lc0};        // notch tip (end of the taper)
Point(2) = {W, 0, 0, lc0};        // end of the ligament (free edge)
Point(3) = {a - t, s, 0, lc0};    // upper slit face, start of the taper to the tip
Point(4) = {0, s, 0, lc1};        // upper slit face at the free edge x = 0
Point(5) = {0, H, 0, lc1};
Point(6) = {W, H, 0, lc1};
Point(7) = {a - t, -s, 0, lc0};   // lower slit face, start of the taper
Point(8) = {0, -s, 0, lc1};
Point(9) = {0, -H, 0, lc1};
Point(10) = {W, -H, 0, lc1};
Point(11) = {a - t - f, s, 0, lc0};   // the last f of the slit faces get uniform edges of about lc0
Point(12) = {a - t - f, -s, 0, lc0};
Point(13) = {a, H, 0, lc1};       // end of the top clamp, above the notch tip
Point(14) = {a, -H, 0, lc1};      // end of the bottom clamp

Line(1) = {1, 2};                 // ligament (shared by both halves)
Transfinite Curve{1} = nlig + 1;
// upper half, counter-clockwise (normal +z)
Line(2) = {2, 6};
Line(14) = {6, 13};               // top edge ahead of the notch tip (free)
Line(3) = {13, 5};                // clamp_top (above the notch)
Line(4) = {5, 4};
Line(5) = {4, 11};                // upper slit face
Line(12) = {11, 3};               // upper slit face, last f before the taper
Line(6) = {3, 1};                 // upper taper face
Transfinite Curve{12} = Round(f / lc0) + 1;
Transfinite Curve{6} = Ceil(Sqrt(t * t + s * s) / lc0) + 1;
Curve Loop(1) = {1, 2, 14, 3, 4, 5, 12, 6};
Plane Surface(1) = {1};
// lower half, counter-clockwise (normal +z)
Line(7) = {1, 7};                 // lower taper face
Line(13) = {7, 12};               // lower slit face, last f before the taper
Line(8) = {12, 8};                // lower slit face
Line(9) = {8, 9};
Line(10) = {9, 14};               // clamp_bottom (below the notch)
Line(15) = {14, 10};              // bottom edge ahead of the notch tip (free)
Line(11) = {10, 2};
Transfinite Curve{13} = Round(f / lc0) + 1;
Transfinite Curve{7} = Ceil(Sqrt(t * t + s * s) / lc0) + 1;
Curve Loop(2) = {7, 13, 8, 9, 10, 15, 11, -1};
Plane Surface(2) = {2};

// size field: lc0 within 1 mm of the ligament and the slit tip, growing linearly to lc1 at 10 mm
Field[1] = Distance;
Field[1].CurvesList = {1, 6, 7, 12, 13};
Field[1].NumPointsPerCurve = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = lc0;
Field[2].SizeMax = lc1;
Field[2].DistMin = 1.0 * mm;
Field[2].DistMax = 10.0 * mm;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("plate", 1) = {1, 2};
Physical Curve("clamp_top", 1) = {3};
Physical Curve("clamp_bottom", 2) = {10};
Physical Curve("ligament", 3) = {1};
Physical Point("notch_tip", 4) = {1};
Physical Curve("clamp_top_full", 5) = {3, 14};
Physical Curve("clamp_bottom_full", 6) = {10, 15};
