// The tank of prm/submerged_collapse.prm (L = 0.3 m long, H = 0.06 m
// high) with cells graded towards the bed: hx = 2.5 mm along x, hb = 1.25
// mm high at the bed, each row r = 1.025 times the one below (32 rows, to
// 2.7 mm at the top; 120 x 32 cells). On a Coulomb base of the beads'
// own friction (the prm's header gives its --set lines) the collapse's
// cell dependence sits in a layer at the bed (doc/pore_water.md, "What
// the cell changes: the bed's layer"); this mesh gives the bed the 1.25 mm
// cells' stresses at a third of their cells.
// Boundary ids (physical tags): 4 the wall (x = 0), 1 the right end, 2
// the bed, 3 the top; the file's wall is id 0, so run it as
//   mpm prm/submerged_collapse.prm --set "Mesh/Source=gmsh" \
//     --set "Mesh/Gmsh file=../meshes/submerged_collapse_graded.msh" \
//     --set "Boundary conditions/wall/Boundary ids=4"
// Regenerate: gmsh -2 -format msh2 submerged_collapse_graded.geo -o submerged_collapse_graded.msh
// Other tanks: -setnumber L 0.9 (longer), -setnumber hb 0.000625 (finer
// bed rows; the number of rows follows from hb and r), -setnumber hx.
DefineConstant[L = 0.3, H = 0.06, hx = 0.0025, hb = 0.00125, r = 1.025];
// rows: hb (r^n - 1) / (r - 1) = H, rounded
rows = Floor(Log(1 + H * (r - 1) / hb) / Log(r) + 0.5);
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {0, H, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {1, 4};
Curve Loop(1) = {1, 2, 3, -4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = Floor(L / hx + 0.5) + 1;
Transfinite Curve{2, 4} = rows + 1 Using Progression r;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve(4) = {4};
Physical Curve(1) = {2};
Physical Curve(2) = {1};
Physical Curve(3) = {3};
Physical Surface(1) = {1};
