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
# RT_ASSERT (core/invariant.h) is off in rtk and everything users link; the tests link a
# second core archive with it on, and ASSERTS=1 turns it on everywhere (the ASan build).
ASSERT_FLAGS := $(if $(filter 1,$(ASSERTS)),-DRT_ASSERTS)
BASE_CFLAGS := -std=c11 $(OPT) -g $(WARN) $(DET_FLAGS) $(REAL_FLAGS) $(ASSERT_FLAGS) $(EXTRA_CFLAGS)
CORE_CFLAGS := $(BASE_CFLAGS) -ffreestanding -fno-builtin -Iinclude
# The fixed core must not touch a floating-point register, where the compiler can say so.
ifeq ($(RT_REAL),fixed)
CORE_CFLAGS += $(shell $(CC) -mgeneral-regs-only -x c -c /dev/null -o /dev/null 2>/dev/null && echo -mgeneral-regs-only)
endif
PKGS := yaml-0.1 spng
PLATFORM_CFLAGS := $(BASE_CFLAGS) -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -Iinclude -Icore -Iplatform \
	$(shell pkg-config --cflags $(PKGS) 2>/dev/null)
LDLIBS := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lyaml -lspng) -lpthread -lm

DEB_PACKAGES := build-essential pkg-config libyaml-dev libspng-dev zlib1g-dev libcriterion-dev libcglm-dev groff-base

