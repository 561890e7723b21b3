# wrinkle — build, test, validate, benchmark, install.
# The two commands a new user needs: `make demo` and `make test` (both install missing Debian
# packages first through the `deps` target).

PREFIX  ?= /usr/local
DESTDIR ?=
CC      ?= cc
CXX     ?= c++
# No -ffast-math anywhere: the exact geometric predicates in predicates.h need strict IEEE
# double arithmetic, and -ffp-contract=off keeps FMA contraction from changing their results.
OPT     ?= -O2
# -fno-math-errno: libm calls need not set errno (nothing in the kit reads it after one), so GCC
# inlines sqrt as sqrtsd without its errno branch and libm call; results are bit-identical (issue 17:
# -1.1 % instructions of wr_mesher_run, -2 % of its Poisson fill). A speed flag only: programs that
# include the headers with their own flags get the same results without it.
# -ffunction-sections -fdata-sections (with -Wl,--gc-sections at link time, GC_LDFLAGS): a program
# keeps only the code it reaches, so it links only the libraries that code calls (PROG_LIBS below).
CFLAGS_COMMON = -g $(OPT) -Wall -Wextra -pedantic -ffp-contract=off -fno-math-errno -ffunction-sections \
                -fdata-sections -Iinclude -Idrivers/lib \
                -I/usr/include/suitesparse -DWR_USE_CHOLMOD=1 -DWR_USE_FFTW=1 -DWR_USE_LIBPNG=1
CFLAGS  ?=
ALL_CFLAGS   = -std=c11 $(CFLAGS_COMMON) $(CFLAGS)
ALL_CXXFLAGS = -std=c++17 $(CFLAGS_COMMON) $(CFLAGS)
LIBS    = -lcjson -lcholmod -lfftw3 -lpng -lgsl -lgslcblas -lm
# Each program links only the libraries its reachable code calls (issue 17: loading CHOLMOD with its
# BLAS, GSL and FFTW cost every process ~4 ms before main): the sections it never reaches are
# dropped (--gc-sections) and with them their references; LIBS_<program> (below, near the drivers)
# lists what is left, LIBS when a program has no list. A list missing a library fails the link with
# the undefined symbols, so it cannot go stale silently; --as-needed drops a listed one unused.
GC_LDFLAGS = -Wl,--gc-sections -Wl,--as-needed
PROG_LIBS  = $(GC_LDFLAGS) $(if $(LIBS_$(notdir $@)),$(LIBS_$(notdir $@)),$(LIBS))

# Debian packages the kit builds against. libopenblas0 gives CHOLMOD an optimized BLAS
# (through the libblas.so.3 alternative) instead of the reference one.
DEB_PACKAGES = libgsl-dev libfftw3-dev libsuitesparse-dev libopenblas0 libcjson-dev \
               libcriterion-dev gnuplot-nox pkg-config universal-ctags libpng-dev python3 python3-numpy \
               libarpack2-dev
BENCH_PACKAGES = libcgal-dev

# ARPACK (eigen.h's eigensolver, statics.h's stability test) only for the programs that use it: the
# test binary and validate_statics_stability (its own implementation unit, build/obj/impl_arpack.o).
ARPACK_FLAGS = -DWR_USE_ARPACK=1
ARPACK_LIBS  = -larpack

SAN = -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=all

