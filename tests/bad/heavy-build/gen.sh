#!/bin/sh
# A 128x128 grid of 32768 triangles; with LoopSubdivision 4 the build makes 8 million
# triangles and their BVH: about 5 s of work here, which the cases interrupt after 1 s.
awk 'BEGIN {
  n = 128
  print "ply"; print "format ascii 1.0"; printf "element vertex %d\n", (n + 1) * (n + 1)
  print "property float x"; print "property float y"; print "property float z"
  printf "element face %d\n", 2 * n * n; print "property list uchar int vertex_indices"; print "end_header"
  for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) printf "%g %g %g\n", i / n - 0.5, j / n - 0.5, ((i * 7 + j * 3) % 5) / 50
  for (j = 0; j < n; j++) for (i = 0; i < n; i++) {
    a = j * (n + 1) + i
    printf "3 %d %d %d\n3 %d %d %d\n", a, a + 1, a + n + 2, a, a + n + 2, a + n + 1
  }
}' >mesh.ply
