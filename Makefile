# archquake Makefile.  Overridable: CC CFLAGS LDFLAGS PREFIX DESTDIR.
# Targets: all check bench install uninstall clean deps fuzz mpi check-mpi
CC      ?= cc
CFLAGS  ?= -O2 -g
LDFLAGS ?=
PREFIX  ?= /usr/local
DESTDIR ?=
FUZZ_SECONDS ?= 60

PKGS      := gsl fftw3 hdf5 inih
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
AQ_CFLAGS  = -std=c11 -Wall -Wextra -D_POSIX_C_SOURCE=200809L -Isrc -Ibuild $(PKG_CFLAGS)
AQ_LIBS    = $(PKG_LIBS) -lpthread -lm
SAN        = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined

LIB_SRC   := $(sort $(wildcard src/*.c src/*/*.c))
LIB_SRC   := $(filter-out src/main.c src/app/mpi.c,$(LIB_SRC))
TEST_SRC  := $(sort $(wildcard tests/*.c))
BENCH_SRC := $(sort $(wildcard bench/bench_*.c))
FUZZ_SRC  := $(sort $(wildcard fuzz/fuzz_*.c))
HDRS      := $(wildcard src/*.h src/*/*.h tests/*.h bench/*.h)

REL_OBJ := $(LIB_SRC:%.c=build/rel/%.o)
SAN_OBJ := $(LIB_SRC:%.c=build/san/%.o)
TEST_OBJ := $(TEST_SRC:%.c=build/san/%.o)

.PHONY: all check bench install uninstall clean deps print-deps fuzz mpi check-mpi FORCE
all: archquake

# The exact build, embedded in results files (src/app/version.c): `git
# describe`, or the version alone outside a git checkout.  The header is
# rewritten only when the description changes.
AQ_DESCRIBE := $(shell git describe --always --dirty 2>/dev/null)
build/describe.h: FORCE
	@mkdir -p build
	@printf '#define AQ_BUILD_SUFFIX "%s"\n' '$(if $(AQ_DESCRIBE), ($(AQ_DESCRIBE)))' > $@.new
	@cmp -s $@.new $@ && rm -f $@.new || mv -f $@.new $@
build/rel/src/app/version.o build/san/src/app/version.o: build/describe.h

archquake: build/rel/src/main.o $(REL_OBJ)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

build/rel/%.o: %.c $(HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) $(CFLAGS) -c -o $@ $<

build/san/%.o: %.c $(HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) -O1 -g $(SAN) -c -o $@ $<

build/san/archquake: build/san/src/main.o $(SAN_OBJ)
	$(CC) $(SAN) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

build/san/runner: $(TEST_OBJ) $(SAN_OBJ)
	$(CC) $(SAN) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

# One runner, sanitizers on; its last line is "N passed, N failed".
# TESTS=substring runs only the tests whose names contain it.
check: build/san/runner build/san/archquake
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  AQ_BIN=build/san/archquake ./build/san/runner $(TESTS)

# archquake-mpi (src/app/mpi.c): the main job over Open MPI ranks; rank 0
# alone writes, with the serial HDF5 library.  Only `make mpi` needs MPI.
MPICC ?= mpicc
mpi: archquake-mpi
build/mpi/main.o: src/main.c $(HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) $(CFLAGS) -DAQ_MAIN=aq_main_serial -c -o $@ $<
build/mpi/mpi.o: src/app/mpi.c $(HDRS)
	@mkdir -p $(dir $@)
	$(MPICC) $(AQ_CFLAGS) $(CFLAGS) -c -o $@ $<
archquake-mpi: build/mpi/mpi.o build/mpi/main.o $(REL_OBJ)
	$(MPICC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(AQ_LIBS)

# The MPI tests (tests/mpi.sh): outputs equal archquake -j 1's at 1, 2 and 3
# ranks, a failing record, --resume, a killed follower.
check-mpi: archquake archquake-mpi
	AQ_BIN=./archquake AQ_MPI_BIN=./archquake-mpi sh tests/mpi.sh

BENCH_BIN := $(BENCH_SRC:bench/%.c=build/bench/%)
build/bench/%: bench/%.c bench/bench.h $(REL_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(AQ_CFLAGS) $(CFLAGS) $(LDFLAGS) -Ibench -o $@ $< $(REL_OBJ) $(AQ_LIBS)

bench: archquake $(BENCH_BIN)
	@for b in $(BENCH_BIN); do echo "== $$b"; ./$$b || exit 1; done
	@if command -v $(MPICC) >/dev/null 2>&1; then $(MAKE) -s mpi && sh bench/mpi.sh; \
	 else echo "== bench/mpi.sh: skipped ($(MPICC) not found: make deps-dev)"; fi

# Fuzz every reader with libFuzzer for FUZZ_SECONDS each, seeded from records/.
FUZZ_BIN := $(FUZZ_SRC:fuzz/%.c=build/fuzz/%)
build/fuzz/%: fuzz/%.c fuzz/fuzz_common.h $(LIB_SRC) $(HDRS) build/describe.h
	@mkdir -p $(dir $@)
	clang $(AQ_CFLAGS) -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -o $@ $< $(LIB_SRC) $(AQ_LIBS)

fuzz: $(FUZZ_BIN)
	@for f in $(FUZZ_BIN); do \
	  n=$$(basename $$f); mkdir -p build/fuzz/corpus-$$n; \
	  echo "== $$n ($(FUZZ_SECONDS) s)"; \
	  ./$$f -max_total_time=$(FUZZ_SECONDS) -max_len=200000 -timeout=10 \
	    build/fuzz/corpus-$$n fuzz/seeds/$$n records tests/data/records 2>&1 | tail -n 3 || exit 1; \
	done

install: archquake
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 archquake $(DESTDIR)$(PREFIX)/bin/archquake

uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/archquake

# Debian packages the build, the tests and `make fuzz` need.
DEB_PKGS := build-essential pkg-config libgsl-dev libfftw3-dev libhdf5-dev \
            libinih-dev hdf5-tools python3-h5py mseed2sac clang libclang-rt-14-dev \
            libopenmpi-dev openmpi-bin
deps:
	apt-get update
	DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $(DEB_PKGS)

print-deps:
	@echo $(DEB_PKGS)

clean:
	rm -rf build archquake archquake-mpi
