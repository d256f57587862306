# rtk in the browser; included by the top-level Makefile (see docs/web.md).
#   make web         the WebAssembly build and the static site, into build-web/site/
#   make serve       serves build-web/site/ on localhost and prints the URL
#   make check-web   the browser tests: headless Chromium driven by playwright-core
#   make web-cli     build-web/rtk-cli.wasm, the rtk command for wasm32-wasi (node's WASI)
# The kernel and the loader compile for wasm32-wasi with clang and Debian's wasi-libc;
# libyaml, libspng and zlib from their Debian source packages (web/wasm/sources.sh).

WEB_BUILD := build-web
WEB_SITE := $(WEB_BUILD)/site
WEB_DEB_PACKAGES := clang lld llvm wasi-libc libclang-rt-14-dev-wasm32 dpkg-dev
WEB_TEST_DEB_PACKAGES := chromium
WEB_PORT ?= 8457
WASI_CC := clang --target=wasm32-wasi
# The native determinism flags (DET_FLAGS), the double build; no -g: the size is downloaded.
WASM_OPT := -O2
WASM_BASE := -std=c11 $(WASM_OPT) $(WARN) $(DET_FLAGS)
WASM_CORE_CFLAGS := $(WASM_BASE) -ffreestanding -fno-builtin -Iinclude
WASM_LIB_CFLAGS := -std=gnu11 $(WASM_OPT) $(DET_FLAGS) -w
WASM_LDFLAGS := -Wl,--max-memory=4294967296 -Wl,-z,stack-size=8388608 -Wl,--strip-debug

WEB_DEBSRC := $(WEB_BUILD)/deb-src
YAML_DIR := $(WEB_DEBSRC)/libyaml-0.2.5
SPNG_DIR := $(WEB_DEBSRC)/libspng-0.7.3
ZLIB_DIR := $(WEB_DEBSRC)/zlib-1.2.13.dfsg
WEB_SOURCES_STAMP := $(WEB_DEBSRC)/.unpacked

WASM_PLATFORM_CFLAGS := $(WASM_BASE) -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE \
	-D_WASI_EMULATED_SIGNAL -D_WASI_EMULATED_GETPID -include web/wasm/wasi_compat.h -Iinclude -Icore -Iplatform \
	-I$(YAML_DIR)/include -I$(SPNG_DIR)/spng -I$(ZLIB_DIR)
WASM_LIBS := -lwasi-emulated-signal -lwasi-emulated-getpid

YAML_OBJ := $(patsubst %,$(WEB_BUILD)/lib/yaml/%.o,api dumper emitter loader parser reader scanner writer)
ZLIB_OBJ := $(patsubst %,$(WEB_BUILD)/lib/z/%.o,adler32 compress crc32 deflate inflate inffast inftrees trees uncompr zutil)
SPNG_OBJ := $(WEB_BUILD)/lib/spng/spng.o

