// Half-disc (R = 1, centre (0, 1)) resting on its curved side: the mesh of the built-in
// scene `half-disc` (scenes/half-disc.toml). Linear quadrilaterals, refined near the
// contact at (0, 0).
//
// Regenerate the shipped mesh (made with Gmsh 4.15.2; `pip install gmsh` provides the command):
//   gmsh scenes/half-disc.geo -2 -format msh41 -o scenes/half-disc.msh
// (add `-bin` for the binary MSH 4.1 variant; contrail reads both).
R = 1.0;
h_far = 0.2;     // element size away from the contact
h_near = 0.025;  // element size at the contact point

Point(1) = {0, R, 0, h_far};      // centre (not meshed: only used by the arcs)
Point(2) = {-R, R, 0, h_far};     // left end of the flat top
Point(3) = {0, 0, 0, h_near};     // lowest point: first contact
Point(4) = {R, R, 0, h_far};      // right end of the flat top

Circle(1) = {2, 1, 3};            // left quarter arc, from (-R, R) down to (0, 0)
Circle(2) = {3, 1, 4};            // right quarter arc, from (0, 0) up to (R, R)
Line(3) = {4, 2};                 // flat top, right to left
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// Size field (sizes before the subdivision into quadrilaterals, which halves them).
Field[1] = Distance;
Field[1].PointsList = {3};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_near;
Field[2].SizeMax = h_far;
Field[2].DistMin = 0.15;
Field[2].DistMax = 0.7;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// All quadrilaterals: recombine, then split any leftover triangle.
Mesh.Algorithm = 8;               // Frontal-Delaunay for quads
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;  // Blossom
Mesh.SubdivisionAlgorithm = 1;    // all quadrilaterals
Mesh.ElementOrder = 1;

Physical Surface("disc") = {1};
Physical Curve("arc") = {1, 2};   // the curved side: contact slave
Physical Curve("top") = {3};      // the flat top: pushed down
Physical Point("tip") = {3};      // the lowest point
