# envtex - environment maps and texture maps, following UCSD CSE 168's lecture.
#
#   make run        install missing packages, build, render the demo to out/demo.{exr,png}
#   make test       the grading suite: unit, golden-image, command-line tests (alias: make check)
#   make check-all  make test plus the slower checks a grade does not need (CI runs it)
#   make asan       the test suite (check-all, but its kit and grade suites) under ASan + UBSan
#   make bench      benchmarks (medians of repeated runs)
#   make update-golden   re-render the golden references (look at them before committing)
#   make docs-images     re-render the pictures in docs/images/ from data/scenes/
#   make grade SUBMISSIONS=dir   build, test and render each student's tree: out/grade/ (CSV, HTML)
#   make autograder  Gradescope's autograder, out/autograder.zip; make submission (in a kit) the
#                    student's tree, out/submission.tar.gz (docs/grading.md)
#   make starter STEPS="latlong cdf" [HINTS=1|2|3]   a starter kit with those steps as stubs (or all)
#   make test STEP=cdf   only the tests of one lecture step (tests/steps)
#   make deps       install the Debian packages envtex needs (apt-get, as root or via sudo)
#   make fuzz       libFuzzer on every parser, FUZZ_SECONDS each (needs clang; docs/robustness.md)
#   make valgrind   every data scene and the bad-input catalogue under valgrind
#
# User CFLAGS / LDFLAGS are respected; the project's own flags live in ET_CFLAGS.

CC ?= cc
CFLAGS ?= -O2 -g
BUILD ?= build
# The scripts under tests/ read and write numbers with awk, sort and printf, and match names with
# [a-z]: under a decimal-comma locale (de_DE) awk read "0.010" as 0 and wrote "0,0010" into the
# bench's CSV files, and under tr_TR [a-z] missed the i of "int".  envtex never calls setlocale.
export LC_ALL := C
# Build on every core (docs/design-notes.md, "make test's time": the test budget against the build).
NPROC := $(shell nproc 2>/dev/null || echo 1)
# parallel builds; a sub-make (make run's, make asan's) shares the top make's job slots instead
# (adding -j again there made make warn "-j2 forced in makefile: resetting jobserver mode")
ifeq ($(MAKELEVEL),0)
MAKEFLAGS += -j$(NPROC)
endif

# Dependencies through pkg-config (lazy: only evaluated when something is compiled, so
# `make deps` works on a machine that has none of them yet).  Debian's OpenEXR 3.1 ships no
# OpenEXRCore.pc: take the include path from OpenEXR.pc and link the C library alone.
PKG_CFLAGS = $(shell pkg-config --cflags libpng OpenEXR)
PKG_LIBS = $(shell pkg-config --libs libpng) -lOpenEXRCore -lm
CHECK_CFLAGS = $(shell pkg-config --cflags check)
CHECK_LIBS = $(shell pkg-config --libs check)

# -ffp-contract=off: a * b + c is rounded twice, as C11 writes it, with every compiler.  GCC does
# this already under -std=c11; Clang fuses such expressions by default, which broke the exact
# identities the tests check (a x b == -(b x a)) and would move the golden images with the compiler.
ET_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -ffp-contract=off -Wall -Wextra -Iinclude -MMD -MP
ALL_CFLAGS = $(ET_CFLAGS) $(PKG_CFLAGS) $(CFLAGS)

