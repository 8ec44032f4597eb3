# mk/motion.mk - the motion planner against its independent reference, at scale. Included by
# the Makefile with `-include mk/motion.mk`.
#
#   make check-motion        1,000,000 random joints per sync mode (NONE, TIME, PHASE,
#                            TIME_IF_NECESSARY: 142,858 random 7-joint plans each, with moving
#                            starts, asymmetric limits and moving target states),
#                            tests/core/test_motion_oracle.c optimised, no sanitizers (make test runs
#                            the same program with 10,500 per mode)
#   make check-motion-long   10,000,000 per sync mode
# QO_MOTION_ORACLE_FILTER=test_oracle_time (a cmocka name pattern) runs one part, e.g. the modes
# in parallel on a machine with cores to spare. QO_MOTION_ORACLE_FIRST=n QO_MOTION_ORACLE_NUM=m
# run only groups n..n+m-1 of each mode (the same cases as the full run: a failure reproduced
# by its case number). test_oracle_wide runs limits log-uniform over the whole accepted range
# [1e-3, 1e9] with vmin/vmax, amin/amax ratios over [1/20, 20]; test_oracle_stress asymmetric
# limits and moving target states with nonzero accelerations on every joint (200,000 joints
# each in NONE, TIME, TIME_IF_NECESSARY).
#
# Each prints one line per mode "sync N: G groups of 7 joints, F failures" and fails on any
# failure (a joint or plan more than 0.1 % slower or faster than the reference, a limit
# exceeded by more than 1e-5 relative, a jump across a re-plan); the first 20 are printed with
# their inputs.
.PHONY: check-motion check-motion-long
MOTION_CHECK_SRC := tests/core/test_motion_oracle.c tests/common/motion_ref.c tests/common/ref.c

$(BUILD)/check/test_motion_oracle_%: $(MOTION_CHECK_SRC) $(BUILD)/libqorient.a
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) -Wno-double-promotion $(FPFLAGS) -O2 -g $(CPPFLAGS_CORE) -Itests \
	    -DQO_MOTION_ORACLE_JOINTS=$* $(MOTION_CHECK_SRC) $(BUILD)/libqorient.a $(CMOCKA_LIBS) -lm -o $@

check-motion: $(BUILD)/check/test_motion_oracle_1000000
	$<

check-motion-long: $(BUILD)/check/test_motion_oracle_10000000
	$<

# make test builds both scales (not runs them), so neither can stop compiling unseen: the 10M
# build once overflowed an int in ORACLE_GROUPS and nothing noticed.
tests-build: $(BUILD)/check/test_motion_oracle_1000000 $(BUILD)/check/test_motion_oracle_10000000

# make bench-motion: planning time against the planner of commit 9bf587d, same cases, one run
# (bench/motion/compare.c). The old source is taken from git and renamed into build/motion_old/.
.PHONY: bench-motion
MOTION_OLD := $(BUILD)/motion_old
MOTION_OLD_REV := 9bf587d
$(MOTION_OLD)/motion_old.c:
	@mkdir -p $(MOTION_OLD)/qoold
	git show $(MOTION_OLD_REV):lib/include/qorient/motion.h | sed 's/qo_motion_/qoold_motion_/g; s/QO_MOTION_/QOOLD_MOTION_/g; s/QORIENT_MOTION_H/QOOLD_MOTION_H/; s|qorient/motion_fx.h|qoold/motion_fx.h|' > $(MOTION_OLD)/qoold/motion.h
	git show $(MOTION_OLD_REV):lib/include/qorient/motion_fx.h | sed 's/qo_motion_/qoold_motion_/g; s/QO_MOTION_/QOOLD_MOTION_/g; s/QORIENT_MOTION_FX_H/QOOLD_MOTION_FX_H/' > $(MOTION_OLD)/qoold/motion_fx.h
	git show $(MOTION_OLD_REV):lib/src/motion.c | sed 's/qo_motion_/qoold_motion_/g; s/QO_MOTION_/QOOLD_MOTION_/g; s|qorient/motion.h|qoold/motion.h|' > $@

$(BUILD)/bench/motion_compare: bench/motion/compare.c $(MOTION_OLD)/motion_old.c $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient.a
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) $(FPFLAGS) -O2 -g $(PORT_DEFS) $(CPPFLAGS_CORE) -I$(MOTION_OLD) -Itests bench/motion/compare.c \
	    $(MOTION_OLD)/motion_old.c $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient.a -lm -o $@

bench-motion: $(BUILD)/bench/motion_compare
	$< $(MOTION_CASES)

# make bench-motion-ir: the same cases, instructions per plan under callgrind (deterministic for
# one compiler: the speed ratio without the shared machine's noise). Needs valgrind (its
# callgrind.h marks each plan as one dump part); bench/motion/ir.sh summarises the parts.
.PHONY: bench-motion-ir
$(BUILD)/bench/motion_ir: bench/motion/compare.c $(MOTION_OLD)/motion_old.c $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient.a
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) $(FPFLAGS) -O2 -g -DQO_BENCH_CALLGRIND $(PORT_DEFS) $(CPPFLAGS_CORE) -I$(MOTION_OLD) -Itests bench/motion/compare.c \
	    $(MOTION_OLD)/motion_old.c $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient.a -lm -o $@

bench-motion-ir: $(BUILD)/bench/motion_ir
	BUILD=$(BUILD) sh bench/motion/ir.sh $(MOTION_CASES)

# make motion-digest: digests of the plans on fixed-seed random cases (bench/motion/digest.c):
# a speed change that keeps every plan bit for bit prints the same lines before and after.
.PHONY: motion-digest
$(BUILD)/bench/motion_digest: bench/motion/digest.c $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient.a
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) $(FPFLAGS) -O2 -g $(CPPFLAGS_CORE) -Itests bench/motion/digest.c \
	    $(BUILD)/libqorient_testcommon.a $(BUILD)/libqorient.a -lm -o $@

motion-digest: $(BUILD)/bench/motion_digest
	$< $(MOTION_CASES)
