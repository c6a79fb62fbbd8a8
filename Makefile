# archquake Makefile.  Overridable: CC CFLAGS LDFLAGS PREFIX DESTDIR.
# Targets: all check ci bench install uninstall clean deps deps-dev fuzz mutate mpi check-mpi
CC      ?= cc
CFLAGS  ?= -O2 -g
LDFLAGS ?=
PREFIX  ?= /usr/local
DESTDIR ?=
FUZZ_SECONDS ?= 60

PKGS      := gsl fftw3 hdf5 inih mseed libxml-2.0 plplot nettle libxxhash
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
# Opened on first use, not linked (src/util/lazylib.h): PLplot for figures,
# libxml2 for StationXML, libmseed for miniSEED, GLPK for the mechanism
# search (below).  Linked,
# they and the libraries they need (ICU, libstdc++, freetype, GMP,
# SuiteSparse...) were loaded by every command: `archquake --version` took
# 3.6x /bin/true.  Their sonames come from the libraries the build would
# have linked.
LAZY_PKGS := plplot libxml-2.0 mseed
# HDF5 is linked from its static archive when one is installed (Debian's
# libhdf5-dev ships it): the shared library brings in ~45 more (curl, TLS,
# Kerberos, LDAP, for an S3 driver archquake never uses) whose loading and
# lazy binding cost every run about 10 ms of CPU.  HDF5_STATIC=0: shared.
HDF5_STATIC ?= 1
HDF5_DIRS  := $(patsubst -L%,%,$(filter -L%,$(shell pkg-config --libs-only-L hdf5 2>/dev/null)))
HDF5_A     := $(if $(filter 1,$(HDF5_STATIC)),$(firstword $(wildcard $(addsuffix /libhdf5.a,$(HDF5_DIRS)))))
HDF5_LIBS   = $(if $(HDF5_A),$(HDF5_A) -lsz -laec -lz -ldl,$(shell pkg-config --libs hdf5 2>/dev/null))
PKG_LIBS   = $(shell pkg-config --libs $(filter-out hdf5 $(LAZY_PKGS),$(PKGS)) 2>/dev/null) $(HDF5_LIBS) -ldl
# The other libraries are linked from their static archives too, where the
# Debian -dev package ships one (libmseed-dev ships none: libmseed is
# opened on first use; libm and libc stay shared): each shared library costs every command its mapping, symbol
# lookup, relocation and page faults, and the nine of these made
# `archquake --version` take 2.3x as long as /bin/true to start (1.5x
# static).  Only the members archquake calls are linked.  STATIC_LIBS=0:
# shared (then rebuild from `make clean`).
STATIC_LIBS ?= 1
STATIC_NAMES := gsl gslcblas fftw3 inih nettle xxhash sz aec z
STATIC_A := $(if $(filter 1,$(STATIC_LIBS)),$(foreach n,$(STATIC_NAMES),$(abspath $(filter /%,$(shell \
              $(CC) -print-file-name=lib$(n).a)))))
# The words of a link line, each -lNAME replaced by NAME's archive if in STATIC_A.
static_libs = $(foreach w,$(1),$(or $(and $(filter -l%,$(w)),$(filter %/lib$(w:-l%=%).a,$(STATIC_A))),$(w)))
AQ_CFLAGS  = -std=c11 -Wall -Wextra -D_POSIX_C_SOURCE=200809L -Isrc -Ibuild $(PKG_CFLAGS)
# zlib: the tests decode the browser's PNG screenshots (also HDF5's own).
# GLPK (no pkg-config file), the mechanism search's linear programs, is
# opened on first use too (src/arch/glpk_lazy.c): libglpk-dev for its header.
AQ_LIBS    = $(call static_libs,$(PKG_LIBS) -lz -lpthread -lm)
SAN        = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined

