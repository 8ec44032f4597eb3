#!/bin/sh
# Figures section "sizes": flash and stack of every core module on Cortex-M0+, M4F and M7
# (tools/size-report.sh; deterministic for one arm-none-eabi-gcc version).
set -eu
sh tools/size-report.sh