# src/LAYER/MODULE.c (README: the layers); the command line, src/cli/, links the library
LIB_SRC = $(filter-out src/cli/%,$(wildcard src/*/*.c))
LIB_OBJ = $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o)
CLI_SRC = $(wildcard src/cli/*.c)
CLI_OBJ = $(CLI_SRC:src/%.c=$(BUILD)/obj/%.o)
# tests/unit/LAYER/test_MODULE.c -> $(BUILD)/tests/test_MODULE (tests/steps names them so)
UNIT_SRC = $(wildcard tests/unit/*/test_*.c)
UNIT_BIN = $(addprefix $(BUILD)/tests/,$(basename $(notdir $(UNIT_SRC))))
TOOL_SRC = $(wildcard tools/programs/*.c)
TOOL_BIN = $(TOOL_SRC:tools/programs/%.c=$(BUILD)/tools/%)

# Each test case's limit, CASE_TIMEOUT seconds (tests/unit/unit.h), times Check's multiplier:
# 1 here (the few test cases marked unit_slow have three times the limit; docs/design-notes.md,
# "Test cases' limits"), 10 under the sanitizers.  TEST_TIMEOUT is each test program's (tests/run).
CASE_TIMEOUT ?= 10
CK_TIMEOUT_MULTIPLIER ?= 1

.PHONY: all test check check-all run asan bench update-golden clean deps docs-images starter \
	starter-check

all: envtex

envtex: $(BUILD)/envtex
	@ln -sf $(BUILD)/envtex envtex

$(BUILD)/envtex: $(CLI_OBJ) $(BUILD)/libenvtex.a
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(PKG_LIBS)

$(BUILD)/libenvtex.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

# The compiler and flags of the last build in $(BUILD): when `make CC=clang` or `make CFLAGS=-O3`
# changes them, every object is compiled again (without this, make said "Nothing to be done" and
# kept the old binary).  The file is rewritten only when its text changes, so an unchanged build
# rebuilds nothing.
BUILD_FLAGS = $(CC) $(ALL_CFLAGS) | $(LDFLAGS)
$(BUILD)/flags: FORCE
	@mkdir -p $(dir $@)
	@printf '%s\n' '$(BUILD_FLAGS)' | cmp -s - $@ || printf '%s\n' '$(BUILD_FLAGS)' > $@
.PHONY: FORCE
FORCE:

$(BUILD)/obj/%.o: src/%.c $(BUILD)/flags
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

.SECONDEXPANSION:
$(BUILD)/tests/%: $$(wildcard tests/unit/*/%.c) $(BUILD)/libenvtex.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(CHECK_CFLAGS) -Itests/unit -o $@ $< $(BUILD)/libenvtex.a \
		$(LDFLAGS) $(CHECK_LIBS) $(PKG_LIBS)

$(BUILD)/tools/%: tools/programs/%.c $(BUILD)/libenvtex.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(BUILD)/libenvtex.a $(LDFLAGS) $(PKG_LIBS)

# ---- tests ---------------------------------------------------------------------------------
# tests/run prints one line per test program and closes with "N passed, N failed".  make test
# is what a grader runs once per student; check-all adds tests/run's CHECK_ALL_ONLY suites.
test check-all: $(BUILD)/envtex $(UNIT_BIN) $(TOOL_BIN)
	@ln -sf $(BUILD)/envtex envtex
	@CK_TIMEOUT_MULTIPLIER=$(CK_TIMEOUT_MULTIPLIER) CASE_TIMEOUT=$(CASE_TIMEOUT) BUILD=$(BUILD) \
		ENVTEX=$(BUILD)/envtex \
		tests/run $(if $(filter check-all,$@),--all,$(if $(STEP),--step $(STEP)))

check: test

# The whole suite again, instrumented.  Its own build folder, so it never mixes objects.
asan:
	CHECK_ALL_AGAIN=1 $(MAKE) BUILD=build-asan CK_TIMEOUT_MULTIPLIER=10 \
		CFLAGS="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all" \
		LDFLAGS="-fsanitize=address,undefined" check-all

update-golden: $(BUILD)/envtex $(TOOL_BIN)
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex tests/golden/update

# a class's grades: make grade SUBMISSIONS=dir [GRADE_OUT=out/grade] [GRADE_JOBS=N] [UNSAFE=1]
# (docs/grading.md; each submission in a sandbox, tools/grade/sandbox; N students at once)
GRADE_OUT ?= out/grade
grade: $(BUILD)/envtex
	@[ -n "$(SUBMISSIONS)" ] || { echo "envtex: make grade needs SUBMISSIONS=DIR, a folder of" \
		"student trees or tarballs" >&2; exit 1; }
	@UNSAFE="$(UNSAFE)" GRADE_JOBS="$(or $(GRADE_JOBS),1)" ENVTEX=$(BUILD)/envtex \
		tools/grade/run "$(SUBMISSIONS)" "$(GRADE_OUT)"
.PHONY: grade

# Gradescope's autograder: out/autograder.zip (setup.sh, run_autograder; docs/grading.md)
autograder:
	@$(IN_KIT)
	@tools/grade/autograder/make-zip out/autograder.zip

# a student's submission, out/submission.tar.gz: the tree without build/ and out/, in one folder
submission:
	@mkdir -p out
	@tar -czf out/submission.tar.gz --exclude='./build*' --exclude=./out --exclude=./.git \
		--exclude=./envtex --transform 's,^\.,envtex,' .
	@echo "submission: out/submission.tar.gz (upload it to Gradescope)"
.PHONY: autograder submission

# assignment starter kits (docs/teaching.md)
# (a kit has neither: it is made in the instructor's tree)
IN_KIT = [ -d tools/starter ] || { echo "envtex: make $@: this is a starter kit; make $@ runs in the" \
	"instructor's tree (docs/teaching.md)" >&2; exit 1; }
starter:
	@$(IN_KIT)
	@BUILD=$(BUILD) STEPS="$(STEPS)" HINTS="$(HINTS)" tools/starter/make-starter

starter-check:
	@$(IN_KIT)
	+@BUILD=$(BUILD) tests/starter/check

docs-images: $(BUILD)/envtex
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex docs/make-images.sh

bench: $(BUILD)/envtex $(TOOL_BIN)
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex tools/bench/run

# ---- the quick start -----------------------------------------------------------------------
# (zip for make autograder; unzip and jq for its test)
DEB_PACKAGES = build-essential pkg-config libpng-dev libopenexr-dev check bubblewrap zip unzip jq
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
	@pkg-config --atleast-version=3.1 OpenEXR || { \
		echo "envtex: needs OpenEXR 3.1 or later (its C API, OpenEXRCore); this system has" \
			"$$(pkg-config --modversion OpenEXR 2>/dev/null || echo none): use Debian 12 or Ubuntu 24.04 or later" >&2; \
		exit 1; }

run: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p out
	./envtex render data/scenes/demo.test -o out/demo.exr
	./envtex tonemap out/demo.exr out/demo.png
	@echo "rendered out/demo.exr and out/demo.png"

clean:
	rm -rf build build-asan build-o3 build-clang envtex out

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d)

