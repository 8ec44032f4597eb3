# mk/install.mk - installation, the installed-tree check, the shared core library and the host
# examples. Included at the end of the Makefile (`-include mk/install.mk`); uses its variables
# (CC, BUILD, STD, CORE_WARN, FPFLAGS, OPT, CORE_SRC, PKG_CONFIG, PKG_CFLAGS, PKG_LIBS, ...).
#
#   make install [PREFIX=/usr/local] [DESTDIR=/staging]
#       PREFIX/include/qorient/*.h               the portable core's public headers
#       PREFIX/include/qorient/ports/{linux,mock}/*.h   the Linux ports' headers (qorient-ports.pc
#                                                 puts that directory on the include path, so
#                                                 "linux/modbus_sink.h" is found as in the tree)
#       PREFIX/lib/libqorient.a                  core, static
#       PREFIX/lib/libqorient.so.X.Y.Z           core, shared (-fPIC), soname libqorient.so.X,
#       PREFIX/lib/libqorient.so.X, libqorient.so  symlinks
#       PREFIX/lib/libqorient_ports.a            Linux ports + mock sink, static only
#       PREFIX/lib/pkgconfig/qorient.pc          -I${includedir}; -L${libdir} -lqorient -lm
#       PREFIX/lib/pkgconfig/qorient-ports.pc    Requires: qorient libmodbus libgpiod inih
#       PREFIX/bin/qorient                       the command
#       PREFIX/share/man/man1/qorient.1          its manual page
#     BINDIR, LIBDIR, INCLUDEDIR, MANDIR, PKGCONFIGDIR override the single directories.
#   make uninstall [PREFIX=...] [DESTDIR=...]   removes exactly those files
#   make install-check  installs into a temporary DESTDIR (build/install-check/root), checks the
#                       file list, the soname and the exported symbols, compiles every installed
#                       header alone, then builds tests/install/consumer.c through pkg-config
#                       (PKG_CONFIG_PATH and PKG_CONFIG_SYSROOT_DIR pointing into the tree)
#                       statically and against the shared library, and
#                       tests/install/consumer_ports.c against qorient-ports, runs them, and
#                       finally uninstalls and checks that no file is left
#   make shared         build/libqorient.so.X.Y.Z and its links in build/ only
#   make examples       the host examples (examples/pi) into build/examples; the MCU examples
#                       are compiled by tools/check-examples.sh (arm-none-eabi-gcc)

PREFIX       ?= /usr/local
DESTDIR      ?=
BINDIR       ?= $(PREFIX)/bin
LIBDIR       ?= $(PREFIX)/lib
INCLUDEDIR   ?= $(PREFIX)/include
MANDIR       ?= $(PREFIX)/share/man
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
INSTALL      ?= install

# The one version: lib/include/qorient/version.h (library.json and CMakeLists.txt repeat it;
# install-check fails when they disagree).
QO_VERSION := $(shell sed -n 's/^\#define QO_VERSION_STRING "\(.*\)"/\1/p' lib/include/qorient/version.h)
QO_SOMAJOR := $(firstword $(subst ., ,$(QO_VERSION)))
QO_SONAME  := libqorient.so.$(QO_SOMAJOR)
QO_SOFILE  := libqorient.so.$(QO_VERSION)

