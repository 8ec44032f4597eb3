# mk/bench.mk - `make bench` (host comparison against cglm, Eigen, libfixmath) and
# `make bench-qemu` (Cortex-M0 / M4F instruction counts under QEMU). Included by the Makefile
# with `-include mk/bench.mk`. Everything is done by tools/bench.sh, which writes its tables and
# gnuplot plots to build/bench-results/ (a working run, not committed: the published figures
# are docs/FIGURES.md's, `make figures`; see docs/BENCHMARKS.md).
.PHONY: bench bench-qemu bench-host
bench:
	BUILD=$(BUILD) sh tools/bench.sh all
bench-host:
	BUILD=$(BUILD) sh tools/bench.sh host
bench-qemu:
	BUILD=$(BUILD) sh tools/bench.sh qemu
