#!/bin/sh
# A flow list of 1000000 one-letter scalars: 2 MB of file, 32 MB of tree nodes.
awk 'BEGIN { printf "Root: ["; for (i = 0; i < 1000000; i++) printf "a,"; print "a]" }' >scene.yaml
