// The USGS miniature flume (Denlinger and Iverson 2001; Tjung et al.,
// "Flume Test"): a bed inclined at 31.4 degrees, 2 m long, joined by a
// circular arc of radius 0.1 m, tangent to both, to a horizontal runout
// Lout long (default 1 m; the loose debris flow of doc/pore_water.md runs
// further: -setnumber Lout 3). The domain extends H = 0.2 m above the bed
// (normal to the incline, vertically above the runout).
//
// Coordinates: the incline and the runout, produced, meet at the origin
// (the "break in slope"); the incline rises to the left (-x), the runout is
// y = 0, x > 0. The arc runs from T1 (on the incline, R tan(theta/2) from
// the origin) to T2 = (R tan(theta/2), 0); its centre is T2 + (0, R).
// Distance along the bed, s, is measured from the arc's midpoint
// (negative upslope); prm/flume_usgs.prm and the "flume" postprocessor use
// the same geometry.
//
// Mesh: unstructured quadrilaterals (Frontal-Delaunay triangles recombined
// by Blossom: all quads, angles 45-135 degrees, shortest edge 2.6 mm,
// 16,116 cells; 32,341 with Lout = 3), size h (default 5 mm, twice the
// paper's 2.5 mm) within 0.14 m of the bed downslope of s = -0.75 m,
// growing to 3 h further away (the upper incline and the top of the
// domain, where the sand never goes).
// A finer mesh: gmsh -2 -format msh2 -setnumber h 0.0025 flume.geo -o X.msh
//
// Physical tags: boundary 1 = the bed (incline, arc, runout: one frictional
// boundary), boundary 2 = the ends and the top (free); surface 1.
// Regenerate: gmsh -2 -format msh2 flume.geo -o flume.msh
If (!Exists(h))
  h = 0.005;
EndIf
If (!Exists(Lout))
  Lout = 1.0;  // runout length
EndIf
theta = 31.4 * Pi / 180;
R     = 0.1;   // radius of the arc
Lin   = 2.0;   // incline length along the slope, from the origin
H     = 0.2;   // height of the domain above the bed
sfine = 0.75;  // fine mesh downslope of s = -sfine (distance along the bed)
d     = R * Tan(theta / 2);  // origin to the tangent points

// Bed
Point(1) = {-Lin * Cos(theta), Lin * Sin(theta), 0};          // top of incline
Point(2) = {-(sfine - R * theta / 2 + d) * Cos(theta),
            (sfine - R * theta / 2 + d) * Sin(theta), 0};     // s = -sfine
Point(3) = {-d * Cos(theta), d * Sin(theta), 0};              // T1
Point(4) = {d, R, 0};                                         // arc centre
Point(5) = {d, 0, 0};                                         // T2
Point(6) = {Lout, 0, 0};                                      // end of runout
// Top: parallel to the incline at H, horizontal at H over the runout; they
// meet at (H tan(theta/2), H).
Point(7) = {Lout, H, 0};
Point(8) = {H * Tan(theta / 2), H, 0};
Point(9) = {-Lin * Cos(theta) + H * Sin(theta), Lin * Sin(theta) + H * Cos(theta), 0};

Line(1)   = {1, 2};
Line(2)   = {2, 3};
Circle(3) = {3, 4, 5};
Line(4)   = {5, 6};
Line(5)   = {6, 7};
Line(6)   = {7, 8};
Line(7)   = {8, 9};
Line(8)   = {9, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};
Plane Surface(1) = {1};

// Size: h within 0.14 m of the lower bed, 3 h beyond 0.3 m.
Field[1] = Distance;
Field[1].CurvesList = {2, 3, 4};
Field[1].NumPointsPerCurve = 2000;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = 3 * h;
Field[2].DistMin = 0.14;
Field[2].DistMax = 0.3;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Mesh.Algorithm = 6;  // Frontal-Delaunay (8, for quads, crashes gmsh 4.8.4 here)
Mesh.RecombinationAlgorithm = 1;  // Blossom
Recombine Surface{1};

Physical Curve(1) = {1, 2, 3, 4};
Physical Curve(2) = {5, 6, 7, 8};
Physical Surface(1) = {1};
