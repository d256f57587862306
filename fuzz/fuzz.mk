# libFuzzer targets and sanitizer runs; included by the top-level Makefile.
#   make fuzz-build               every target, ASan+UBSan+libFuzzer, into build-fuzz/
#   make fuzz FUZZ_SECONDS=N      runs each target N seconds from its seed corpus
#   make fuzz-long FUZZ_SECONDS=N  fresh random seeds, N s per target and backend; keeps the
#                                 minimised corpus in fuzz/corpus/ (fuzz/long.sh)
#   make fuzz-coverage            line coverage of core/ per target from its corpus (llvm-cov)
#   make check-asan               the Criterion suite and the bad-input catalogue under ASan+UBSan
# Core targets are built for every scalar backend present (double, and fixed once
# core/real_fixed.h exists); the parser targets (yaml, ply, png) for double only.

FUZZ_CC ?= clang
FUZZ_SECONDS ?= 20
FUZZ_JOBS ?= 2
# libFuzzer's random seed: fixed, so a run (in CI too) can be replayed exactly; 0 draws
# a new one each run, for exploring (make fuzz FUZZ_SEED=0 FUZZ_SECONDS=600).
FUZZ_SEED ?= 1
FUZZ_BUILD := build-fuzz
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_PARSERS := fuzz_yaml fuzz_ply fuzz_png
FUZZ_ALL := $(patsubst fuzz/%.c,%,$(wildcard fuzz/fuzz_*.c))
FUZZ_CORE_TARGETS := $(filter-out $(FUZZ_PARSERS),$(FUZZ_ALL))
# Helpers linked into every target; png_reference.c (libpng) only into fuzz_png.
FUZZ_HELPERS := $(filter-out fuzz/fuzz_%.c fuzz/png_reference.c,$(wildcard fuzz/*.c))
# Backends built, and backends `make fuzz` runs (FUZZ_RUN_VARIANTS=double for one).
FUZZ_VARIANTS ?= double $(if $(wildcard core/real_fixed.h),fixed)
FUZZ_RUN_VARIANTS ?= $(FUZZ_VARIANTS)

# The top-level flags without the backend switch; each variant adds its own.
FUZZ_CORE_CFLAGS := $(filter-out -DRT_REAL_FIXED,$(CORE_CFLAGS)) -DRT_ASSERTS $(FUZZ_SAN) -fsanitize=fuzzer-no-link
FUZZ_PLATFORM_CFLAGS := $(filter-out -DRT_REAL_FIXED,$(PLATFORM_CFLAGS)) $(FUZZ_SAN) -fsanitize=fuzzer-no-link
fuzz_real_flag = $(if $(filter fixed,$(1)),-DRT_REAL_FIXED)
fuzz_targets = $(if $(filter fixed,$(1)),$(FUZZ_CORE_TARGETS),$(FUZZ_ALL))

fuzz_bins = $(foreach v,$(1),$(addprefix $(FUZZ_BUILD)/$(v)/,$(call fuzz_targets,$(v))))
FUZZ_BINS := $(call fuzz_bins,$(FUZZ_VARIANTS))

.PHONY: fuzz-deps fuzz-build fuzz-build-run fuzz fuzz-long fuzz-coverage fuzz-clean check-asan
clean: fuzz-clean

define FUZZ_VARIANT_RULES
# Objects are intermediates of the pattern chain; keep them for incremental builds.
.PRECIOUS: $(FUZZ_BUILD)/$(1)/core/%.o $(FUZZ_BUILD)/$(1)/platform/%.o $(FUZZ_BUILD)/$(1)/fuzz/%.o

$(FUZZ_BUILD)/$(1)/core/%.o: core/%.c
	@mkdir -p $$(@D)
	$(FUZZ_CC) $(FUZZ_CORE_CFLAGS) $(call fuzz_real_flag,$(1)) -MMD -MP -c $$< -o $$@

$(FUZZ_BUILD)/$(1)/platform/%.o: platform/%.c
	@mkdir -p $$(@D)
	$(FUZZ_CC) $(FUZZ_PLATFORM_CFLAGS) $(call fuzz_real_flag,$(1)) -MMD -MP -c $$< -o $$@

$(FUZZ_BUILD)/$(1)/fuzz/%.o: fuzz/%.c
	@mkdir -p $$(@D)
	$(FUZZ_CC) $(FUZZ_PLATFORM_CFLAGS) $(call fuzz_real_flag,$(1)) -MMD -MP -c $$< -o $$@

$(FUZZ_BUILD)/$(1)/librtcore.a: $(patsubst %.c,$(FUZZ_BUILD)/$(1)/%.o,$(call core_sources,$(1)))
	@rm -f $$@
	ar rcs $$@ $$^

$(FUZZ_BUILD)/$(1)/librtplatform.a: $(patsubst %.c,$(FUZZ_BUILD)/$(1)/%.o,$(PLATFORM_SRC))
	@rm -f $$@
	ar rcs $$@ $$^

$(FUZZ_BUILD)/$(1)/fuzz_%: $(FUZZ_BUILD)/$(1)/fuzz/fuzz_%.o $(patsubst %.c,$(FUZZ_BUILD)/$(1)/%.o,$(FUZZ_HELPERS)) \
		$(if $(filter fixed,$(1)),,$(FUZZ_BUILD)/$(1)/librtplatform.a) $(FUZZ_BUILD)/$(1)/librtcore.a
	$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -o $$@ $$^ $$(LDLIBS)
endef
$(foreach v,$(sort $(FUZZ_VARIANTS) $(FUZZ_RUN_VARIANTS)),$(eval $(call FUZZ_VARIANT_RULES,$(v))))
# fuzz_png checks libspng against libpng (libpng-dev, installed by fuzz-deps).
$(FUZZ_BUILD)/double/fuzz_png: $(FUZZ_BUILD)/double/fuzz/png_reference.o
$(FUZZ_BUILD)/double/fuzz_png: LDLIBS += $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng16)

# clang, its libFuzzer runtime and libpng (fuzz_png's reference), installed like `make deps` does when missing.
fuzz-deps:
	@command -v $(FUZZ_CC) >/dev/null && [ -n "$$($(FUZZ_CC) -print-file-name=libclang_rt.fuzzer-$$(uname -m).a | grep /)" ] \
	  && dpkg -s libpng-dev >/dev/null 2>&1 || { \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  $$sudo apt-get update -qq && $$sudo apt-get install -y -qq clang libclang-rt-14-dev libpng-dev; }

fuzz-build: fuzz-deps
	$(MAKE) $(FUZZ_BINS)

# Only what `make fuzz` runs, so a run does not wait for (or fail on) the other backend.
fuzz-build-run: fuzz-deps
	$(MAKE) $(call fuzz_bins,$(FUZZ_RUN_VARIANTS))

# Each target runs on a scratch copy of its seed corpus; any crash, leak, sanitizer
# report or broken invariant fails the run and leaves the input in the scratch folder.
fuzz: fuzz-build-run
	FUZZ_SEED=$(FUZZ_SEED) fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_JOBS) $(call fuzz_bins,$(FUZZ_RUN_VARIANTS))

# Explores (random seeds) and grows fuzz/corpus/ with what adds coverage; FUZZ_TARGETS
# narrows it (e.g. FUZZ_TARGETS="fuzz_box fuzz_bvh"). Runs add up in fuzz/long-runs.txt.
FUZZ_TARGETS ?= $(FUZZ_ALL)
fuzz-long: fuzz-build-run
	fuzz/long.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_JOBS) \
	  $(filter $(addprefix %/,$(FUZZ_TARGETS)),$(call fuzz_bins,$(FUZZ_RUN_VARIANTS)))
	fuzz/long.sh --totals

# Line coverage of core/ per target from the corpora alone (fuzz/coverage.sh, llvm-14).
FUZZ_COV_BUILD := build-fuzz-cov
fuzz-coverage: fuzz-deps
	$(MAKE) FUZZ_BUILD=$(FUZZ_COV_BUILD) FUZZ_SAN="-fprofile-instr-generate -fcoverage-mapping" \
	  $(subst $(FUZZ_BUILD)/,$(FUZZ_COV_BUILD)/,$(FUZZ_BINS))
	fuzz/coverage.sh $(FUZZ_COV_BUILD) $(subst $(FUZZ_BUILD)/,$(FUZZ_COV_BUILD)/,$(FUZZ_BINS))

fuzz-clean:
	rm -rf $(FUZZ_BUILD) $(FUZZ_COV_BUILD) build-asan build-asan-fixed

ASAN_BUILD := build-asan$(if $(filter fixed,$(RT_REAL)),-fixed)
ASAN_FLAGS := -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer

# OPT reaches both the compile and the link lines of the top-level rules.
check-asan: deps
	$(MAKE) BUILD=$(ASAN_BUILD) OPT="$(ASAN_FLAGS)" ASSERTS=1 $(ASAN_BUILD)/rtk $(ASAN_BUILD)/rtk-tests
	fuzz/sanitized.sh $(ASAN_BUILD)/sanitizer-reports $(ASAN_BUILD)/rtk-tests --jobs 2
	tests/bad/run.sh $(ASAN_BUILD)/rtk

-include $(wildcard $(FUZZ_BUILD)/*/*/*.d)
