# make check-dist: the distributed-rendering recipes of dist/ on real engines -- GNU
# parallel and a one-node Slurm cluster started on this machine -- with stitched frames
# checked against whole-frame hashes (dist/check.sh, docs/distributed.md). Installs
# Debian's slurm-wlm, munge and parallel when missing; needs root for the daemons.

DIST_PACKAGES := slurm-wlm munge parallel

.PHONY: check-dist dist-deps
dist-deps:
	@missing=""; for p in $(DIST_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  $$sudo apt-get install -y -qq $$missing || \
	    { $$sudo apt-get update -qq && $$sudo apt-get install -y -qq $$missing; }; \
	fi

check-dist: deps dist-deps
	$(MAKE) build/rtk
	dist/check.sh build/rtk
