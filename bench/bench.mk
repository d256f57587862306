# `make bench`: rtk (double and fixed) against Intel Embree on the same triangles and
# rays, plus the render time of every corpus and benchmark scene. Included by the
# top-level Makefile; Embree (libembree-dev) is a bench-only dependency.
# Results: the table on stdout, build/bench/results.csv and build/bench/results.json.
# `make bench-scale`: the cost curve (martini at Loop levels 0-5) against Embree; the
# table on stdout, build/bench-scale/scale.csv and the plot build/bench-scale/scale.png
# (gnuplot, from gnuplot-nox).

BENCH_DEB := libembree-dev gnuplot-nox
BENCH_HARNESS_OBJ := $(BUILD)/bench/workload.o $(BUILD)/bench/timing.o $(BUILD)/bench/results.o
BENCH_RTK_OBJ := $(BUILD)/bench/rtk_bench.o $(BUILD)/bench/rtk_rays.o $(BENCH_HARNESS_OBJ)
# The Embree harness is plain hosted C; the determinism flags do not concern it.
BENCH_EMBREE_CFLAGS := -std=c11 $(OPT) -g $(WARN) -D_POSIX_C_SOURCE=200809L

.PHONY: bench bench-deps bench-scale

$(BUILD)/bench/%.o: bench/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/bench/rtk-bench: $(BENCH_RTK_OBJ) $(BUILD)/librtplatform.a $(BUILD)/librtcore.a
	$(CC) $(OPT) -o $@ $^ $(LDLIBS)

# The SHA-256 of built trees, to prove a change to the build leaves them as they were.
$(BUILD)/bench/tree-hash: $(BUILD)/bench/tree_hash.o $(BUILD)/librtplatform.a $(BUILD)/librtcore.a
	$(CC) $(OPT) -o $@ $^ $(LDLIBS)

$(BUILD)/bench/embree-harness: bench/embree_harness.c $(BENCH_HARNESS_OBJ)
	@mkdir -p $(@D)
	$(CC) $(BENCH_EMBREE_CFLAGS) -MMD -MP -o $@ $< $(BENCH_HARNESS_OBJ) -lembree3 -lpthread -lm

# Installs Embree when it is missing (root or sudo), like `make deps` does for rtk.
bench-deps: deps
	@missing=""; for p in $(BENCH_DEB); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  $$sudo apt-get update -qq && $$sudo apt-get install -y -qq $$missing; \
	fi

# The fixed-point build is optional: when it does not build, the table says so.
bench: bench-deps
	$(MAKE) RT_REAL=double BUILD=build build/rtk build/bench/rtk-bench build/bench/embree-harness
	@mkdir -p build/bench; \
	if $(MAKE) RT_REAL=fixed BUILD=build-fixed build-fixed/rtk build-fixed/bench/rtk-bench \
	    >build/bench/fixed-build.log 2>&1; then fixed=1; \
	else fixed=0; echo "fixed: not built (see build/bench/fixed-build.log)"; fi; \
	BENCH_FIXED=$$fixed bench/run.sh

# Double build only: the cost curve compares rtk's default build with Embree.
bench-scale: bench-deps
	$(MAKE) RT_REAL=double BUILD=build build/rtk build/bench/rtk-bench build/bench/embree-harness
	bench/scale.sh

-include $(BENCH_RTK_OBJ:.o=.d) $(BUILD)/bench/tree_hash.d $(BUILD)/bench/embree-harness.d