WEB_CORE_SRC := $(call core_sources,double)
# platform/thread/threads.c and pool.c need POSIX threads; wasm gets one thread (web/wasm/parallel_serial.c).
# WASI has no signals to handle (web/wasm/signals_none.c), no file owners or modes (owner_none.c).
WEB_PLATFORM_SRC := $(filter-out platform/cli/main.c platform/thread/threads.c platform/thread/pool.c platform/cli/signals.c,\
	$(wildcard platform/*/*.c))
WEB_SHIM_SRC := web/wasm/parallel_serial.c web/wasm/realpath.c web/wasm/signals_none.c web/wasm/owner_none.c
WEB_CORE_OBJ := $(WEB_CORE_SRC:%.c=$(WEB_BUILD)/%.o)
WEB_PLATFORM_OBJ := $(WEB_PLATFORM_SRC:%.c=$(WEB_BUILD)/%.o) $(WEB_SHIM_SRC:%.c=$(WEB_BUILD)/%.o)
WEB_API_OBJ := $(patsubst %.c,$(WEB_BUILD)/%.o,$(wildcard web/wasm/rtk_wasm*.c))
WEB_ARCHIVES := $(WEB_BUILD)/librtplatform.a $(WEB_BUILD)/librtcore.a $(WEB_BUILD)/libspng.a \
	$(WEB_BUILD)/libyaml.a $(WEB_BUILD)/libz.a

.PHONY: web web-deps web-cli web-site serve check-web web-clean
clean: web-clean

web-deps:
	@missing=""; for p in $(WEB_DEB_PACKAGES) $(WEB_EXTRA_DEB); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	command -v node >/dev/null && command -v npm >/dev/null || missing="$$missing nodejs npm"; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  $$sudo apt-get update -qq && $$sudo apt-get install -y -qq $$missing; \
	fi

$(WEB_SOURCES_STAMP): web/wasm/sources.sh
	web/wasm/sources.sh $(WEB_DEBSRC)
	@touch $@

# The libraries' sources exist once the stamp does (order-only: they are not remade).
$(WEB_BUILD)/lib/yaml/%.o: | $(WEB_SOURCES_STAMP)
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_LIB_CFLAGS) -I$(YAML_DIR)/include -DYAML_VERSION_MAJOR=0 -DYAML_VERSION_MINOR=2 \
		-DYAML_VERSION_PATCH=5 '-DYAML_VERSION_STRING="0.2.5"' -c $(YAML_DIR)/src/$*.c -o $@
$(WEB_BUILD)/lib/z/%.o: | $(WEB_SOURCES_STAMP)
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_LIB_CFLAGS) -c $(ZLIB_DIR)/$*.c -o $@
$(WEB_BUILD)/lib/spng/spng.o: | $(WEB_SOURCES_STAMP)
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_LIB_CFLAGS) -I$(ZLIB_DIR) -c $(SPNG_DIR)/spng/spng.c -o $@

$(WEB_BUILD)/libyaml.a: $(YAML_OBJ)
$(WEB_BUILD)/libz.a: $(ZLIB_OBJ)
$(WEB_BUILD)/libspng.a: $(SPNG_OBJ)
$(WEB_BUILD)/librtcore.a: $(WEB_CORE_OBJ)
$(WEB_BUILD)/librtplatform.a: $(WEB_PLATFORM_OBJ)
$(WEB_BUILD)/%.a:
	@rm -f $@
	llvm-ar rcs $@ $^

$(WEB_BUILD)/core/%.o: core/%.c
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_CORE_CFLAGS) -MMD -MP -c $< -o $@

$(WEB_BUILD)/platform/%.o: platform/%.c | $(WEB_SOURCES_STAMP)
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_PLATFORM_CFLAGS) -MMD -MP -c $< -o $@
# The commit names the wasm build as it does the native one, so their parts stitch together.
$(WEB_BUILD)/platform/cli/version.o: $(BUILD)/commit.stamp
$(WEB_BUILD)/platform/cli/version.o: WASM_PLATFORM_CFLAGS += -DRTK_COMMIT='"$(RTK_COMMIT)"'
$(WEB_BUILD)/web/wasm/%.o: web/wasm/%.c | $(WEB_SOURCES_STAMP)
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_PLATFORM_CFLAGS) -MMD -MP -c $< -o $@

# The rtk command itself, for node's WASI (web/test/cli_hashes.mjs checks it against build/rtk).
web-cli: web-deps
	$(MAKE) $(WEB_BUILD)/rtk-cli.wasm
$(WEB_BUILD)/rtk-cli.wasm: $(WEB_BUILD)/platform/cli/main.o $(WEB_ARCHIVES) web/web.mk
	$(WASI_CC) $(WASM_OPT) $(WASM_LDFLAGS) -o $@ $(filter-out web/web.mk,$^) $(WASM_LIBS)

# The browser's module: a WASI reactor exporting web/wasm/rtk_wasm*.c's functions.
$(WEB_SITE)/rtk.wasm: $(WEB_API_OBJ) $(WEB_ARCHIVES) web/web.mk
	@mkdir -p $(@D)
	$(WASI_CC) $(WASM_OPT) $(WASM_LDFLAGS) -mexec-model=reactor -o $@ $(filter-out web/web.mk,$^) $(WASM_LIBS)

# The static site: the page, its npm libraries (pinned by web/package-lock.json), the
# corpus (copied from $(RTK_SHARED)/cse457 each time, never committed) and its list.
RTK_SHARED ?= ../shared
web: web-deps
	$(MAKE) $(WEB_SITE)/rtk.wasm web-site
	@echo "web: built $(WEB_SITE)/ ($$(du -k $(WEB_SITE)/rtk.wasm | cut -f1) KiB of wasm); make serve to open it"

web-site:
	@if [ ! -d web/node_modules ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then \
	  cd web && npm ci --no-audit --no-fund; fi
	@mkdir -p $(WEB_SITE)/vendor/three/addons/controls $(WEB_SITE)/vendor/three/addons/renderers \
		$(WEB_SITE)/vendor/three/addons/lines $(WEB_SITE)/vendor/browser_wasi_shim
	cp web/app/* $(WEB_SITE)/
	cp web/node_modules/three/build/three.module.js web/node_modules/three/build/three.core.js $(WEB_SITE)/vendor/three/
	cp web/node_modules/three/examples/jsm/controls/OrbitControls.js $(WEB_SITE)/vendor/three/addons/controls/
	cp web/node_modules/three/examples/jsm/renderers/Projector.js web/node_modules/three/examples/jsm/renderers/SVGRenderer.js $(WEB_SITE)/vendor/three/addons/renderers/
	cp $(addprefix web/node_modules/three/examples/jsm/lines/,Line2.js LineGeometry.js LineMaterial.js \
		LineSegments2.js LineSegmentsGeometry.js) $(WEB_SITE)/vendor/three/addons/lines/
	cp web/node_modules/@bjorn3/browser_wasi_shim/dist/*.js $(WEB_SITE)/vendor/browser_wasi_shim/
	cp web/node_modules/three/LICENSE $(WEB_SITE)/vendor/three/
	cp web/node_modules/@bjorn3/browser_wasi_shim/LICENSE-MIT $(WEB_SITE)/vendor/browser_wasi_shim/ 2>/dev/null || true
	@test -d $(RTK_SHARED)/cse457 || { echo "web: no corpus at $(RTK_SHARED)/cse457 (set RTK_SHARED)" >&2; exit 1; }
	rm -rf $(WEB_SITE)/cse457 && cp -r $(RTK_SHARED)/cse457 $(WEB_SITE)/cse457
	node web/tools/corpus_manifest.mjs $(WEB_SITE)

# Serves the built site on localhost until interrupted.
serve:
	@test -f $(WEB_SITE)/index.html || { echo "serve: no site yet; run make web first" >&2; exit 1; }
	@echo "rtk web: http://127.0.0.1:$(WEB_PORT)/"
	@cd $(WEB_SITE) && exec python3 -m http.server $(WEB_PORT) --bind 127.0.0.1

# The browser tests against native build/rtk; installs Chromium (Debian) and the npm
# packages (playwright-core drives /usr/bin/chromium; no browser download).
check-web:
	$(MAKE) web-deps WEB_EXTRA_DEB="$(WEB_TEST_DEB_PACKAGES)"
	$(MAKE) deps
	$(MAKE) build/rtk
	$(MAKE) web
	web/test/check_web.sh

-include $(WEB_API_OBJ:.o=.d) $(WEB_CORE_OBJ:.o=.d) $(WEB_PLATFORM_OBJ:.o=.d) $(WEB_BUILD)/platform/cli/main.d

web-clean:
	rm -rf $(WEB_BUILD)