HEADERS     = $(wildcard include/wrinkle/*.h)
DRIVER_SRC  = $(wildcard drivers/*.c)
DRIVERS     = $(patsubst drivers/%.c,bin/%,$(DRIVER_SRC))
VALID_SRC   = $(wildcard validation/*.c)
VALIDATORS  = $(patsubst validation/%.c,bin/%,$(VALID_SRC))
LIB_SRC     = $(wildcard drivers/lib/*.c)
LIB_OBJ     = $(patsubst drivers/lib/%.c,build/obj/%.o,$(LIB_SRC))
TEST_SRC    = $(wildcard tests/test_*.c)
BENCH_SRC   = $(wildcard bench/*.c)
BENCH_CXX   = $(wildcard bench/*.cpp)
BENCHES     = $(patsubst bench/%.c,bin/%,$(BENCH_SRC)) $(patsubst bench/%.cpp,bin/%,$(BENCH_CXX))
EXTRA_HDR   = $(wildcard drivers/lib/*.h)

.SECONDARY: $(LIB_OBJ)
.PHONY: all deps deps-bench demo test python-test validate validate-long bench install uninstall clean check-headers check-examples

all: $(DRIVERS) $(VALIDATORS) build/libwrinkle.so

# The shared library of the Python binding (python/wrinkle): one implementation unit
# (python/wrinkle_capi.c, a flat C interface) plus the pattern and scene readers. Only wr_py_*
# symbols are exported (-fvisibility=hidden), so it never clashes with a program's own wrinkle.
build/libwrinkle.so: python/wrinkle_capi.c drivers/lib/pattern.c drivers/lib/scene.c drivers/lib/jsonout.c $(HEADERS) $(EXTRA_HDR)
	@mkdir -p build
	$(CC) $(ALL_CFLAGS) -fPIC -shared -fvisibility=hidden python/wrinkle_capi.c drivers/lib/pattern.c \
	    drivers/lib/scene.c drivers/lib/jsonout.c -o $@ -lcjson -lcholmod -lfftw3 -lpng -lm

deps:
	@sh tools/deps.sh $(DEB_PACKAGES)

deps-bench: deps
	@sh tools/deps.sh $(BENCH_PACKAGES)

build/obj/%.o: drivers/lib/%.c $(HEADERS) $(EXTRA_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

# What each program's reachable code calls (PROG_LIBS; found by linking without libraries: the
# undefined references left after --gc-sections). -lm throughout; cJSON for the pattern/scene/result
# files, CHOLMOD for spd.h's direct solver, FFTW for the wrinkle field's spectra, libpng for PNGs.
LIBS_wrinkle-mesh = -lcjson -lm
LIBS_wrinkle-report = -lcjson -lm
LIBS_wrinkle-resolution = -lcjson -lm
LIBS_wrinkle-sim = -lcjson -lcholmod -lpng -lm
LIBS_wrinkle-statics = -lcjson -lcholmod -lfftw3 -lpng -lm
LIBS_wrinkle-tfw = -lcjson -lcholmod -lfftw3 -lpng -lm
LIBS_validate_cantilever = -lcjson -lcholmod -lgsl -lgslcblas -lm
LIBS_validate_fig5 = -lcjson -lm
LIBS_validate_meshing = -lcjson -lm
LIBS_validate_table1 = -lcjson -lm
LIBS_validate_tfw_release = -lcjson -lcholmod -lm
$(foreach p,curtain optimal_vs_uniform stretch tfw_crosscheck tfw_sphere_drape tfw_twisted_cylinder statics_stability,\
  $(eval LIBS_validate_$(p) = -lcjson -lcholmod -lfftw3 -lm))
$(foreach p,sim_curtain sim_garments sim_shirring sim_stretch statics_loop tfw_inflatables tfw_sheared_rectangle \
  tfw_stretched_sheet,$(eval LIBS_validate_$(p) = -lcjson -lcholmod -lfftw3 -lpng -lm))
$(foreach p,collision mesher poisson triangle,$(eval LIBS_bench_$(p) = -lm))
$(foreach p,pcg projection tfw dynamics weld,$(eval LIBS_bench_$(p) = -lcholmod -lm))
LIBS_bench_statics = -lcjson -lcholmod -lm
LIBS_probe_mesher_edges = -lcjson -lm

bin/%: drivers/%.c $(LIB_OBJ) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) $< $(LIB_OBJ) -o $@ $(PROG_LIBS)

# Drivers that need only the dependency-free core link only what they use (process start: 1 ms
# instead of 5 ms with CHOLMOD, GSL, FFTW and cJSON loaded): their own implementation unit of the
# headers they include, compiled from the header itself, and the CLI helpers.
# impl_cdt.o (wrinkle-triangulate's only implementation unit) at -O3 (TRI_OPT): the filters of the exact
# predicates and the refinement loops inlined and unrolled further, outputs byte-identical (strict IEEE
# arithmetic either way: no -ffast-math, -ffp-contract=off), ~5 % fewer instructions (issue 17).
TRI_OPT ?= -O3
build/obj/impl_cdt.o: include/wrinkle/triangulate.h include/wrinkle/predicates.h include/wrinkle/polyfile.h include/wrinkle/core.h
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(TRI_OPT) -x c -DWRINKLE_IMPLEMENTATION -c include/wrinkle/polyfile.h -o $@

# wrinkle-triangulate, Triangle's drop-in, runs once per small file: linked statically (libc and
# libm only), so a process maps no shared object and resolves no symbol at start (issue 17: 0.26M ->
# 0.13M instructions and ~0.4 ms less CPU per process; bench/RESULTS.md, bench_triangle 2026-12-07).
# TRI_LDFLAGS= (empty) links it dynamically.
# make memcheck runs build/dyn/wrinkle-triangulate, its dynamically linked twin (same sources and
# objects): valgrind cannot follow static glibc's allocator and reports its start-up as errors.
TRI_LDFLAGS ?= -static
TRI_LINK = $(CC) $(ALL_CFLAGS) $(TRI_OPT) $< build/obj/cli.o build/obj/impl_cdt.o -o $@
bin/wrinkle-triangulate: drivers/wrinkle-triangulate.c build/obj/cli.o build/obj/impl_cdt.o $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(TRI_LINK) $(TRI_LDFLAGS) $(GC_LDFLAGS) -lm
build/dyn/wrinkle-triangulate: drivers/wrinkle-triangulate.c build/obj/cli.o build/obj/impl_cdt.o $(HEADERS) $(EXTRA_HDR)
	@mkdir -p build/dyn
	$(TRI_LINK) $(GC_LDFLAGS) -lm

build/obj/impl_arpack.o: drivers/lib/impl.c $(HEADERS) $(EXTRA_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) -c $< -o $@

bin/validate_statics_stability: validation/validate_statics_stability.c build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) $< build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) -o $@ $(PROG_LIBS) $(ARPACK_LIBS)

# validate_statics_fig7 (make validate-long only) runs statics.h's stability test too.
bin/validate_statics_fig7: validation/validate_statics_fig7.c build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) $< build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) -o $@ $(LIBS) $(ARPACK_LIBS)

# validate_tfw_sheared_rectangle and _twisted_cylinder: their --stvk-loop references run the stability test.
bin/validate_tfw_sheared_rectangle bin/validate_tfw_twisted_cylinder: bin/%: validation/%.c build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) $< build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) -o $@ $(PROG_LIBS) $(ARPACK_LIBS)

bin/%: validation/%.c $(LIB_OBJ) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) $< $(LIB_OBJ) -o $@ $(PROG_LIBS)

bin/%: bench/%.c $(LIB_OBJ) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) -O3 $< $(LIB_OBJ) -o $@ $(PROG_LIBS)

# bench_loop_linear runs statics.h's stability test (ARPACK), as validate_statics_stability.
bin/bench_loop_linear: bench/bench_loop_linear.c validation/stretch_probe.h build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) -O3 $< build/obj/impl_arpack.o $(filter-out build/obj/impl.o,$(LIB_OBJ)) -o $@ $(LIBS) $(ARPACK_LIBS)

# bench_triangle times bin/wrinkle-triangulate as a process (against Triangle when WR_TRIANGLE names
# a Triangle binary built outside the tree; without it the Triangle columns are skipped).
bin/bench_triangle: bin/wrinkle-triangulate

# bench_dynamics is its own implementation unit, built with OpenMP, so it measures the thread gain of
# dynamics.h's face blocks in one run (the library objects stay serial; results are bit-identical).
bin/bench_dynamics: bench/bench_dynamics.c $(HEADERS)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) -O3 -fopenmp -DWR_BENCH_IMPL $< -o $@ $(PROG_LIBS)

# bench_weld is its own implementation unit too (serial), so the same source can be built against
# another tree's headers (-I) to compare two versions of the weld in one run.
bin/bench_weld: bench/bench_weld.c $(HEADERS)
	@mkdir -p bin
	$(CC) $(ALL_CFLAGS) -O3 -DWR_BENCH_IMPL $< -o $@ $(PROG_LIBS)

bin/%: bench/%.cpp $(LIB_OBJ) $(HEADERS) $(EXTRA_HDR)
	@mkdir -p bin
	$(CXX) $(ALL_CXXFLAGS) -O3 -frounding-math $< $(LIB_OBJ) -o $@ $(LIBS) -lgmp -lmpfr

# Unit tests: every tests/test_*.c plus tests/impl.c (the one WRINKLE_IMPLEMENTATION unit) in one
# Criterion binary, built with ASan+UBSan. Driver helpers (but not drivers/lib/impl.c, the drivers'
# implementation unit) are rebuilt with the sanitizers too. One object per source (dependencies from
# -MMD), so `make -j2` compiles two at a time and a changed test file recompiles alone.
TEST_OBJ = $(patsubst tests/%.c,build/test/obj/%.o,$(TEST_SRC) tests/impl.c) \
           $(patsubst drivers/lib/%.c,build/test/obj/lib_%.o,$(filter-out drivers/lib/impl.c,$(LIB_SRC)))
build/test/obj/%.o: tests/%.c
	@mkdir -p build/test/obj
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) $(SAN) -O1 -MMD -MP -c $< -o $@
build/test/obj/lib_%.o: drivers/lib/%.c
	@mkdir -p build/test/obj
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) $(SAN) -O1 -MMD -MP -c $< -o $@
build/test/wrinkle_tests: $(TEST_OBJ)
	@mkdir -p build/test
	$(CC) $(ALL_CFLAGS) $(ARPACK_FLAGS) $(SAN) -O1 $(TEST_OBJ) -o $@ $(LIBS) $(ARPACK_LIBS) -lcriterion
-include $(TEST_OBJ:.o=.d)

check-headers:
	@sh tests/check_headers.sh

# Every header's top-block EXAMPLE, compiled (C11 and C++17, -Werror) and run (tests/check_examples.sh).
check-examples:
	@sh tests/check_examples.sh

test: deps
	@$(MAKE) --no-print-directory all build/test/wrinkle_tests
	@sh tests/check_headers.sh
	@sh tests/check_examples.sh
	@sh tests/run_tests.sh
	@$(MAKE) --no-print-directory python-test

# The Python binding's tests (python/tests, unittest) against build/libwrinkle.so. Debian's python3
# (with python3-numpy from DEB_PACKAGES) unless PYTHON says otherwise; a failure fails `make test`.
PYTHON ?= $(shell [ -x /usr/bin/python3 ] && echo /usr/bin/python3 || echo python3)
python-test: build/libwrinkle.so
	@echo "python binding tests ($(PYTHON)):"
	@PYTHONPATH=python OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 $(PYTHON) -m unittest discover -s python/tests

demo: deps
	@$(MAKE) --no-print-directory all
	@sh tools/demo.sh

validate: deps
	@$(MAKE) --no-print-directory all
	@sh validation/run_all.sh

# The dynamic-simulator validations (validation/validate_sim_*.c) in full: tens of CPU minutes each
# on this 2-core box; `make validate` runs their --quick versions.
# Also validate_statics_fig7 (TFW Fig. 7, linear StVK at 16k-130k vertices, about 1 CPU hour), only here.
# And validate_tfw_sheared_rectangle / _twisted_cylinder --stvk-loop (StVK with the Loop element, issue 15).
validate-long: deps
	@$(MAKE) --no-print-directory all
	@sh validation/run_all.sh --long

bench: deps-bench
	@$(MAKE) --no-print-directory $(BENCHES)
	@sh bench/run_all.sh

# The pattern and scene readers for engines (drivers/lib/pattern.c, scene.c and the JSON writer
# scene.c uses): a static library without wrinkle code (link it with your WRINKLE_IMPLEMENTATION
# unit) plus cJSON. Installed with its headers under include/wrinkle/formats/.
FORMATS_SRC = drivers/lib/pattern.c drivers/lib/scene.c drivers/lib/jsonout.c
FORMATS_HDR = drivers/lib/pattern.h drivers/lib/scene.h drivers/lib/jsonout.h
build/libwrinkle-formats.a: $(patsubst drivers/lib/%.c,build/obj/%.o,$(FORMATS_SRC))
	@mkdir -p build
	rm -f $@ && ar rcs $@ $^

PC_FILES = wrinkle wrinkle-core wrinkle-formats
install: all build/libwrinkle-formats.a
	install -d $(DESTDIR)$(PREFIX)/include/wrinkle/formats $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 $(HEADERS) $(DESTDIR)$(PREFIX)/include/wrinkle/
	install -m 644 $(FORMATS_HDR) $(DESTDIR)$(PREFIX)/include/wrinkle/formats/
	install -m 644 build/libwrinkle-formats.a $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(DRIVERS) $(DESTDIR)$(PREFIX)/bin/
	for p in $(PC_FILES); do sed -e 's|@PREFIX@|$(PREFIX)|g' tools/$$p.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/$$p.pc; done

uninstall:
	rm -rf $(DESTDIR)$(PREFIX)/include/wrinkle
	rm -f $(patsubst bin/%,$(DESTDIR)$(PREFIX)/bin/%,$(DRIVERS)) $(DESTDIR)$(PREFIX)/lib/libwrinkle-formats.a
	rm -f $(patsubst %,$(DESTDIR)$(PREFIX)/lib/pkgconfig/%.pc,$(PC_FILES))

clean:
	rm -rf bin build

# ---- hostile input, leaks, drop-in use (issue 7) -------------------------------------------------
# libFuzzer harnesses tests/fuzz/fuzz_*.c, each its own WRINKLE_IMPLEMENTATION unit, built with clang
# and ASan+UBSan; FUZZ_EXTRA_<name> lists the driver helpers a harness exercises.
# `make fuzz` runs each for FUZZ_SECONDS (default 10 min), `make fuzz-smoke` for 60 s (CI).
FUZZ_CC      ?= clang
FUZZ_SECONDS ?= 600
FUZZ_FLAGS    = -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
                -fno-omit-frame-pointer -ffp-contract=off -Iinclude -Idrivers/lib \
                -I/usr/include/suitesparse -DWR_USE_CHOLMOD=1 -DWR_USE_FFTW=1
FUZZ_SRC      = $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_NAMES    = $(patsubst tests/fuzz/%.c,%,$(FUZZ_SRC))
FUZZERS       = $(addprefix build/fuzz/,$(FUZZ_NAMES))
FUZZ_EXTRA_fuzz_scene   = drivers/lib/scene.c drivers/lib/jsonout.c
FUZZ_EXTRA_fuzz_pattern = drivers/lib/pattern.c

.PHONY: fuzz fuzz-build fuzz-smoke memcheck examples install-check driver-check deps-check mutate

# Tools of these checks (installed like DEB_PACKAGES: apt-get when root / passwordless sudo).
CHECK_PACKAGES = clang libclang-rt-14-dev valgrind strace python3
deps-check: deps
	@sh tools/deps.sh $(CHECK_PACKAGES)

build/fuzz/%: tests/fuzz/%.c $(HEADERS) $(EXTRA_HDR) $(LIB_SRC)
	@mkdir -p build/fuzz
	$(FUZZ_CC) $(FUZZ_FLAGS) $< $(FUZZ_EXTRA_$*) -o $@ $(LIBS)

fuzz-build: deps-check
	@$(MAKE) --no-print-directory $(FUZZERS)

fuzz: fuzz-build
	@sh tests/fuzz/run.sh $(FUZZ_SECONDS) $(FUZZ_NAMES)

# FUZZ_SMOKE_NAMES: the harnesses CI runs (default all); `make fuzz` always runs every harness.
FUZZ_SMOKE_NAMES ?= $(FUZZ_NAMES)
fuzz-smoke: fuzz-build
	@sh tests/fuzz/run.sh 60 $(FUZZ_SMOKE_NAMES)

# Mutation check (issue 20): each mutant of tests/mutants.txt applied alone to a scratch copy of the
# tree, unit tests (its Criterion filter, fail-fast) and fast validations run; survivors reported
# (tools/mutate.py; MUTATE_ARGS e.g. --only ID,ID or --list FILE). Survivors: tests/MUTANTS.md.
mutate: deps
	@nice python3 tools/mutate.py $(MUTATE_ARGS)

# Every driver's smoke invocation under valgrind memcheck: any error or definite/indirect leak fails.
memcheck: deps-check all build/dyn/wrinkle-triangulate
	@sh tests/memcheck.sh

# Every driver: --help, one-line non-zero failure on bad input, atomic outputs.
driver-check: deps-check all
	@sh tests/drivers_smoke.sh

# The drop-in examples built straight against include/ (install-check builds them against an install).
EXAMPLE_FLAGS = -g -O2 -Wall -Wextra -pedantic -Werror -ffp-contract=off -Iinclude \
                -I/usr/include/suitesparse -DWR_USE_CHOLMOD=1
EXAMPLE_LIBS  = -lcholmod -lfftw3 -lm
build/examples/minimal_c: examples/minimal_c/main.c $(HEADERS)
	@mkdir -p build/examples
	$(CC) -std=c11 $(EXAMPLE_FLAGS) $< -o $@ $(EXAMPLE_LIBS)
build/examples/minimal_cpp: examples/minimal_cpp/impl.cpp examples/minimal_cpp/main.cpp $(HEADERS)
	@mkdir -p build/examples
	$(CXX) -std=c++17 $(EXAMPLE_FLAGS) examples/minimal_cpp/impl.cpp examples/minimal_cpp/main.cpp -o $@ $(EXAMPLE_LIBS)
build/examples/%: examples/tutorial/%.c $(HEADERS)
	@mkdir -p build/examples
	$(CC) -std=c11 $(EXAMPLE_FLAGS) $< -o $@ $(EXAMPLE_LIBS)
examples: build/examples/minimal_c build/examples/minimal_cpp build/examples/fabric_to_mesh \
          build/examples/coarse_to_wrinkles
	./build/examples/minimal_c
	./build/examples/minimal_cpp
	./build/examples/fabric_to_mesh
	./build/examples/coarse_to_wrinkles

# `make install` into a scratch DESTDIR, then build and run the examples through pkg-config.
install-check:
	@sh tools/install_check.sh