LIB_SRC   := $(sort $(wildcard src/*.c src/*/*.c))
LIB_SRC   := $(filter-out src/main.c src/app/mpi.c,$(LIB_SRC))
TEST_SRC  := $(sort $(wildcard tests/*.c))
BENCH_SRC := $(sort $(wildcard bench/bench_*.c))
FUZZ_SRC  := $(sort $(wildcard fuzz/fuzz_*.c))
HDRS      := $(wildcard src/*.h src/*/*.h tests/*.h bench/*.h)

# Each object depends on the headers it includes, as the compiler lists
# them (-MMD: build/.../X.d beside X.o, read below; -MP: a header removed
# is no error), so a header's change rebuilds only what includes it.
DEPFLAGS = -MMD -MP
REL_OBJ := $(LIB_SRC:%.c=build/rel/%.o)
SAN_OBJ := $(LIB_SRC:%.c=build/san/%.o)
TEST_OBJ := $(TEST_SRC:%.c=build/san/%.o)
MUT_OBJ  := $(LIB_SRC:%.c=build/mut/%.o) $(TEST_SRC:%.c=build/mut/%.o)

.PHONY: all check ci bench install uninstall clean deps deps-dev print-deps print-deps-dev fuzz mutate mpi check-mpi FORCE
all: archquake build/archquake.1

# The exact build, embedded in results files (src/app/version.c): `git
# describe`, or the version alone outside a git checkout.  The header is
# rewritten only when the description changes.
AQ_DESCRIBE := $(shell git describe --always --dirty 2>/dev/null)
build/describe.h: FORCE
	@mkdir -p build
	@printf '#define AQ_BUILD_SUFFIX "%s"\n' '$(if $(AQ_DESCRIBE), ($(AQ_DESCRIBE)))' > $@.new
	@cmp -s $@.new $@ && rm -f $@.new || mv -f $@.new $@
build/rel/src/app/version.o build/san/src/app/version.o build/mut/src/app/version.o build/fz/src/app/version.o: build/describe.h

# Where installed arches are looked for (src/app/opt_arch.c), from PREFIX;
# rewritten only when PREFIX changes.
build/datadir.h: FORCE
	@mkdir -p build
	@printf '#define AQ_DATADIR "%s"\n' '$(PREFIX)/share/archquake' > $@.new
	@cmp -s $@.new $@ && rm -f $@.new || mv -f $@.new $@
build/rel/src/app/opt_arch.o build/san/src/app/opt_arch.o build/mut/src/app/opt_arch.o build/fz/src/app/opt_arch.o: build/datadir.h

# The FFTW_ESTIMATE wisdom of every filter length (tools/fftw_wisdom.c): a
# process imports its lengths' instead of planning them (src/signal/filter.c).
build/fftw_wisdom.h: tools/fftw_wisdom.c
	@mkdir -p build
	$(CC) $(AQ_CFLAGS) $(CFLAGS) $(LDFLAGS) -o build/fftw_wisdom_gen $< $(AQ_LIBS)
	./build/fftw_wisdom_gen $@
build/rel/src/signal/filter.o build/san/src/signal/filter.o build/mut/src/signal/filter.o build/fz/src/signal/filter.o: build/fftw_wisdom.h

# The sonames of the libraries opened on first use (src/util/lazylib.h),
# read from the shared libraries the compiler would link; rewritten only
# when they change.
lazy_soname = $(or $(shell objdump -p "$$($(CC) -print-file-name=lib$(1).so)" 2>/dev/null | \
                 sed -n 's/^ *SONAME *//p'),lib$(1).so)
build/lazylib_sonames.h: FORCE
	@mkdir -p build
	@printf '#define AQ_PLPLOT_SONAME "%s"\n#define AQ_XML2_SONAME "%s"\n#define AQ_GLPK_SONAME "%s"\n#define AQ_MSEED_SONAME "%s"\n' \
	  '$(call lazy_soname,plplot)' '$(call lazy_soname,xml2)' '$(call lazy_soname,glpk)' \
	  '$(call lazy_soname,mseed)' > $@.new
	@printf '#define AQ_SICONOS_SONAME "%s"\n' '$(call lazy_soname,siconos_numerics)' >> $@.new
	@cmp -s $@.new $@ && rm -f $@.new || mv -f $@.new $@
$(foreach d,rel san mut fz,build/$(d)/src/plot/plplot_lazy.o build/$(d)/src/io/xml_lazy.o build/$(d)/src/arch/glpk_lazy.o build/$(d)/src/io/mseed_lazy.o): build/lazylib_sonames.h
# Siconos Numerics (the block model's contact problems, src/blocks/siconos_lazy.c),
# opened on first use too; its headers live under /usr/include/siconos.
SICONOS_CFLAGS := -I/usr/include/siconos/numerics -I/usr/include/siconos
$(foreach d,rel san mut fz,build/$(d)/src/blocks/siconos_lazy.o): build/lazylib_sonames.h
$(foreach d,rel san mut fz,build/$(d)/src/blocks/siconos_lazy.o): AQ_CFLAGS += $(SICONOS_CFLAGS)
# tests that name a library by its soname read it too
$(TEST_OBJ) $(TEST_SRC:%.c=build/mut/%.o): build/lazylib_sonames.h

archquake: build/rel/src/main.o $(REL_OBJ)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

build/rel/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) $(CFLAGS) $(DEPFLAGS) -c -o $@ $<

build/san/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) -O1 -g $(SAN) $(DEPFLAGS) -c -o $@ $<

