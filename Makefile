# rtk build. `make` builds build/rtk; `make RT_REAL=fixed` builds build-fixed/rtk.
# `make demo` and `make check` install their own Debian dependencies first.

RT_REAL ?= double
ifeq ($(RT_REAL),fixed)
BUILD ?= build-fixed
REAL_FLAGS := -DRT_REAL_FIXED
else ifeq ($(RT_REAL),double)
BUILD ?= build
REAL_FLAGS :=
else
$(error RT_REAL must be double or fixed)
endif

CC ?= cc
OPT ?= -O2
# Determinism: no FMA contraction, no fast-math, no errno side path for sqrt.
DET_FLAGS := -ffp-contract=off -fno-fast-math -fno-math-errno
WARN := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wvla
BASE_CFLAGS := -std=c11 $(OPT) -g $(WARN) $(DET_FLAGS) $(REAL_FLAGS) $(EXTRA_CFLAGS)
CORE_CFLAGS := $(BASE_CFLAGS) -ffreestanding -fno-builtin
# The fixed core must not touch a floating-point register, where the compiler can say so.
ifeq ($(RT_REAL),fixed)
CORE_CFLAGS += $(shell $(CC) -mgeneral-regs-only -x c -c /dev/null -o /dev/null 2>/dev/null && echo -mgeneral-regs-only)
endif
PKGS := yaml-0.1 spng
PLATFORM_CFLAGS := $(BASE_CFLAGS) -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -Icore -Iplatform \
	$(shell pkg-config --cflags $(PKGS) 2>/dev/null)
LDLIBS := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lyaml -lspng) -lpthread -lm

DEB_PACKAGES := build-essential pkg-config libyaml-dev libspng-dev libcriterion-dev libcglm-dev

# The core of one backend: every core file but the other backend's real_double*/real_fixed*.
core_sources = $(filter-out core/real_double%.c core/real_fixed%.c,$(wildcard core/*.c)) $(wildcard core/real_$(1)*.c)
CORE_SRC := $(call core_sources,$(RT_REAL))
PLATFORM_SRC := $(filter-out platform/cli/main.c,$(wildcard platform/*/*.c))
TEST_SRC := $(wildcard tests/*.c)

CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
PLATFORM_OBJ := $(PLATFORM_SRC:%.c=$(BUILD)/%.o)
TEST_OBJ := $(TEST_SRC:%.c=$(BUILD)/%.o)

.PHONY: all deps demo check check-determinism bless clean core-sources format format-check
all: $(BUILD)/rtk

$(BUILD)/core/%.o: core/%.c
	@mkdir -p $(@D)
	$(CC) $(CORE_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/platform/%.o: platform/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/librtcore.a: $(CORE_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/librtplatform.a: $(PLATFORM_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/rtk: $(BUILD)/platform/cli/main.o $(BUILD)/librtplatform.a $(BUILD)/librtcore.a
	$(CC) $(OPT) -o $@ $^ $(LDLIBS)

$(BUILD)/rtk-tests: $(TEST_OBJ) $(BUILD)/librtplatform.a $(BUILD)/librtcore.a
	$(CC) $(OPT) -o $@ $^ $(LDLIBS) -lcriterion

# The core's sources for RT_REAL, for the scripts that compile it themselves (targets/).
core-sources:
	@echo $(CORE_SRC)

# Installs the Debian packages above when any is missing (root or sudo).
deps:
	@missing=""; for p in $(DEB_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  $$sudo apt-get update -qq && $$sudo apt-get install -y -qq $$missing; \
	fi

demo: deps
	$(MAKE) $(BUILD)/rtk
	$(BUILD)/rtk render scenes/demo.yaml -o demo.png
	@echo "wrote demo.png"

# The unit and reference tests on the double build, then the golden render hashes
# of both builds (the fixed build also runs its own math and precision suites).
check: deps
	$(MAKE) build/rtk build/rtk-tests
	$(MAKE) RT_REAL=fixed build-fixed/rtk build-fixed/rtk-tests
	build/rtk-tests --jobs 2
	build-fixed/rtk-tests --jobs 2 --filter 'real_fixed/*'
	build-fixed/rtk-tests --jobs 2 --filter 'precision/*'
	tests/golden.sh check build/rtk double
	tests/golden.sh check build-fixed/rtk fixed
	tests/bad/run.sh build/rtk

# Same hashes for every thread count, tile size, compiler, -O level and CPU; the core
# freestanding; the fixed core on a Cortex-M3 under qemu. See docs/determinism.md.
check-determinism: deps
	targets/freestanding.sh
	targets/determinism.sh double fixed
	targets/baremetal.sh

# Rewrites tests/golden/$(RT_REAL).sha256; say why in the commit that changes it.
bless: $(BUILD)/rtk
	tests/golden.sh bless $(BUILD)/rtk $(RT_REAL)

# The C sources in the style of .clang-format (clang-format 14): `make format` rewrites
# them, `make format-check` lists every file that differs and fails.
FORMAT_SRC = $(shell git ls-files '*.c' '*.h' 2>/dev/null)
format:
	clang-format -i $(FORMAT_SRC)
format-check:
	@command -v clang-format >/dev/null || { echo "format-check: clang-format is not installed"; exit 1; }
	@clang-format --dry-run --Werror $(FORMAT_SRC) && echo "format-check: $(words $(FORMAT_SRC)) files in style"

clean:
	rm -rf build build-fixed build-baremetal demo.png

-include $(CORE_OBJ:.o=.d) $(PLATFORM_OBJ:.o=.d) $(TEST_OBJ:.o=.d) $(BUILD)/platform/cli/main.d

# Optional fragments: fuzzers (fuzz/fuzz.mk) and benchmarks (bench/bench.mk).
-include fuzz/fuzz.mk
-include bench/bench.mk
-include tests/valgrind.mk
