# qorient - the one build entry point.
#
#   make            core library (build/libqorient.a), ports and the command (build/qorient)
#   make test       host tests under AddressSanitizer + UndefinedBehaviorSanitizer
#   make core-check the core alone with -Werror on gcc, clang and arm-none-eabi-gcc, plus the
#                   no-heap / no-float-in-fixed-core checks (what .ci/run calls)
#   make clean
#
# Layout of sources (new files are picked up by the wildcards, no edit here needed):
#   lib/src/*.c            portable core; *_fx.c files are the fixed-point core (no float at all)
#   ports/mock/*.c         recording sink (host only)
#   ports/linux/*.c        Linux ports (libmodbus, libgpiod, streamer, simulator)
#   cli/*.c                the `qorient` command: main, option/number parsing and the portable
#                          subcommands (convert, slerp, plan, gimbal), which need only the core
#   cli/linux/*.c          its Linux-only subcommands (stream, sim): they need the Linux ports
#                          (libmodbus, libgpiod, threads); kept apart so the portable part can be
#                          built and fuzzed without them
#   tests/SUITE/test_*.c   one cmocka program each (SUITE: core, ports, examples, fuzz; see
#                          docs/TESTING.md); tests/common/*.c linked into all of them; built as
#                          build/tests/test_NAME whatever the folder
#   tests/SUITE/test_*.sh  shell tests (tests/cli/: the command; tests/examples/), run with
#                          build/qorient
#   bench/*.c              figure programs (accuracy_*.c run by `make figures`, docs/FIGURES.md)

CC      ?= cc
BUILD   ?= build
PKG_CONFIG ?= pkg-config

STD      := -std=c99
WARN     := -Wall -Wextra -Wpedantic -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
# float32 results must not depend on whether the compiler fuses a*b+c: contraction off everywhere.
FPFLAGS  := -ffp-contract=off
OPT      ?= -O2 -g
CORE_WARN := $(WARN) -Wdouble-promotion -Wcast-align -Wconversion -Wno-sign-conversion
CPPFLAGS_CORE := -Ilib/include

SAN      := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer

PKGS       := libmodbus libgpiod inih
PKG_CFLAGS := $(shell $(PKG_CONFIG) --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell $(PKG_CONFIG) --libs $(PKGS) 2>/dev/null)
CMOCKA_LIBS := $(shell $(PKG_CONFIG) --libs cmocka 2>/dev/null || echo -lcmocka)
PORT_DEFS  := -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE
# libgpiod v2 where installed (pkg-config says so), else the v1 API of Debian bookworm.
PORT_DEFS  += $(shell $(PKG_CONFIG) --atleast-version=2 libgpiod 2>/dev/null && echo -DQO_GPIOD_V2)

