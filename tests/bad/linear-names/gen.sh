#!/bin/sh
# 200000 materials, each used by one of 200000 spheres (40 MB of YAML): a loader that
# finds a material by a linear search compares names 2e10 times here.
awk 'BEGIN {
  n = 200000
  print "Materials:"
  for (i = 0; i < n; i++)
    printf "    M%d: {Shader: Blinn-Phong Shader, Uniforms: {Diffuse: {Color: {R: 0.5, G: 0.5, B: 0.5}}}}\n", i
  print "Root:"
  print "    Name: Root"
  print "    Children:"
  print "        - {Name: Camera, Components: {Transform: {Translation: {Z: 4}}, Camera: {Render Width (px): 4, Render Height (px): 3}}}"
  for (i = 0; i < n; i++)
    printf "        - {Name: S%d, Components: {Transform: {Translation: {X: %d}}, Sphere: {Material: M%d}}}\n", i, i, n - 1 - i
}' >scene.yaml
