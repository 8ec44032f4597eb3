# Builds the core's cmocka tests for one emulated Cortex-M target, against the bare-metal cmocka
# shim (tests/qemu/cmocka.h), newlib with semihosting (rdimon) and tests/qemu/startup.c + cm.ld.
# Called by tests/qemu/run-target.sh (not by the top Makefile):
#
#   make -f tests/qemu/cortexm.mk QT=m0|m4f|m7 TESTS="test_quat test_euler ..." [-j2]
#
# Outputs: build/qemu-QT/TEST.elf (one per test, flat whatever its tests/SUITE/ folder), build/qemu-QT/selftest.elf (the shim's own test),
# build/qemu-QT/libqorient.a
# The core is built with the project's core flags and -Werror; the test sources with the host
# test flags minus -Werror (their warnings under newlib's types are reported, not fatal).

QT    ?= m4f
TESTS ?=
CROSS ?= arm-none-eabi-
CC    := $(CROSS)gcc
AR    := $(CROSS)ar
OUT   := build/qemu-$(QT)

ifeq ($(QT),m0)
CPU := -mcpu=cortex-m0 -mthumb -mfloat-abi=soft
MEM := -Wl,--defsym=__flash_size=256K -Wl,--defsym=__ram_size=16K
else ifeq ($(QT),m4f)
CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
MEM := -Wl,--defsym=__flash_size=4M -Wl,--defsym=__ram_size=4M
else ifeq ($(QT),m7)
CPU := -mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-d16
MEM := -Wl,--defsym=__flash_size=4M -Wl,--defsym=__ram_size=4M
else
$(error QT must be m0, m4f or m7)
endif

STD       := -std=c99
WARN      := -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes
CORE_WARN := $(WARN) -Werror -Wdouble-promotion -Wcast-align -Wconversion -Wno-sign-conversion
FPFLAGS   := -ffp-contract=off
OPT       := -O2 -g -ffunction-sections -fdata-sections
SPECS     := --specs=rdimon.specs
# As on the host (the top Makefile builds tests with these): M_PI and friends from newlib math.h.
TEST_DEFS := -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE
# The motion tests' references are double precision: software double on these cores runs them
# about a thousand times slower than the host, so a sample of the host's random cases (the same
# seeds, the first ORACLE_JOINTS joints per sync mode of test_motion_oracle, the first
# MOVING_CASES starts of test_motion's test_scurve_moving) checks the target's float32 planner
# here; the host runs them all (10,500 and 240), the Linux targets a tenth of the oracle's.
ORACLE_JOINTS ?= 40
MOVING_CASES ?= 60
TEST_DEFS += -DQO_MOTION_ORACLE_JOINTS=$(ORACLE_JOINTS) -DQO_MOTION_MOVING_CASES=$(MOVING_CASES)

CORE_SRC   := $(sort $(wildcard lib/src/*.c))
COMMON_SRC := $(sort $(wildcard tests/common/*.c))
CORE_OBJ   := $(CORE_SRC:%.c=$(OUT)/obj/%.o)
COMMON_OBJ := $(COMMON_SRC:%.c=$(OUT)/obj/%.o)
SHIM_OBJ   := $(OUT)/obj/tests/qemu/cmocka.o $(OUT)/obj/tests/qemu/startup.o
ELF        := $(TESTS:%=$(OUT)/%.elf) $(OUT)/selftest.elf

.PHONY: all
.SECONDARY:
all: $(ELF)

$(OUT)/obj/lib/%.o: lib/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(CPU) $(STD) $(CORE_WARN) $(FPFLAGS) $(OPT) -Ilib/include -c $< -o $@

$(OUT)/obj/tests/qemu/%.o: tests/qemu/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(CPU) $(STD) $(WARN) -Werror $(FPFLAGS) $(OPT) -isystem tests/qemu -c $< -o $@

# Test sources: the shim is found as <cmocka.h> first, as a system header like the real one.
$(OUT)/obj/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(CPU) $(STD) $(WARN) -Wno-double-promotion $(FPFLAGS) $(OPT) $(TEST_DEFS) \
	    -isystem tests/qemu -Ilib/include -Itests -c $< -o $@ 2>$@.warn; rc=$$?; \
	    cat $@.warn >&2; exit $$rc

$(OUT)/libqorient.a: $(CORE_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

# TESTS names programs (test_quat); each is found in its suite folder (tests/core/test_quat.c,
# tests/examples/test_example_mcu.c, ...). A name with no source is left to fail as before.
define TEST_ELF
$(OUT)/$(1).elf: $(OUT)/obj/$(patsubst %.c,%.o,$(or $(firstword $(wildcard tests/*/$(1).c)),tests/$(1).c)) $$(COMMON_OBJ) $$(SHIM_OBJ) $$(OUT)/libqorient.a tests/qemu/cm.ld
	$$(CC) $$(CPU) $$(SPECS) -T tests/qemu/cm.ld $$(MEM) -Wl,--gc-sections -o $$@ \
	    $$< $$(COMMON_OBJ) $$(SHIM_OBJ) $$(OUT)/libqorient.a -lm
endef
$(foreach t,$(TESTS),$(eval $(call TEST_ELF,$(t))))

# The shim's own test (tests/qemu/selftest.c): run first, must report exactly what it expects.
$(OUT)/selftest.elf: $(OUT)/obj/tests/qemu/selftest.o $(SHIM_OBJ) tests/qemu/cm.ld
	$(CC) $(CPU) $(SPECS) -T tests/qemu/cm.ld $(MEM) -Wl,--gc-sections -o $@ $< $(SHIM_OBJ) -lm

-include $(shell find $(OUT) -name '*.d' 2>/dev/null)
