// The background mesh of the slope of Griffiths and Lane (1999), example 1
// (doc/slope_stability.md): a rectangle 80 m x 12 m (slope_runout.msh:
// 100 m x 12 m) of 1 m squares (refine
// with 'Mesh/Global refinements'), the toe of the 2:1 slope at x = 0 on the
// rigid base y = 0, the slope rising towards +x, the runout towards -x.
// The base is split at the toe, so that the slope stands on a fixed base
// (as in Griffiths and Lane) and what runs out slides on a floor with a
// boundary condition of its own. Physical tags (boundary ids):
//   1 the back x = 40, 2 the base under the slope (0 <= x <= 40),
//   3 the top y = 12, 4 the floor in front of the toe (x <= 0),
//   5 the front x = -40.
// Regenerate: gmsh -2 -format msh2 slope.geo -o slope.msh, and the longer
// mesh of the runout (60 m from the toe to the back):
//   gmsh -2 -format msh2 -setnumber back 60 slope.geo -o slope_runout.msh
front = 40;  // floor length in front of the toe
DefineConstant[back = 40];  // toe to the back boundary
top   = 12;
h     = 1;

Point(1) = {-front, 0, 0};
Point(2) = {0, 0, 0};
Point(3) = {back, 0, 0};
Point(4) = {back, top, 0};
Point(5) = {0, top, 0};
Point(6) = {-front, top, 0};
Line(1) = {1, 2};   // floor
Line(2) = {2, 3};   // base under the slope
Line(3) = {3, 4};   // back
Line(4) = {4, 5};   // top over the slope
Line(5) = {5, 6};   // top over the floor
Line(6) = {6, 1};   // front
Line(7) = {2, 5};   // interior line above the toe
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1, 5} = front / h + 1;
Transfinite Curve{2, 4} = back / h + 1;
Transfinite Curve{3, 6, 7} = top / h + 1;
Transfinite Surface{1};
Transfinite Surface{2};
Recombine Surface{1, 2};
Physical Curve(1) = {3};
Physical Curve(2) = {2};
Physical Curve(3) = {4, 5};
Physical Curve(4) = {1};
Physical Curve(5) = {6};
Physical Surface(1) = {1, 2};