# ---- hostile input (docs/robustness.md) ----------------------------------------------------
# Fuzz targets: tests/fuzz/fuzz_NAME.c, one per parser.  `make test` builds each with the
# project's compiler and tests/fuzz/replay.c (a plain main) into $(BUILD)/fuzz/fuzz_NAME, and
# tests/fuzz/run-tests replays the seed corpora and the regression inputs through them.
FUZZ_SRC = $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_NAMES = $(FUZZ_SRC:tests/fuzz/fuzz_%.c=%)
FUZZ_REPLAY_BIN = $(FUZZ_NAMES:%=$(BUILD)/fuzz/fuzz_%)

$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz.c tests/fuzz/replay.c tests/fuzz/fuzz.h \
		tests/fuzz/fuzz_image.h $(BUILD)/libenvtex.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests/fuzz -o $@ $< tests/fuzz/fuzz.c tests/fuzz/replay.c \
		$(BUILD)/libenvtex.a $(LDFLAGS) $(PKG_LIBS)

test check-all: $(FUZZ_REPLAY_BIN)

# envtex and every program make test runs, built and not run: tools/grade builds a submission with
# it, then runs make test; tools/grade-timing times it against make test.
programs: $(BUILD)/envtex $(UNIT_BIN) $(TOOL_BIN) $(FUZZ_REPLAY_BIN)
.PHONY: programs

# `make fuzz [FUZZ_SECONDS=60] [FUZZ_TARGETS="scene exr"]`: libFuzzer, one target at a time,
# each for FUZZ_SECONDS, under FUZZ_LIMITS.  New inputs go to build-fuzz/corpus/NAME, crashes to
# build-fuzz/crashes/ (keep each one under tests/fuzz/regressions/NAME/ once it is fixed).
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= $(FUZZ_NAMES)
FUZZ_CC ?= clang
FUZZ_BUILD = build-fuzz
FUZZ_SAN = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_MAX_LEN_scene = 8192
FUZZ_MAX_LEN_DEFAULT = 65536
# The targets pass their loaders a 64 MiB memory budget (FUZZ_MEMORY_BUDGET, tests/fuzz/fuzz.h):
# a header that claims more is refused by it.  These limits sit well above the budget, so an input
# that escapes it (a loader that allocates before it charges, a decompression bomb the budget
# misses) fails the fuzzer as an out-of-memory or a timeout instead of passing slowly.  The
# slowest input the budget admits takes under 1 s (docs/robustness.md).
FUZZ_LIMITS = -malloc_limit_mb=256 -rss_limit_mb=1024 -timeout=5

