// Serosa liver lobe: an ellipsoid 15 (x) x 6 (y) x 10 (z) cm, its base
// flattened (cut by the plane y = -0.018) and a concave spherical dent in the
// underside (visceral surface). Units: metres, y up. Physical volume 1 "liver".
// Mesh size (m) can be overridden: gmsh -setnumber h 0.005 (see tools/make_assets.sh)
SetFactory("OpenCASCADE");

If (!Exists(h))         h = 0.010;    EndIf
If (!Exists(curvature)) curvature = 10; EndIf  // elements per 2 Pi of curvature

Sphere(1) = {0, 0, 0, 1};
// put the sphere's poles (degenerate points of its parametrization) at the
// ellipsoid's x tips: poles on the flat sides gave sliver tets there
Rotate {{0, 1, 0}, {0, 0, 0}, Pi/2} { Volume{1}; }
Dilate {{0, 0, 0}, {0.075, 0.030, 0.050}} { Volume{1}; }
// flattened base: keep y >= -0.018
Box(2) = {-0.1, -0.018, -0.1, 0.2, 0.1, 0.2};
lobe() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };
// concave dent in the underside: sphere of radius 42 mm whose top is at y = -0.006
Sphere(3) = {0.015, -0.048, 0.0, 0.042};
liver() = BooleanDifference{ Volume{lobe()}; Delete; }{ Volume{3}; Delete; };

Physical Volume("liver", 1) = {liver()};

Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = 0.3*h;
MeshSize{ PointsOf{ Volume{liver()}; } } = h;
Mesh.MeshSizeFromCurvature = curvature;
Mesh.Algorithm3D = 1;   // Delaunay
Mesh.Optimize = 1;      // (Debian's gmsh has no Netgen optimizer)
Mesh.OptimizeThreshold = 0.5;  // re-optimize every tet below this gamma
General.NumThreads = 1;