CORE_HDR  := $(sort $(wildcard lib/include/qorient/*.h))
LINUX_HDR := $(sort $(wildcard ports/linux/*.h))
MOCK_HDR  := $(sort $(wildcard ports/mock/*.h))
MANPAGE   := cli/qorient.1

.PHONY: install uninstall install-check shared examples

# ---- shared core library: the core compiled again with -fPIC ----
PIC_OBJ := $(CORE_SRC:%.c=$(BUILD)/pic/%.o)

$(BUILD)/pic/lib/%.o: lib/%.c
	@mkdir -p $(@D)
	$(CC) -MMD -MP $(STD) $(CORE_WARN) $(FPFLAGS) $(OPT) -fPIC $(CPPFLAGS_CORE) -c $< -o $@

# -Wl,--no-undefined: every symbol the core uses is in libm or libc (checked at link time).
$(BUILD)/$(QO_SOFILE): $(PIC_OBJ)
	@mkdir -p $(@D)
	$(CC) -shared -Wl,-soname,$(QO_SONAME) -Wl,--no-undefined -o $@ $(PIC_OBJ) -lm

$(BUILD)/$(QO_SONAME) $(BUILD)/libqorient.so: $(BUILD)/$(QO_SOFILE)
	ln -sf $(QO_SOFILE) $(BUILD)/$(QO_SONAME)
	ln -sf $(QO_SONAME) $(BUILD)/libqorient.so

shared: $(BUILD)/$(QO_SOFILE) $(BUILD)/$(QO_SONAME) $(BUILD)/libqorient.so

# ---- pkg-config files, written for the PREFIX/LIBDIR/INCLUDEDIR of this install ----
# $(1) = output file. Paths below PREFIX are written relative to ${prefix}.
qo_pcdir = $(patsubst $(PREFIX)/%,$${prefix}/%,$(1))
define qo_write_pc_core
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$(call qo_pcdir,$(LIBDIR))' \
	    'includedir=$(call qo_pcdir,$(INCLUDEDIR))' '' 'Name: qorient' \
	    'Description: Quaternion orientation, Euler angles, interpolation and joint trajectories: the portable C99 core (float32 and fixed point)' \
	    'Version: $(QO_VERSION)' 'Cflags: -I$${includedir}' 'Libs: -L$${libdir} -lqorient -lm' > $(1)
endef
define qo_write_pc_ports
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$(call qo_pcdir,$(LIBDIR))' \
	    'includedir=$(call qo_pcdir,$(INCLUDEDIR))' '' 'Name: qorient-ports' \
	    'Description: qorient Linux ports: Modbus RTU/TCP and GPIO step/dir sinks, periodic streamer, simulated drive bank, mock sink (static library)' \
	    'Version: $(QO_VERSION)' 'Requires: qorient libmodbus libgpiod inih' \
	    'Cflags: -I$${includedir}/qorient/ports' 'Libs: -L$${libdir} -lqorient_ports -pthread' > $(1)
endef

# ---- install / uninstall ($(1) = DESTDIR) ----
define qo_install_to
	$(INSTALL) -d $(1)$(BINDIR) $(1)$(LIBDIR) $(1)$(PKGCONFIGDIR) $(1)$(MANDIR)/man1 \
	    $(1)$(INCLUDEDIR)/qorient/ports/linux $(1)$(INCLUDEDIR)/qorient/ports/mock
	$(INSTALL) -m 644 $(CORE_HDR) $(1)$(INCLUDEDIR)/qorient/
	$(INSTALL) -m 644 $(LINUX_HDR) $(1)$(INCLUDEDIR)/qorient/ports/linux/
	$(INSTALL) -m 644 $(MOCK_HDR) $(1)$(INCLUDEDIR)/qorient/ports/mock/
	$(INSTALL) -m 644 $(BUILD)/libqorient.a $(BUILD)/libqorient_ports.a $(1)$(LIBDIR)/
	$(INSTALL) -m 755 $(BUILD)/$(QO_SOFILE) $(1)$(LIBDIR)/
	ln -sf $(QO_SOFILE) $(1)$(LIBDIR)/$(QO_SONAME)
	ln -sf $(QO_SONAME) $(1)$(LIBDIR)/libqorient.so
	$(INSTALL) -m 755 $(BUILD)/qorient $(1)$(BINDIR)/
	$(INSTALL) -m 644 $(MANPAGE) $(1)$(MANDIR)/man1/
	$(call qo_write_pc_core,$(1)$(PKGCONFIGDIR)/qorient.pc)
	$(call qo_write_pc_ports,$(1)$(PKGCONFIGDIR)/qorient-ports.pc)
	chmod 644 $(1)$(PKGCONFIGDIR)/qorient.pc $(1)$(PKGCONFIGDIR)/qorient-ports.pc
endef

install: all shared
	$(call qo_install_to,$(DESTDIR))

# Only our files ($(1) = DESTDIR); the standard directories stay.
define qo_uninstall_from
	rm -f $(1)$(BINDIR)/qorient $(1)$(MANDIR)/man1/qorient.1 \
	    $(1)$(LIBDIR)/libqorient.a $(1)$(LIBDIR)/libqorient_ports.a \
	    $(1)$(LIBDIR)/$(QO_SOFILE) $(1)$(LIBDIR)/$(QO_SONAME) $(1)$(LIBDIR)/libqorient.so \
	    $(1)$(PKGCONFIGDIR)/qorient.pc $(1)$(PKGCONFIGDIR)/qorient-ports.pc
	rm -rf $(1)$(INCLUDEDIR)/qorient
endef

uninstall:
	$(call qo_uninstall_from,$(DESTDIR))

# ---- install-check ----
QO_CHK      := $(BUILD)/install-check
QO_CHK_ROOT  = $(abspath $(QO_CHK))/root
# pkgconf prepends PKG_CONFIG_SYSROOT_DIR to the -I/-L of EVERY package, the system's libmodbus
# too, so the ports consumer adds the system packages' own flags again without it.
QO_CHK_PC    = PKG_CONFIG_SYSROOT_DIR=$(QO_CHK_ROOT) PKG_CONFIG_PATH=$(QO_CHK_ROOT)$(PKGCONFIGDIR) $(PKG_CONFIG)
QO_CHK_CC    = $(CC) -std=c99 -Wall -Wextra -Wpedantic -Werror

install-check: all shared
	rm -rf $(QO_CHK)
	@mkdir -p $(QO_CHK)
	$(call qo_install_to,$(QO_CHK_ROOT))
	@echo "install-check: installed into $(QO_CHK_ROOT) (PREFIX=$(PREFIX)):"
	@cd $(QO_CHK_ROOT) && find . -type f -o -type l | sort | sed 's/^\./  /'
	@for f in $(BINDIR)/qorient $(MANDIR)/man1/qorient.1 $(LIBDIR)/libqorient.a \
	    $(LIBDIR)/libqorient_ports.a $(LIBDIR)/$(QO_SOFILE) $(PKGCONFIGDIR)/qorient.pc \
	    $(PKGCONFIGDIR)/qorient-ports.pc $(INCLUDEDIR)/qorient/qorient.h \
	    $(INCLUDEDIR)/qorient/ports/linux/modbus_sink.h $(INCLUDEDIR)/qorient/ports/mock/mock_sink.h; do \
	    test -f $(QO_CHK_ROOT)$$f || { echo "install-check: FAIL: $$f not installed"; exit 1; }; done
	@test "$$(readlink $(QO_CHK_ROOT)$(LIBDIR)/$(QO_SONAME))" = $(QO_SOFILE) && \
	    test "$$(readlink $(QO_CHK_ROOT)$(LIBDIR)/libqorient.so)" = $(QO_SONAME) || \
	    { echo "install-check: FAIL: shared library symlinks"; exit 1; }
	@readelf -d $(QO_CHK_ROOT)$(LIBDIR)/$(QO_SOFILE) | grep -q 'SONAME.*\[$(QO_SONAME)\]' || \
	    { echo "install-check: FAIL: soname is not $(QO_SONAME)"; exit 1; }
	@bad=$$(nm -D --defined-only $(QO_CHK_ROOT)$(LIBDIR)/$(QO_SOFILE) | awk '$$2 ~ /[TDRB]/ && $$3 !~ /^qo_/ { print $$3 }'); \
	    test -z "$$bad" || { echo "install-check: FAIL: exported without the qo_ prefix: $$bad"; exit 1; }; \
	    echo "install-check: $(QO_SOFILE): soname $(QO_SONAME), $$(nm -D --defined-only $(QO_CHK_ROOT)$(LIBDIR)/$(QO_SOFILE) | grep -c ' T qo_') functions, all qo_*"
	@grep -q '"version": "$(QO_VERSION)"' library.json && grep -q 'VERSION $(QO_VERSION) ' CMakeLists.txt || \
	    { echo "install-check: FAIL: library.json / CMakeLists.txt version is not $(QO_VERSION)"; exit 1; }
	@test "$$($(QO_CHK_PC) --modversion qorient)" = $(QO_VERSION) && \
	    test "$$($(QO_CHK_PC) --print-requires qorient-ports | tr '\n' ' ')" = "qorient libmodbus libgpiod inih " || \
	    { echo "install-check: FAIL: pkg-config metadata"; exit 1; }
	@echo "install-check: pkg-config: qorient $$($(QO_CHK_PC) --modversion qorient): $$($(QO_CHK_PC) --cflags --libs qorient)"
	@n=0; for h in $(notdir $(CORE_HDR)); do \
	    printf '#include "qorient/%s"\n#include "qorient/%s"\nint qo_probe(void);\nint qo_probe(void) { return 0; }\n' $$h $$h > $(QO_CHK)/hdr.c; \
	    $(QO_CHK_CC) -Wconversion -Wdouble-promotion -Wshadow -Wstrict-prototypes $$($(QO_CHK_PC) --cflags qorient) -c $(QO_CHK)/hdr.c -o $(QO_CHK)/hdr.o || \
	    { echo "install-check: FAIL: installed qorient/$$h does not compile on its own"; exit 1; }; n=$$((n + 1)); done; \
	    echo "install-check: $$n installed core headers each compile alone (twice included)"
	$(QO_CHK_CC) $$($(QO_CHK_PC) --cflags qorient) tests/install/consumer.c -o $(QO_CHK)/consumer_static \
	    $$($(QO_CHK_PC) --libs qorient | sed 's/-lqorient\b/-Wl,-Bstatic -lqorient -Wl,-Bdynamic/')
	$(QO_CHK_CC) $$($(QO_CHK_PC) --cflags qorient) tests/install/consumer.c -o $(QO_CHK)/consumer_shared \
	    $$($(QO_CHK_PC) --libs qorient)
	@! readelf -d $(QO_CHK)/consumer_static | grep -q 'NEEDED.*libqorient' || \
	    { echo "install-check: FAIL: the static consumer needs libqorient.so"; exit 1; }
	@readelf -d $(QO_CHK)/consumer_shared | grep -q 'NEEDED.*\[$(QO_SONAME)\]' || \
	    { echo "install-check: FAIL: the shared consumer does not need $(QO_SONAME)"; exit 1; }
	$(QO_CHK)/consumer_static
	LD_LIBRARY_PATH=$(QO_CHK_ROOT)$(LIBDIR) $(QO_CHK)/consumer_shared
	@LD_LIBRARY_PATH=$(QO_CHK_ROOT)$(LIBDIR) ldd $(QO_CHK)/consumer_shared | grep -q '$(QO_SONAME) => $(QO_CHK_ROOT)$(LIBDIR)/$(QO_SONAME)' || \
	    { echo "install-check: FAIL: the shared consumer did not load the installed $(QO_SONAME)"; exit 1; }
	$(CC) -std=c99 -Wall -Wextra -Wpedantic -Werror -D_POSIX_C_SOURCE=200809L \
	    $$($(QO_CHK_PC) --cflags qorient-ports) $$($(PKG_CONFIG) --cflags libmodbus libgpiod inih) \
	    tests/install/consumer_ports.c -o $(QO_CHK)/consumer_ports \
	    $$($(QO_CHK_PC) --libs qorient-ports | sed 's/-lqorient\b/-Wl,-Bstatic -lqorient -Wl,-Bdynamic/') \
	    $$($(PKG_CONFIG) --libs libmodbus libgpiod inih)
	$(QO_CHK)/consumer_ports
	@if command -v groff >/dev/null 2>&1; then \
	    w=$$(groff -man -Tutf8 -ww -z $(QO_CHK_ROOT)$(MANDIR)/man1/qorient.1 2>&1); \
	    test -z "$$w" || { echo "install-check: FAIL: groff -man -ww: $$w"; exit 1; }; \
	    echo "install-check: man1/qorient.1 formats without a warning (groff -man -ww)"; \
	 else echo "install-check: groff not installed: man1/qorient.1 not formatted"; fi
	$(QO_CHK_ROOT)$(BINDIR)/qorient version
	$(call qo_uninstall_from,$(QO_CHK_ROOT))
	@left=$$(find $(QO_CHK_ROOT) -type f -o -type l); test -z "$$left" || \
	    { echo "install-check: FAIL: uninstall left: $$left"; exit 1; }
	@echo "install-check: uninstall removed every installed file"
	@echo "install-check: all ok"

# ---- host examples ----
examples: $(BUILD)/examples/stream_modbus

$(BUILD)/examples/stream_modbus: examples/pi/stream_modbus.c $(BUILD)/libqorient_ports.a $(BUILD)/libqorient.a
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) $(FPFLAGS) $(OPT) $(PORT_DEFS) $(CPPFLAGS_CORE) -Iports $(PKG_CFLAGS) $< \
	    $(BUILD)/libqorient_ports.a $(BUILD)/libqorient.a $(PKG_LIBS) -lm -pthread -o $@

