// The tutorial's ground (doc/tutorial.md): a hillside surveyed at eleven
// points, steep (28-34 degrees) at the top, easing to a runout with a small
// counter-slope at x = 18-21 m, 40 m long. The domain is the band between
// the ground and a line 3-6 m above it: material points only go where
// there are cells.
//
// Boundary ids: the physical tags of the curves (the names are for the
// reader: mpm reads the numbers and its parameter file names them, see
// prm/tutorial_slope.prm):
//   1 ground  (the surveyed profile: a frictional bed)
//   2 wall    (x = 0, the back of the released column: slip)
//   3 open    (the top and the right end: free, not listed in the prm)
// Surface: physical tag 1 (the cells' material id).
//
// Mesh: unstructured quadrilaterals of size h (Frontal-Delaunay triangles
// recombined by Blossom). Regenerate:
//   gmsh -2 -format msh2 tutorial_slope.geo -o tutorial_slope.msh
// and a finer mesh made by Gmsh itself (new unstructured cells, where
// 'Mesh/Global refinements' splits each of these cells in four):
//   gmsh -2 -format msh2 -setnumber h 0.125 tutorial_slope.geo -o X.msh
DefineConstant[h = 0.25];

// The ground profile, left to right (x, y in m).
Point(1)  = {0,  9.0, 0};
Point(2)  = {3,  7.4, 0};
Point(3)  = {6,  5.6, 0};
Point(4)  = {9,  3.6, 0};
Point(5)  = {12, 2.0, 0};
Point(6)  = {15, 1.0, 0};
Point(7)  = {18, 0.6, 0};
Point(8)  = {21, 0.8, 0};
Point(9)  = {24, 0.5, 0};
Point(10) = {30, 0.0, 0};
Point(11) = {40, -0.3, 0};
// The top of the domain.
Point(12) = {40, 2.7, 0};
Point(13) = {12, 8.0, 0};
Point(14) = {0, 14.0, 0};

For i In {1:10}
  Line(i) = {i, i + 1};       // ground segments 1-10
EndFor
Line(11) = {11, 12};          // right end
Line(12) = {12, 13};          // top
Line(13) = {13, 14};          // top
Line(14) = {14, 1};           // wall at x = 0
Curve Loop(1) = {1:14};
Plane Surface(1) = {1};

Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.Algorithm = 6;               // Frontal-Delaunay
Mesh.RecombinationAlgorithm = 1;  // Blossom: all quadrilaterals
Recombine Surface{1};

Physical Curve("ground", 1) = {1:10};
Physical Curve("wall", 2)   = {14};
Physical Curve("open", 3)   = {11, 12, 13};
Physical Surface("soil", 1) = {1};
