# Tests on emulated targets (included by the top Makefile with `-include mk/qemu.mk`):
#   make test-qemu                       core tests on Cortex-M0/M4F/M7 (qemu-system-arm,
#                                        semihosting) and the whole host suite for Raspberry Pi
#                                        aarch64 / armhf under qemu-user; see tools/test-qemu.sh
#   make test-qemu QEMU_TARGETS="m4f aarch64"    a subset
# Exit status 77 means a prerequisite could not be installed (not a test failure).
.PHONY: test-qemu
test-qemu:
	sh tools/test-qemu.sh $(QEMU_TARGETS)
