// Serosa appendectomy set: cecum + appendix + mesoappendix, one conformal mesh.
// Units: metres. y is up (gravity -y), x to the patient's left in the scene's
// frame (the appendix hangs off the cecum's lower end towards +x and down).
// Physical volumes: 1 "appendix", 2 "mesoappendix", 3 "cecum".
// Mesh sizes (m) can be overridden: gmsh -setnumber h_cecum 0.004 ... (see tools/make_assets.sh)
SetFactory("OpenCASCADE");

If (!Exists(h_cecum))    h_cecum = 0.008;     EndIf
If (!Exists(h_appendix)) h_appendix = 0.0035; EndIf
If (!Exists(h_meso))     h_meso = 0.0025;     EndIf
If (!Exists(curvature))  curvature = 8;       EndIf  // elements per 2 Pi of curvature
If (!Exists(h_base))     h_base = 0;          EndIf  // > 0: refine round the appendix's base

// ---- cecum: a slightly flattened ellipsoidal pouch, 5 (x) x 6 (y) x 4 (z) cm
Sphere(1) = {0, 0, 0, 1};
Dilate {{0, 0, 0}, {0.025, 0.030, 0.020}} { Volume{1}; }

// ---- appendix: bent capsule, radius 3.5 mm, centreline in the z = 0 plane.
// straight root from inside the cecum (x = 0.008) to x = 0.04 at y = -0.022,
// a 45 degree bend downwards (radius 12 mm), a 44 mm straight part, round tip.
r  = 0.0035;
yb = -0.022;
R  = 0.012;
Ls = 0.044;
Cylinder(2) = {0.008, yb, 0, 0.032, 0, 0, r};
Torus(3) = {0, 0, 0, R, r, Pi/4};            // arc from angle 0 to 45 deg
Rotate {{0, 0, 1}, {0, 0, 0}, Pi/4} { Volume{3}; }      // now 45..90 deg
Translate {0.040, yb - R, 0} { Volume{3}; }  // 90 deg end at (0.04, yb)
bx = 0.040 + R*Cos(Pi/4);
by = yb - R + R*Sin(Pi/4);
dx = Cos(Pi/4); dy = -Sin(Pi/4);
Cylinder(4) = {bx, by, 0, Ls*dx, Ls*dy, 0, r};
Sphere(5) = {bx + Ls*dx, by + Ls*dy, 0, r};
app() = BooleanUnion{ Volume{2}; Delete; }{ Volume{3, 4, 5}; Delete; };

// ---- mesoappendix: a 2.5 mm thick fold in the plane of the appendix, on the
// concave side of the bend, from the cecum along the appendix to 1 cm before
// the tip, with a free edge bowing about 2 cm away from the appendix.
t = 0.0025;
Point(101) = {0.010, yb, -t/2};                           // inside the cecum
Point(102) = {0.040, yb, -t/2};                           // start of the bend
Point(103) = {bx, by, -t/2};                              // end of the bend
Point(104) = {bx + 0.034*dx, by + 0.034*dy, -t/2};        // 1 cm before tip
Point(105) = {0.034, -0.040, -t/2};                       // free edge
Point(106) = {0.004, -0.027, -t/2};                       // inside the cecum
Line(101) = {101, 102};
Line(102) = {102, 103};
Line(103) = {103, 104};
Line(104) = {104, 105};
Line(105) = {105, 106};
Line(106) = {106, 101};
Curve Loop(101) = {101, 102, 103, 104, 105, 106};
Plane Surface(101) = {101};
slab() = Extrude {0, 0, t} { Surface{101}; };
// slab(1) is the extruded volume
meso() = BooleanDifference{ Volume{slab(1)}; Delete; }{ Volume{app(0), 1}; };
app2() = BooleanDifference{ Volume{app(0)}; Delete; }{ Volume{1}; };
all() = BooleanFragments{ Volume{1, app2(), meso()}; Delete; }{};
Printf("cecum 1, appendix %g, meso %g, all: %g %g %g", app2(0), meso(0), all(0), all(1), all(2));

Physical Volume("appendix", 1) = {app2()};
Physical Volume("mesoappendix", 2) = {meso()};
Physical Volume("cecum", 3) = {1};

// ---- mesh sizes: smallest wins at shared points (meso last)
MeshSize{ PointsOf{ Volume{1}; } } = h_cecum;
MeshSize{ PointsOf{ Volume{app2()}; } } = h_appendix;
MeshSize{ PointsOf{ Volume{meso()}; } } = h_meso;
Mesh.MeshSizeMax = h_cecum;
// The base, where the appendix is secured and transected: h_base within 15 mm of the point
// (0.025, -0.024, 0) (from the cecum wall to 2 cm along the appendix, the mesoappendix's root
// included), growing to the other sizes over the next 10 mm.
If (h_base > 0)
  Field[1] = Ball;
  Field[1].XCenter = 0.025; Field[1].YCenter = -0.024; Field[1].ZCenter = 0;
  Field[1].Radius = 0.015; Field[1].Thickness = 0.010;
  Field[1].VIn = h_base; Field[1].VOut = h_cecum;
  Background Field = 1;
EndIf
Mesh.MeshSizeMin = 0.5*h_meso;
Mesh.MeshSizeFromCurvature = curvature;
Mesh.Algorithm3D = 1;   // Delaunay
Mesh.Optimize = 1;
Mesh.OptimizeThreshold = 0.5;  // re-optimize every tet below this gamma
// (Debian's gmsh has no Netgen optimizer; gmsh's own optimizer is used)
General.NumThreads = 1;
