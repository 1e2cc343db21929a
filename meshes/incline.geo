// A 30 degree incline for the sliding block (Tjung et al., "Rigid Block"):
// a strip 6 m along the slope and 2 m across it, meshed with 0.25 m quads
// aligned with the slope (not with x and y). The bed (the lower edge) has
// physical tag 1, the other edges tag 2, the surface (material id) tag 1.
// Regenerate: gmsh -2 -format msh2 incline.geo -o incline.msh
theta = 30 * Pi / 180;
L = 6;   // along the slope
H = 2;   // across the slope
h = 0.25;

Point(1) = {0, 0, 0};
Point(2) = {L * Cos(theta), -L * Sin(theta), 0};
Point(3) = {L * Cos(theta) + H * Sin(theta), -L * Sin(theta) + H * Cos(theta), 0};
Point(4) = {H * Sin(theta), H * Cos(theta), 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = L / h + 1;
Transfinite Curve{2, 4} = H / h + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve(1) = {1};
Physical Curve(2) = {2, 3, 4};
Physical Surface(1) = {1};