CORE_SRC  := $(sort $(wildcard lib/src/*.c))
FX_SRC    := $(sort $(wildcard lib/src/*_fx.c))
PORT_SRC  := $(sort $(wildcard ports/mock/*.c ports/linux/*.c))
CLI_SRC   := $(sort $(wildcard cli/*.c cli/linux/*.c))
# The suite folders, in the order `make test` runs them; tests/common, qemu, install and vm
# hold no test_*.c / test_*.sh of their own.
TEST_DIRS := core ports examples fuzz cli
TEST_SRC  := $(foreach d,$(TEST_DIRS),$(sort $(wildcard tests/$(d)/test_*.c)))
# tests/common/linux/: the Linux-only harness (pty relay); tests/common/*.c also builds for Cortex-M
TEST_COMMON := $(sort $(wildcard tests/common/*.c tests/common/linux/*.c))
TEST_SH   := $(foreach d,$(TEST_DIRS),$(sort $(wildcard tests/$(d)/test_*.sh)))

CORE_OBJ  := $(CORE_SRC:%.c=$(BUILD)/obj/%.o)
PORT_OBJ  := $(PORT_SRC:%.c=$(BUILD)/obj/%.o)
CLI_OBJ   := $(CLI_SRC:%.c=$(BUILD)/obj/%.o)

SCORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/san/%.o)
SPORT_OBJ := $(PORT_SRC:%.c=$(BUILD)/san/%.o)
SCOMMON_OBJ := $(TEST_COMMON:%.c=$(BUILD)/san/%.o)
# build/tests/test_NAME, flat: scripts and tools run the programs by name, not by suite.
TEST_BIN  := $(addprefix $(BUILD)/tests/,$(basename $(notdir $(TEST_SRC))))

.PHONY: all lib demo test test-run test-vm core-check clean tests-build figures figures-check parity parity-check
# Keep the sanitizer objects between runs (they are intermediates of the test pattern rule).
.SECONDARY:
all: $(BUILD)/libqorient.a $(BUILD)/libqorient_ports.a $(BUILD)/qorient

lib: $(BUILD)/libqorient.a

# ---- normal build ----
$(BUILD)/obj/lib/%.o: lib/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(CORE_WARN) $(FPFLAGS) $(OPT) $(CPPFLAGS_CORE) -c $< -o $@

$(BUILD)/obj/ports/%.o: ports/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(WARN) $(FPFLAGS) $(OPT) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports $(PKG_CFLAGS) -c $< -o $@

$(BUILD)/obj/cli/%.o: cli/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(WARN) $(FPFLAGS) $(OPT) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Icli $(PKG_CFLAGS) -c $< -o $@

$(BUILD)/libqorient.a: $(CORE_OBJ)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/libqorient_ports.a: $(PORT_OBJ)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/qorient: $(CLI_OBJ) $(BUILD)/libqorient_ports.a $(BUILD)/libqorient.a
	$(CC) $(OPT) -o $@ $(CLI_OBJ) $(BUILD)/libqorient_ports.a $(BUILD)/libqorient.a $(PKG_LIBS) -lm -pthread -lutil

# ---- sanitizer build for tests ----
$(BUILD)/san/lib/%.o: lib/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(CORE_WARN) $(FPFLAGS) -O1 -g $(SAN) $(CPPFLAGS_CORE) -c $< -o $@

$(BUILD)/san/ports/%.o: ports/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(WARN) $(FPFLAGS) -O1 -g $(SAN) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports $(PKG_CFLAGS) -c $< -o $@

$(BUILD)/san/cli/%.o: cli/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(WARN) $(FPFLAGS) -O1 -g $(SAN) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Icli $(PKG_CFLAGS) -c $< -o $@

# The command as the shell tests run it: the same sources under ASan + UBSan, so a bad input
# that reaches undefined behaviour in cli/ fails `make test`, not only a cmocka program.
SCLI_OBJ := $(CLI_SRC:%.c=$(BUILD)/san/%.o)
$(BUILD)/san/qorient: $(SCLI_OBJ) $(SPORT_OBJ) $(SCORE_OBJ)
	$(CC) $(SAN) -o $@ $^ $(PKG_LIBS) -lm -pthread -lutil

$(BUILD)/san/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(WARN) -Wno-double-promotion $(FPFLAGS) -O1 -g $(SAN) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Itests $(PKG_CFLAGS) -c $< -o $@

# One link rule per program: build/tests/test_NAME from build/san/tests/SUITE/test_NAME.o.
define TEST_LINK
$(BUILD)/tests/$(basename $(notdir $(1))): $(BUILD)/san/$(1:.c=.o) $$(SCOMMON_OBJ) $$(SPORT_OBJ) $$(SCORE_OBJ)
	@mkdir -p $$(@D)
	$$(CC) $$(SAN) -o $$@ $$^ $$(CMOCKA_LIBS) $$(PKG_LIBS) -lm -pthread -lutil
endef
$(foreach s,$(TEST_SRC),$(eval $(call TEST_LINK,$(s))))

# ---- figures: accuracy and speed programs in bench/ (optimised, no sanitizers) ----
# The bench programs link tests/common (the double references, the port harness) as an archive,
# optimised like them, so a program pulls only the objects it uses.
BENCH_SRC := $(sort $(wildcard bench/*.c))
BENCH_BIN := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%)
BCOMMON_OBJ := $(TEST_COMMON:%.c=$(BUILD)/bench-obj/%.o)
$(BUILD)/bench-obj/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(WARN) -Wno-double-promotion $(FPFLAGS) -O2 -g $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Itests $(PKG_CFLAGS) -c $< -o $@
$(BUILD)/libqorient_testcommon.a: $(BCOMMON_OBJ)
	rm -f $@ && ar rcs $@ $^
$(BUILD)/bench/%: bench/%.c $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient_ports.a $(BUILD)/libqorient.a
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) $(FPFLAGS) -O2 -g $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports -Itests $(PKG_CFLAGS) $< \
	    $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient_ports.a $(BUILD)/libqorient.a $(PKG_LIBS) -lm -pthread -lutil -o $@

# docs/FIGURES.md regenerated from the code (tools/figures.sh: one script per section in
# tools/figures/); figures-check regenerates the deterministic sections and fails when the
# committed page differs (CI).
figures: $(BENCH_BIN)
	@BUILD=$(BUILD) sh tools/figures.sh
	@sh tools/parity.sh
figures-check: $(BENCH_BIN)
	@BUILD=$(BUILD) sh tools/figures.sh --check

# docs/PARITY.md (concept x core) from the "parity" blocks at the top of the public headers;
# parity-check (CI) fails when the page is stale or a concept lacks a stated twin or gap.
parity:
	@sh tools/parity.sh
parity-check:
	@sh tools/parity.sh --check

tests-build: $(TEST_BIN) $(BUILD)/qorient $(BUILD)/san/qorient

# `make test` first installs missing Debian packages (tools/deps.sh: sudo when not root), then
# builds in a fresh make so pkg-config sees them. test-run: runs every cmocka program and every
# shell test; tests/run.sh prints the totals and fails on any failure.
test:
	@sh tools/deps.sh test
	@$(MAKE) --no-print-directory test-run

test-run: tests-build
	@QORIENT=$(BUILD)/san/qorient QORIENT_BUILD=$(BUILD) sh tests/run.sh $(TEST_BIN) -- $(TEST_SH)

# The GPIO sink against the kernel's gpio-sim in a QEMU VM (needs root-free qemu, downloads
# Debian's kernel packages once into build/vm).
test-vm: $(BUILD)/libqorient.a $(BUILD)/libqorient_ports.a
	BUILD=$(BUILD) sh tests/vm/run-gpiosim.sh

# The main job with no hardware: simulated drives, a planned arm move and a gimbal path
# streamed over loopback Modbus, and a picture of what was planned and sent, at the tick times.
demo:
	@sh tools/deps.sh demo
	@$(MAKE) --no-print-directory all
	@sh tools/demo.sh

# ---- core portability and hygiene (also run by .ci/run) ----
core-check:
	sh tools/core-check.sh

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
-include mk/install.mk
-include mk/bench.mk
-include mk/qemu.mk
-include mk/fuzz.mk
-include mk/motion.mk
