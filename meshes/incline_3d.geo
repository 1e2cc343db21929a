// The 30 degree incline of incline.geo extruded 1 m in z into hexahedra:
// a slab 6 m along the slope, 2 m across it and 1 m wide, in cells of
// 0.25 m aligned with the slope (not with x and y). The bed (the face
// extruded from the lower edge) has physical tag 1, the other faces tag 2,
// the volume (material id) tag 1. Gravity is along -y.
// Regenerate: gmsh -3 -format msh2 incline_3d.geo -o incline_3d.msh
theta = 30 * Pi / 180;
L = 6;   // along the slope
H = 2;   // across the slope
W = 1;   // width (z)
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
// out[0]: the top face, out[1]: the volume, out[2..5]: the faces extruded
// from lines 1..4.
out[] = Extrude {0, 0, W} { Surface{1}; Layers{W / h}; Recombine; };
Physical Surface(1) = {out[2]};
Physical Surface(2) = {1, out[0], out[3], out[4], out[5]};
Physical Volume(1) = {out[1]};