build/san/archquake: build/san/src/main.o $(SAN_OBJ)
	$(CC) $(SAN) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

build/san/runner: $(TEST_OBJ) $(SAN_OBJ)
	$(CC) $(SAN) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

# One runner, sanitizers on; its last line is "N passed, N failed".
# TESTS=substring runs only the tests whose names contain it.
# The disk cache of prepared records (docs/cache.md) goes to build/tmp/cache,
# emptied first, not to the user's ~/.cache.
check: build/san/runner build/san/archquake
	rm -rf build/tmp/cache
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  XDG_CACHE_HOME=$(CURDIR)/build/tmp/cache \
	  AQ_BIN=build/san/archquake ./build/san/runner $(TESTS)

# archquake-mpi (src/app/mpi.c): the main job over Open MPI ranks; rank 0
# alone writes, with the serial HDF5 library.  Only `make mpi` needs MPI.
MPICC ?= mpicc
mpi: archquake-mpi
build/mpi/mpi.o: src/app/mpi.c
	@mkdir -p $(dir $@)
	$(MPICC) $(AQ_CFLAGS) $(CFLAGS) $(DEPFLAGS) -c -o $@ $<
archquake-mpi: build/mpi/mpi.o $(REL_OBJ)
	$(MPICC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

# The MPI tests (tests/mpi.sh): outputs equal archquake -j 1's at 1, 2 and 3
# ranks, a failing record, --resume, a killed follower.
check-mpi: archquake archquake-mpi
	rm -rf build/tmp/cache-mpi
	XDG_CACHE_HOME=$(CURDIR)/build/tmp/cache-mpi AQ_BIN=./archquake AQ_MPI_BIN=./archquake-mpi \
	  sh tests/mpi.sh

# Mutation testing (tests/mutate.py): the tests without sanitizers at -O1
# (fast to rebuild and run); each mutant recompiles one file and relinks.
build/mut/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) -O1 -g $(DEPFLAGS) -c -o $@ $<

build/mut/runner: $(MUT_OBJ)
	$(CC) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

build/mut/archquake: build/mut/src/main.o $(filter build/mut/src/%,$(MUT_OBJ))
	$(CC) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

mutate: build/mut/runner build/mut/archquake
	rm -rf build/tmp/cache-mut
	XDG_CACHE_HOME=$(CURDIR)/build/tmp/cache-mut \
	AQ_CFLAGS='$(AQ_CFLAGS)' AQ_LIBS='$(AQ_LIBS)' CC='$(CC)' LDFLAGS='$(LDFLAGS)' \
	  python3 tests/mutate.py $(MUTANTS)

BENCH_BIN := $(BENCH_SRC:bench/%.c=build/bench/%)
build/bench/%: bench/%.c bench/bench.h $(REL_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) $(CFLAGS) $(LDFLAGS) -Ibench -o $@ $< $(REL_OBJ) $(AQ_LIBS)

bench: archquake $(BENCH_BIN)
	@for b in $(BENCH_BIN); do echo "== $$b"; ./$$b || exit 1; done
	@if command -v $(MPICC) >/dev/null 2>&1; then $(MAKE) -s mpi && sh bench/mpi.sh; \
	 else echo "== bench/mpi.sh: skipped ($(MPICC) not found: make deps-dev)"; fi

