# The programs of examples/, built against the library as users build them, and run by
# `make check-examples` (part of make check):
#   render_scene: the hosted API (rtk_open, rtk_render, rtk_write_image), linked with
#     librtk.a; its hash must equal `rtk render --hash` for the same scene and size.
#   blob_hash: the kernel alone on a blob linked into the program, built -nostdlib
#     -ffreestanding with no C library; its own objects and the core may need nothing from
#     outside (nm -u), and its hash must equal the same render's.
# Both use only include/rtk.h.

EXAMPLES_BUILD := $(BUILD)/examples
EXAMPLE_SCENE := scenes/demo.yaml
EXAMPLE_SIZE := 96
EXAMPLE_CFLAGS := -std=c11 -O2 -Wall -Wextra -Werror -Iinclude

.PHONY: examples check-examples

examples: $(EXAMPLES_BUILD)/render_scene $(EXAMPLES_BUILD)/blob_hash

$(EXAMPLES_BUILD)/render_scene: examples/render_scene.c include/rtk.h $(BUILD)/librtk.a
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) $< -o $@ $(BUILD)/librtk.a $(LDLIBS)

$(EXAMPLES_BUILD)/scene.rtscene: $(BUILD)/rtk $(EXAMPLE_SCENE)
	@mkdir -p $(@D)
	$(BUILD)/rtk pack $(EXAMPLE_SCENE) --width $(EXAMPLE_SIZE) --height $(EXAMPLE_SIZE) -o $@

# ld names the blob's symbols after its file name: _binary_scene_rtscene_start/_end.
$(EXAMPLES_BUILD)/scene_blob.o: $(EXAMPLES_BUILD)/scene.rtscene
	cd $(@D) && ld -r -b binary -o scene_blob.o scene.rtscene

$(EXAMPLES_BUILD)/blob_hash.o: examples/blob_hash.c include/rtk.h
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) -ffreestanding -fno-builtin -fno-stack-protector -c $< -o $@

# The kernel's memcpy, memset and memmove; gcc must not turn their loops into calls to themselves.
$(EXAMPLES_BUILD)/memory.o: targets/cortex-m/memory.c
	@mkdir -p $(@D)
	$(CC) $(EXAMPLE_CFLAGS) -ffreestanding -fno-builtin -fno-tree-loop-distribute-patterns -c $< -o $@

$(EXAMPLES_BUILD)/blob_hash: $(EXAMPLES_BUILD)/blob_hash.o $(EXAMPLES_BUILD)/memory.o $(EXAMPLES_BUILD)/scene_blob.o \
	$(BUILD)/librtcore.a
	$(CC) -static -nostdlib -Wl,-z,noexecstack -o $@ $^

check-examples: examples $(BUILD)/rtk
	@set -e; want=$$($(BUILD)/rtk render $(EXAMPLE_SCENE) --width $(EXAMPLE_SIZE) --height $(EXAMPLE_SIZE) --hash --quiet); \
	got=$$($(EXAMPLES_BUILD)/render_scene $(EXAMPLE_SCENE) $(EXAMPLES_BUILD)/demo.png $(EXAMPLE_SIZE) $(EXAMPLE_SIZE)); \
	[ "$$got" = "$$want" ] || { echo "examples: render_scene printed $$got, rtk render $$want"; exit 1; }; \
	echo "examples: render_scene gives rtk render's hash $$want"; \
	got=$$($(EXAMPLES_BUILD)/blob_hash); \
	[ "$$got" = "$$want" ] || { echo "examples: blob_hash printed $$got, rtk render $$want"; exit 1; }; \
	ld -r -o $(EXAMPLES_BUILD)/blob_hash_all.o $(EXAMPLES_BUILD)/blob_hash.o $(EXAMPLES_BUILD)/memory.o $(CORE_OBJ); \
	extra=$$(nm -u $(EXAMPLES_BUILD)/blob_hash_all.o | awk '/ U /{print $$2}' | \
		grep -vxE '_binary_scene_rtscene_(start|end)' || true); \
	[ -z "$$extra" ] || { echo "examples: blob_hash or the core needs $$extra"; exit 1; }; \
	echo "examples: blob_hash, the kernel without a C library, gives the same hash"
