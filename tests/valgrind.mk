# make check-valgrind: memcheck over a heavy render (double and fixed builds) and every
# bad-input case, 0 errors and 0 bytes lost in every category (tests/valgrind.sh).
# Included by the top-level Makefile; installs valgrind with apt-get when missing, as `make deps` does.
.PHONY: check-valgrind valgrind-deps

valgrind-deps:
	@command -v valgrind >/dev/null || { \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  $$sudo apt-get update -qq && $$sudo apt-get install -y -qq valgrind; }

check-valgrind: deps valgrind-deps
	$(MAKE) build/rtk
	$(MAKE) RT_REAL=fixed build-fixed/rtk
	tests/valgrind.sh build/rtk build-fixed/rtk
