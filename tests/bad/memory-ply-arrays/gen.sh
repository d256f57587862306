#!/bin/sh
# An ASCII PLY of 1000000 vertices (6 MB of file, 24 MB of vertex array) and one face.
awk 'BEGIN {
  print "ply"; print "format ascii 1.0"; print "element vertex 1000000"
  print "property float x"; print "property float y"; print "property float z"
  print "element face 1"; print "property list uchar int vertex_indices"; print "end_header"
  for (i = 0; i < 1000000; i++) print i % 7, i % 5, i % 3
  print "3 0 1 2"
}' >mesh.ply