# The core of one backend: every core file but the other backend's real_double*/real_fixed*.
core_sources = $(filter-out core/real_double%.c core/real_fixed%.c,$(wildcard core/*.c)) $(wildcard core/real_$(1)*.c)
CORE_SRC := $(call core_sources,$(RT_REAL))
PLATFORM_SRC := $(filter-out platform/cli/main.c,$(wildcard platform/*/*.c))
TEST_SRC := $(wildcard tests/*.c)

CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
CORE_ASSERT_OBJ := $(CORE_SRC:%.c=$(BUILD)/asserts/%.o)
PLATFORM_OBJ := $(PLATFORM_SRC:%.c=$(BUILD)/%.o)
TEST_OBJ := $(TEST_SRC:%.c=$(BUILD)/%.o)

.PHONY: all deps demo check check-determinism bless clean core-sources format format-check lib install uninstall \
	check-install
all: $(BUILD)/rtk

$(BUILD)/core/%.o: core/%.c
	@mkdir -p $(@D)
	$(CC) $(CORE_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/asserts/core/%.o: core/%.c
	@mkdir -p $(@D)
	$(CC) $(CORE_CFLAGS) -DRT_ASSERTS -MMD -MP -c $< -o $@

$(BUILD)/platform/%.o: platform/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -MMD -MP -c $< -o $@

# The commit `rtk --version` names (git describe; "unknown" outside a git checkout).
# version.o is rebuilt when it changes, through a stamp that is rewritten only then.
RTK_COMMIT := $(shell git describe --always --dirty --abbrev=12 --exclude='*' 2>/dev/null || echo unknown)
$(BUILD)/commit.stamp: FORCE
	@mkdir -p $(@D); echo '$(RTK_COMMIT)' | cmp -s - $@ || echo '$(RTK_COMMIT)' >$@
$(BUILD)/platform/cli/version.o: $(BUILD)/commit.stamp
$(BUILD)/platform/cli/version.o: PLATFORM_CFLAGS += -DRTK_COMMIT='"$(RTK_COMMIT)"'
.PHONY: FORCE

$(BUILD)/librtcore.a: $(CORE_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/librtcore-asserts.a: $(CORE_ASSERT_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/librtplatform.a: $(PLATFORM_OBJ)
	@rm -f $@
	ar rcs $@ $^

# The invariant handler is linked as an object: nothing before the core archive asks for it.
$(BUILD)/rtk: $(BUILD)/platform/cli/main.o $(BUILD)/platform/debug/invariant.o $(BUILD)/librtplatform.a $(BUILD)/librtcore.a
	$(CC) $(OPT) -o $@ $^ $(LDLIBS)

$(BUILD)/rtk-tests: $(TEST_OBJ) $(BUILD)/platform/debug/invariant.o $(BUILD)/librtplatform.a $(BUILD)/librtcore-asserts.a
	$(CC) $(OPT) -o $@ $^ $(LDLIBS) -lcriterion -lz

# The core's sources for RT_REAL, for the scripts that compile it themselves (targets/).
core-sources:
	@echo $(CORE_SRC)

# ---- The library and its installation ----
# librtk.a and librtk.so hold the kernel and the hosted API: everything but the rtk
# command, save its signal bookkeeping and messages, which the output writer calls (the
# bookkeeping does nothing without rtp_signals_install). librtk.so exports the rtk_ names of
# include/rtk.h (platform/api/rtk.map).
# While the version is 0.x its SONAME carries the minor number: 0.5 and 0.6 may differ.
RTK_VERSION := $(shell sed -n 's/^\#define RTK_VERSION_STRING "\(.*\)"/\1/p' include/rtk.h)
RTK_SONAME := librtk.so.$(basename $(RTK_VERSION))
LIB_SRC := $(CORE_SRC) $(filter-out platform/cli/% platform/debug/invariant.c,$(PLATFORM_SRC)) \
           platform/cli/signals.c platform/cli/message.c
LIB_OBJ := $(LIB_SRC:%.c=$(BUILD)/%.o)
LIB_PIC_OBJ := $(LIB_SRC:%.c=$(BUILD)/pic/%.o)

$(BUILD)/pic/core/%.o: core/%.c
	@mkdir -p $(@D)
	$(CC) $(CORE_CFLAGS) -fPIC -MMD -MP -c $< -o $@
$(BUILD)/pic/platform/%.o: platform/%.c
	@mkdir -p $(@D)
	$(CC) $(PLATFORM_CFLAGS) -fPIC -MMD -MP -c $< -o $@

$(BUILD)/librtk.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^
$(BUILD)/$(RTK_SONAME): $(LIB_PIC_OBJ) platform/api/rtk.map
	$(CC) -shared -Wl,-soname,$(RTK_SONAME) -Wl,--version-script=platform/api/rtk.map -o $@ $(LIB_PIC_OBJ) $(LDLIBS)
$(BUILD)/rtk.pc: platform/api/rtk.pc.in include/rtk.h
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' \
		-e 's|@VERSION@|$(RTK_VERSION)|' $< >$@

PREFIX ?= /usr/local
BINDIR ?= $(PREFIX)/bin
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
MANDIR ?= $(PREFIX)/share/man
COMPLETIONDIR ?= $(PREFIX)/share/bash-completion/completions
INSTALLED := $(BINDIR)/rtk $(LIBDIR)/librtk.a $(LIBDIR)/$(RTK_SONAME) $(LIBDIR)/librtk.so \
	$(INCLUDEDIR)/rtk.h $(LIBDIR)/pkgconfig/rtk.pc $(MANDIR)/man1/rtk.1 $(COMPLETIONDIR)/rtk

lib: $(BUILD)/librtk.a $(BUILD)/$(RTK_SONAME)

# rtk.pc names PREFIX, so it is remade whenever install runs.
install: $(BUILD)/rtk lib
	@rm -f $(BUILD)/rtk.pc && $(MAKE) -s $(BUILD)/rtk.pc
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR) \
		$(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(COMPLETIONDIR)
	install -m 755 $(BUILD)/rtk $(DESTDIR)$(BINDIR)/rtk
	install -m 644 $(BUILD)/librtk.a $(DESTDIR)$(LIBDIR)/librtk.a
	install -m 755 $(BUILD)/$(RTK_SONAME) $(DESTDIR)$(LIBDIR)/$(RTK_SONAME)
	ln -sf $(RTK_SONAME) $(DESTDIR)$(LIBDIR)/librtk.so
	install -m 644 include/rtk.h $(DESTDIR)$(INCLUDEDIR)/rtk.h
	install -m 644 $(BUILD)/rtk.pc $(DESTDIR)$(LIBDIR)/pkgconfig/rtk.pc
	install -m 644 docs/rtk.1 $(DESTDIR)$(MANDIR)/man1/rtk.1
	install -m 644 platform/cli/completion.bash $(DESTDIR)$(COMPLETIONDIR)/rtk

uninstall:
	rm -f $(addprefix $(DESTDIR),$(INSTALLED))

# Installs into a scratch prefix and builds examples/render_scene.c against it with
# pkg-config, shared and static, as a user would; then uninstalls.
check-install: $(BUILD)/rtk
	tests/install.sh

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

# The unit and reference tests on the double build, then the golden render hashes and
# BVH hashes of both builds (the fixed build also runs its own math, precision and
# reference suites, and must stay within 1 level of the double build on every golden
# scene), and the bad-input catalogue on both.
check: deps
	$(MAKE) build/rtk build/rtk-tests build/bench/tree-hash
	$(MAKE) RT_REAL=fixed build-fixed/rtk build-fixed/rtk-tests build-fixed/bench/tree-hash
	build/rtk-tests --jobs 2
	build-fixed/rtk-tests --jobs 2 --filter 'real_fixed/*'
	build-fixed/rtk-tests --jobs 2 --filter 'precision/*'
	build-fixed/rtk-tests --jobs 2 --filter 'reference/*'
	tests/golden.sh check build/rtk double
	tests/golden.sh check build-fixed/rtk fixed
	tests/tree_hash.sh check build/bench/tree-hash double
	tests/tree_hash.sh check build-fixed/bench/tree-hash fixed
	targets/fixed_vs_double.sh
	tests/bad/run.sh build/rtk
	tests/bad/run.sh build-fixed/rtk
	$(MAKE) check-examples
	tests/install.sh

# Same hashes for every thread count, tile size, compiler, -O level and CPU; the core
# freestanding; the fixed core on a Cortex-M3 under qemu. See docs/determinism.md.
check-determinism: deps
	targets/freestanding.sh
	targets/determinism.sh double fixed
	targets/baremetal.sh

# Rewrites tests/golden/$(RT_REAL).sha256 and re-pins the determinism matrix's 64x64
# hashes (matrix-$(RT_REAL).sha256; the fixed build also the bare-metal hash), all
# from this build: say why in the commit that changes them.
bless: $(BUILD)/rtk
	tests/golden.sh bless $(BUILD)/rtk $(RT_REAL)
	targets/determinism.sh --bless $(RT_REAL)
	$(if $(filter fixed,$(RT_REAL)),targets/baremetal.sh --bless)

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

-include $(CORE_OBJ:.o=.d) $(CORE_ASSERT_OBJ:.o=.d) $(LIB_PIC_OBJ:.o=.d) $(PLATFORM_OBJ:.o=.d) $(TEST_OBJ:.o=.d) $(BUILD)/platform/cli/main.d

# Optional fragments: fuzzers (fuzz/fuzz.mk), benchmarks (bench/bench.mk), distributed
# rendering on GNU parallel and Slurm (dist/dist.mk).
-include fuzz/fuzz.mk
-include bench/bench.mk
-include dist/dist.mk
-include tests/valgrind.mk
-include examples/examples.mk
-include web/web.mk
