# mk/fuzz.mk - libFuzzer targets (clang + Debian's libclang-rt), included by the Makefile.
#
#   make fuzz                  builds every fuzz/fuzz_*.c and runs each for FUZZ_SECONDS (default 10)
#   make fuzz FUZZ_SECONDS=600 FUZZ_TARGETS="quat regmap"   a long run of some targets
#   make fuzz-ci               the short run of .ci/run: FUZZ_CI_SECONDS (default 15) per target,
#                              FUZZ_JOBS (default: the machine's cores) targets at a time
#   make fuzz-build            build only (build/fuzz/fuzz_NAME)
#
# Each target runs on a working corpus build/fuzz/corpus/NAME (new units land there) seeded
# from the committed fuzz/corpus/NAME and fuzz/regress/NAME; a crash or property violation
# leaves its input in build/fuzz/artifacts/ (copy it to fuzz/regress/NAME/ to keep it as a
# regression test: tests/fuzz/test_fuzz_regress.c replays both directories under `make test`).
# fuzz/run.sh prints the executions per target (libFuzzer's stat::number_of_executed_units)
# and a last line "N passed, M failed"; it exits non-zero on any finding.
#
# Everything (core, ports, CLI except its main.c, and the tests' double reference
# tests/common/ref.c) is rebuilt with clang into build/fuzz with
# -fsanitize=fuzzer-no-link,address,undefined, so libFuzzer sees coverage in the code under
# test, not only in the harness.

FUZZ_CC       ?= clang
FUZZ_SECONDS  ?= 10
FUZZ_CI_SECONDS ?= 15
FUZZ_TARGETS  ?=
FUZZ_CORES    := $(shell nproc 2>/dev/null || echo 1)
FUZZ_JOBS     ?= $(FUZZ_CORES)
FUZZ_BUILD    := $(BUILD)/fuzz
FUZZ_SAN      := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_CFLAGS   := $(STD) $(WARN) $(FPFLAGS) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer-no-link
FUZZ_SRC      := $(sort $(wildcard fuzz/fuzz_*.c))
FUZZ_NAMES    := $(FUZZ_SRC:fuzz/fuzz_%.c=%)
FUZZ_BIN      := $(FUZZ_NAMES:%=$(FUZZ_BUILD)/fuzz_%)
FUZZ_LIB_SRC  := $(CORE_SRC) $(PORT_SRC) $(filter-out cli/main.c,$(CLI_SRC))
# The double reference of the tests (tests/common/ref.c), in the same archive: a target that
# includes "common/ref.h" links it, one copy for every test, bench and fuzz program.
FUZZ_LIB_SRC  += tests/common/ref.c
FUZZ_LIB_OBJ  := $(FUZZ_LIB_SRC:%.c=$(FUZZ_BUILD)/obj/%.o)

.PHONY: fuzz fuzz-ci fuzz-build

# The packages first (tools/deps.sh fuzz: clang and its libclang-rt-N-dev), then the build.
fuzz-build:
	@sh tools/deps.sh fuzz
	@$(MAKE) -s -j$(FUZZ_CORES) --no-print-directory $(FUZZ_BIN)

fuzz: fuzz-build
	@FUZZ_BUILD=$(FUZZ_BUILD) sh fuzz/run.sh $(FUZZ_SECONDS) $(or $(FUZZ_TARGETS),$(FUZZ_NAMES))

fuzz-ci: fuzz-build
	@FUZZ_BUILD=$(FUZZ_BUILD) FUZZ_JOBS=$(FUZZ_JOBS) sh fuzz/run.sh $(FUZZ_CI_SECONDS) $(or $(FUZZ_TARGETS),$(FUZZ_NAMES))

$(FUZZ_BUILD)/obj/lib/%.o: lib/%.c
	@mkdir -p $(@D)
	$(FUZZ_CC) -MMD -MP $(FUZZ_CFLAGS) $(CPPFLAGS_CORE) -c $< -o $@

$(FUZZ_BUILD)/obj/ports/%.o: ports/%.c
	@mkdir -p $(@D)
	$(FUZZ_CC) -MMD -MP $(FUZZ_CFLAGS) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports $(PKG_CFLAGS) -c $< -o $@

$(FUZZ_BUILD)/obj/cli/%.o: cli/%.c
	@mkdir -p $(@D)
	$(FUZZ_CC) -MMD -MP $(FUZZ_CFLAGS) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Icli $(PKG_CFLAGS) -c $< -o $@

$(FUZZ_BUILD)/obj/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(FUZZ_CC) -MMD -MP $(FUZZ_CFLAGS) $(CPPFLAGS_CORE) -Itests -c $< -o $@

$(FUZZ_BUILD)/libqo_fuzz.a: $(FUZZ_LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(FUZZ_BUILD)/obj/fuzz/%.o: fuzz/%.c
	@mkdir -p $(@D)
	$(FUZZ_CC) -MMD -MP $(FUZZ_CFLAGS) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Ifuzz -Itests $(PKG_CFLAGS) -c $< -o $@

$(FUZZ_BUILD)/fuzz_%: $(FUZZ_BUILD)/obj/fuzz/fuzz_%.o $(FUZZ_BUILD)/libqo_fuzz.a
	$(FUZZ_CC) $(FUZZ_SAN) -fsanitize=fuzzer -o $@ $< $(FUZZ_BUILD)/libqo_fuzz.a $(PKG_LIBS) -lm -pthread -lutil
