// The SOFA-matching benchmark box (docs/BENCHMARKS.md "FEM"): 4 x 1 x 1 m along x,
// x in [0, 4], y and z in [-0.5, 0.5]. Uniform size h (set with -setnumber h H):
// h = 0.101 gives ~19.1k tets (assets/box_19k.msh), h = 0.0584 ~95.6k (assets/box_95k.msh).
SetFactory("OpenCASCADE");
Box(1) = {0, -0.5, -0.5, 4, 1, 1};
Physical Volume(1) = {1};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.Algorithm3D = 1;
Mesh.MaxNumThreads3D = 1;