# Fuzz every reader with libFuzzer for FUZZ_SECONDS each, seeded from
# fuzz/seeds, records/ and tests/data/records.  A crash, leak, timeout or
# undefined behaviour stops that harness: its log is shown, the input that
# did it is named (build/fuzz/crash-NAME/...) and the target fails.
FUZZ_BIN := $(FUZZ_SRC:fuzz/%.c=build/fuzz/%)
# The library is compiled once for every harness (instrumented for
# coverage, not linked with libFuzzer's main); each harness links it.
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=undefined
FUZZ_OBJ := $(LIB_SRC:%.c=build/fz/%.o)
.SECONDARY: $(FUZZ_OBJ)
# leg_taylor.c's series code (each order's loops unrolled for degree 14)
# takes clang more than 15 CPU-minutes at -O1 under ASan and UBSan, and
# 1 s at -O0; no harness steps an arch, so only speed is given up.
FUZZ_OPT := -O1
build/fz/src/arch/leg_taylor.o: FUZZ_OPT := -O0
build/fz/%.o: %.c
	@mkdir -p $(dir $@)
	clang $(AQ_CFLAGS) $(FUZZ_OPT) -g -fsanitize=fuzzer-no-link $(FUZZ_SAN) $(DEPFLAGS) -c -o $@ $<
# The harnesses link an archive of it, so that each takes only the members
# its reader needs: linked as objects, every harness held the whole program
# (17 harnesses, 345 MB of disk; 44.5 MB linked from the archive).
FUZZ_LIB := build/fz/libarchquake.a
$(FUZZ_LIB): $(FUZZ_OBJ)
	@rm -f $@
	ar rcs $@ $^
build/fuzz/%: fuzz/%.c fuzz/fuzz_common.h $(FUZZ_LIB) $(HDRS)
	@mkdir -p $(dir $@)
	clang $(AQ_CFLAGS) -O1 -g -fsanitize=fuzzer $(FUZZ_SAN) -o $@ $< $(FUZZ_LIB) $(AQ_LIBS)

# FUZZ_KEEP_CORPUS=0: a harness's corpus is removed once it has passed
# (make ci: 20 s of the 17 harnesses grow 270 MB of inputs).
FUZZ_KEEP_CORPUS ?= 1
fuzz: $(FUZZ_BIN)
	@fail=0; for f in $(FUZZ_BIN); do \
	  n=$$(basename $$f); mkdir -p build/fuzz/corpus-$$n build/fuzz/crash-$$n; \
	  echo "== $$n ($(FUZZ_SECONDS) s)"; \
	  if ./$$f -max_total_time=$(FUZZ_SECONDS) -max_len=200000 -timeout=10 \
	      -artifact_prefix=build/fuzz/crash-$$n/ \
	      build/fuzz/corpus-$$n fuzz/seeds/$$n records tests/data/records \
	      > build/fuzz/$$n.log 2>&1; then \
	    grep -a '^Done ' build/fuzz/$$n.log || tail -n 1 build/fuzz/$$n.log; \
	    [ "$(FUZZ_KEEP_CORPUS)" = 1 ] || rm -rf build/fuzz/corpus-$$n; \
	  else \
	    tail -n 40 build/fuzz/$$n.log; \
	    art=$$(sed -n 's/.*Test unit written to \([^ ]*\).*/\1/p' build/fuzz/$$n.log | tail -n 1); \
	    echo "fuzz: $$n FAILED on input $${art:-(none written; see build/fuzz/$$n.log)}"; \
	    fail=1; \
	  fi; \
	done; exit $$fail

# CI (.ci/run) and the README's test command: the tests, a short fuzz of
# every reader (CI_FUZZ_SECONDS each), then the MPI tests (make check-mpi);
# the last line adds the two suites' "N passed, N failed".  What a stage
# leaves on disk is removed once it has passed (the tests' disk cache, the
# fuzz corpora, the MPI tests' cache): a clean clone's make ci peaked at
# 486 MB of disk besides the packages, the checkout's 80 MB included
# (1.3 GB before); the first line says how much is free.
CI_FUZZ_SECONDS ?= 20
ci:
	@mkdir -p build
	@df -Pm build | awk 'NR == 2 { print "ci: " $$4 " MB free for build/" }'
	@$(MAKE) --no-print-directory check > build/ci-check.log 2>&1; rc=$$?; \
	  cat build/ci-check.log; [ $$rc -eq 0 ] || exit $$rc; rm -rf build/tmp/cache; \
	  $(MAKE) --no-print-directory fuzz FUZZ_SECONDS=$(CI_FUZZ_SECONDS) FUZZ_KEEP_CORPUS=0 || exit 1; \
	  $(MAKE) --no-print-directory -j2 mpi > build/ci-mpi-build.log 2>&1 || { cat build/ci-mpi-build.log; exit 1; }; \
	  $(MAKE) --no-print-directory check-mpi > build/ci-mpi.log 2>&1; rc=$$?; \
	  cat build/ci-mpi.log; [ $$rc -eq 0 ] || exit $$rc; rm -rf build/tmp/cache-mpi; \
	  tail -n 1 build/ci-check.log build/ci-mpi.log | \
	    awk '/passed,/ { p += $$1; f += $$3 } END { printf "%d passed, %d failed\n", p, f }'