fuzz:
	@command -v $(FUZZ_CC) >/dev/null 2>&1 && \
	printf '#include <stddef.h>\nint LLVMFuzzerTestOneInput(const unsigned char *d, size_t n) { (void)d; return (int)n * 0; }\n' | \
		$(FUZZ_CC) -fsanitize=fuzzer -x c - -o /dev/null 2>/dev/null || \
		{ echo "envtex: make fuzz needs clang and libFuzzer; run: sudo apt-get install -y clang libclang-rt-14-dev" >&2; exit 1; }
	@$(MAKE) --no-print-directory BUILD=$(FUZZ_BUILD) CC=$(FUZZ_CC) \
		CFLAGS="-O1 -g -fsanitize=fuzzer-no-link $(FUZZ_SAN)" $(FUZZ_BUILD)/libenvtex.a
	@mkdir -p $(FUZZ_BUILD)/crashes
	@set -e; for t in $(FUZZ_TARGETS); do \
		$(FUZZ_CC) $(ET_CFLAGS) $(PKG_CFLAGS) -O1 -g -fsanitize=fuzzer $(FUZZ_SAN) -Itests/fuzz \
			-o $(FUZZ_BUILD)/fuzz_$$t tests/fuzz/fuzz_$$t.c tests/fuzz/fuzz.c \
			$(FUZZ_BUILD)/libenvtex.a $(PKG_LIBS); \
	done
	@set -e; for t in $(FUZZ_TARGETS); do \
		case $$t in scene) len=$(FUZZ_MAX_LEN_scene);; *) len=$(FUZZ_MAX_LEN_DEFAULT);; esac; \
		mkdir -p $(FUZZ_BUILD)/corpus/$$t; \
		seeds=""; for d in tests/fuzz/corpus/$$t tests/fuzz/regressions/$$t; do [ -d $$d ] && seeds="$$seeds $$d"; done; \
		echo "fuzz: $$t for $(FUZZ_SECONDS) s (max_len $$len)"; \
		$(FUZZ_BUILD)/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -max_len=$$len $(FUZZ_LIMITS) \
			-print_final_stats=1 -artifact_prefix=$(FUZZ_BUILD)/crashes/$$t- \
			$(FUZZ_BUILD)/corpus/$$t $$seeds 2>$(FUZZ_BUILD)/fuzz_$$t.log \
			|| { tail -n 40 $(FUZZ_BUILD)/fuzz_$$t.log; echo "fuzz: $$t found a crash (see $(FUZZ_BUILD)/crashes/)"; exit 1; }; \
		grep -E '^(stat::number_of_executed_units|Done)' $(FUZZ_BUILD)/fuzz_$$t.log || true; \
	done

# `make valgrind`: every data scene rendered under valgrind (no errors, no leaks), then the
# bad-input catalogue (tests/bad) with envtex run under valgrind.
VALGRIND = valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect
valgrind: $(BUILD)/envtex
	@command -v valgrind >/dev/null 2>&1 || { echo "envtex: make valgrind needs valgrind; run: sudo apt-get install -y valgrind" >&2; exit 1; }
	@set -e; tmp=$$(mktemp -d); trap 'rm -rf "$$tmp"' EXIT; \
	for s in data/scenes/*.test; do \
		echo "valgrind: $$s"; \
		$(VALGRIND) $(BUILD)/envtex render $$s -o $$tmp/out.exr --quiet --spp 1 >/dev/null; \
	done
	@BUILD=$(BUILD) ENVTEX=$(BUILD)/envtex WRAP="$(VALGRIND)" tests/bad/run-tests

clean: clean-fuzz
clean-fuzz:
	rm -rf $(FUZZ_BUILD)

.PHONY: fuzz valgrind clean-fuzz
