#!/bin/sh
# 4000 nested flow lists around 300000 scalars (600 KB): libyaml scans each token in
# time proportional to the flow depth, so this took 8-16 s before the work bound.
awk 'BEGIN {
  s = "Root: "
  for (i = 0; i < 4000; i++) s = s "["
  printf "%s", s
  for (i = 0; i < 300000; i++) printf "a,"
  s = "a"
  for (i = 0; i < 4000; i++) s = s "]"
  print s
}' >scene.yaml
