# envtex - environment maps and texture maps, following UCSD CSE 168's lecture.
#
#   make run        install missing packages, build, render the demo to out/demo.{exr,png}
#   make test       unit tests, golden-image tests, command-line tests (alias: make check)
#   make asan       the whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer
#   make bench      benchmarks (medians of repeated runs)
#   make update-golden   re-render the golden references (look at them before committing)
#   make deps       install the Debian packages envtex needs (apt-get, as root or via sudo)
#
# User CFLAGS / LDFLAGS are respected; the project's own flags live in ET_CFLAGS.

CC ?= cc
CFLAGS ?= -O2 -g
BUILD ?= build

# Dependencies through pkg-config (lazy: only evaluated when something is compiled, so
# `make deps` works on a machine that has none of them yet).  Debian's OpenEXR 3.1 ships no
# OpenEXRCore.pc: take the include path from OpenEXR.pc and link the C library alone.
PKG_CFLAGS = $(shell pkg-config --cflags libpng OpenEXR)
PKG_LIBS = $(shell pkg-config --libs libpng) -lOpenEXRCore -lm
CHECK_CFLAGS = $(shell pkg-config --cflags check)
CHECK_LIBS = $(shell pkg-config --libs check)

ET_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Iinclude -MMD -MP
ALL_CFLAGS = $(ET_CFLAGS) $(PKG_CFLAGS) $(CFLAGS)

LIB_SRC = $(filter-out src/main.c,$(wildcard src/*.c))
LIB_OBJ = $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o)
UNIT_SRC = $(wildcard tests/unit/test_*.c)
UNIT_BIN = $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%)
TOOL_SRC = $(wildcard tests/tools/*.c)
TOOL_BIN = $(TOOL_SRC:tests/tools/%.c=$(BUILD)/tools/%)

.PHONY: all test check run asan bench update-golden clean deps unit golden cli

all: envtex

envtex: $(BUILD)/envtex
	@ln -sf $(BUILD)/envtex envtex

$(BUILD)/envtex: $(BUILD)/obj/main.o $(BUILD)/libenvtex.a
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(PKG_LIBS)

$(BUILD)/libenvtex.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/obj/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

$(BUILD)/tests/%: tests/unit/%.c $(BUILD)/libenvtex.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(CHECK_CFLAGS) -Itests/unit -o $@ $< $(BUILD)/libenvtex.a \
		$(LDFLAGS) $(CHECK_LIBS) $(PKG_LIBS)

$(BUILD)/tools/%: tests/tools/%.c $(BUILD)/libenvtex.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(BUILD)/libenvtex.a $(LDFLAGS) $(PKG_LIBS)

# ---- tests ---------------------------------------------------------------------------------
# tests/run prints one line per test program and closes with "N passed, N failed".
test: $(BUILD)/envtex $(UNIT_BIN) $(TOOL_BIN)
	@ln -sf $(BUILD)/envtex envtex
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex tests/run $(if $(STEP),--step $(STEP))

check: test

# The whole suite again, instrumented.  Its own build folder, so it never mixes objects.
asan:
	$(MAKE) BUILD=build-asan \
		CFLAGS="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all" \
		LDFLAGS="-fsanitize=address,undefined" test

update-golden: $(BUILD)/envtex $(TOOL_BIN)
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex tests/golden/update

bench: $(BUILD)/envtex $(TOOL_BIN)
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex tests/bench/run

# ---- the quick start -----------------------------------------------------------------------
DEB_PACKAGES = build-essential pkg-config libpng-dev libopenexr-dev check
deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
		dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then echo "deps: all packages present"; exit 0; fi; \
	if [ "$$(id -u)" = 0 ]; then SUDO=""; \
	elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then SUDO="sudo"; \
	else echo "envtex: missing packages; run: sudo apt-get install -y$$missing" >&2; exit 1; fi; \
	echo "deps: installing$$missing"; \
	$$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
	$$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing

run: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p out
	./envtex render data/scenes/demo.test -o out/demo.exr
	./envtex tonemap out/demo.exr out/demo.png
	@echo "rendered out/demo.exr and out/demo.png"

clean:
	rm -rf build build-asan envtex out

-include $(LIB_OBJ:.o=.d) $(BUILD)/obj/main.d