# The man page is written from the binary's own --help texts (tools/man.sh),
# so the two cannot drift apart.  INSTALL_BIN: the binary installed and
# read for the page (the tests install the sanitized one).
INSTALL_BIN ?= archquake
build/archquake.1: $(INSTALL_BIN) tools/man.sh
	@mkdir -p build
	sh tools/man.sh $(INSTALL_BIN) > $@.new && mv -f $@.new $@

BINDIR  = $(DESTDIR)$(PREFIX)/bin
ARCHDIR = $(DESTDIR)$(PREFIX)/share/archquake/arches
DOCDIR  = $(DESTDIR)$(PREFIX)/share/doc/archquake
MAN1DIR = $(DESTDIR)$(PREFIX)/share/man/man1
ARCH_FILES := $(wildcard arches/*.cfg arches/*.csv)
# README.md with docs/ and docs/figures/ beside it, as in the source tree,
# so that the README's links lead to installed files.
DOC_FILES  := $(wildcard docs/*.md)
FIG_FILES  := $(wildcard docs/figures/*.png)
install: $(INSTALL_BIN) build/archquake.1
	install -d $(BINDIR) $(ARCHDIR) $(DOCDIR)/docs/figures $(MAN1DIR)
	install -m 755 $(INSTALL_BIN) $(BINDIR)/archquake
	if test -f archquake-mpi; then install -m 755 archquake-mpi $(BINDIR)/archquake-mpi; fi
	install -m 644 $(ARCH_FILES) $(ARCHDIR)
	install -m 644 README.md $(DOCDIR)
	install -m 644 $(DOC_FILES) $(DOCDIR)/docs
	install -m 644 $(FIG_FILES) $(DOCDIR)/docs/figures
	install -m 644 build/archquake.1 $(MAN1DIR)/archquake.1

uninstall:
	rm -f $(BINDIR)/archquake $(BINDIR)/archquake-mpi $(MAN1DIR)/archquake.1
	rm -f $(addprefix $(ARCHDIR)/,$(notdir $(ARCH_FILES)))
	rm -f $(DOCDIR)/README.md $(addprefix $(DOCDIR)/,$(DOC_FILES) $(FIG_FILES))
	-rmdir $(ARCHDIR) $(DESTDIR)$(PREFIX)/share/archquake $(DOCDIR)/docs/figures \
	  $(DOCDIR)/docs $(DOCDIR) 2>/dev/null

# Debian packages: DEB_PKGS builds and runs archquake (`make deps`);
# DEB_DEV_PKGS adds what the tests, `make fuzz` and `make mpi` need
# (`make deps-dev`, used by .ci/run).
DEB_PKGS := build-essential pkg-config libgsl-dev libfftw3-dev libhdf5-dev libaec-dev zlib1g-dev \
            libinih-dev libmseed-dev libxml2-dev libplplot-dev plplot-driver-cairo nettle-dev \
            libglpk-dev libxxhash-dev libsiconos-numerics-dev
DEB_DEV_PKGS := $(DEB_PKGS) hdf5-tools python3-h5py mseed2sac clang libclang-rt-14-dev \
            openmpi-bin libopenmpi-dev man-db locales poppler-utils chromium librsvg2-bin
# The downloaded packages are removed once installed (apt-get clean): for
# deps-dev they take 1.5 GB, which the build, the tests and the fuzz need.
deps:
	apt-get update
	DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $(DEB_PKGS)
	apt-get clean

deps-dev:
	apt-get update
	DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $(DEB_DEV_PKGS)
	apt-get clean

print-deps:
	@echo $(DEB_PKGS)

print-deps-dev:
	@echo $(DEB_DEV_PKGS)

clean:
	rm -rf build archquake archquake-mpi

# the objects' header dependencies (DEPFLAGS), once they have been built
-include $(wildcard build/*/*.d build/*/*/*.d build/*/*/*/*.d)
