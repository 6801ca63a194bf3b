# railcontact: `make run` and `make test` install what is missing (Debian packages), build,
# then run the main job / the whole test suite. `make bench` runs the benchmarks.
BUILD ?= build
JOBS ?= 2
DEBIAN_PACKAGES := cmake make g++ pkg-config libeigen3-dev libfftw3-dev libcli11-dev \
  nlohmann-json3-dev libtomlplusplus-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev \
  libboost-math-dev \
  python3-matplotlib python3-numpy python3-scipy python3-dev python3-pybind11 python3-pytest gfortran valgrind \
  libopenmpi-dev openmpi-bin

.PHONY: all deps deps-fuzz configure build run test test-portable test-sanitize test-valgrind fuzz bench clean

all: build

deps:
	@missing=""; for p in $(DEBIAN_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing Debian packages:$$missing"; \
	  if [ "$$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi; \
	  $$SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y --no-install-recommends $$missing; \
	fi

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/railcontact run

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The whole suite built for another instruction set than this CPU's -march=native (its own build
# directory, Release, without the benchmarks): scripts/portable_arch.sh picks one this CPU runs
# whose floating-point code differs (icelake-server on an AMD CPU with AVX-512, x86-64-v3 on an
# Intel one, ...; PORTABLE_ARCH=... chooses another). A test that compares two code paths to the
# last bit fails here as on another CPU (docs/RELIABILITY.md "Reproducibility across CPUs").
PORTABLE_BUILD ?= build-portable
PORTABLE_ARCH ?= $(shell scripts/portable_arch.sh)
test-portable: deps
	@test -n "$(PORTABLE_ARCH)" || { echo "test-portable: no instruction set (scripts/portable_arch.sh failed)"; exit 2; }
	cmake -S . -B $(PORTABLE_BUILD) -DCMAKE_BUILD_TYPE=Release -DRAILCONTACT_ARCH=$(PORTABLE_ARCH) \
	  -DRAILCONTACT_BUILD_BENCHMARKS=OFF
	cmake --build $(PORTABLE_BUILD) -j $(JOBS)
	ctest --test-dir $(PORTABLE_BUILD) --output-on-failure -j $(JOBS)

# The whole suite built with AddressSanitizer and UndefinedBehaviorSanitizer (its own build
# directory; about 10 minutes of build and 1 minute of tests on 2 cores).
SANITIZE_BUILD ?= build-sanitize
SANITIZE_FLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
test-sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAILCONTACT_ARCH=OFF \
	  -DRAILCONTACT_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="$(SANITIZE_FLAGS)" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
	  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" -DRAILCONTACT_BUILD_PYTHON=OFF
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS) --timeout 900

# The C examples (tests/install/example.c, handles.c) under valgrind (ctest c_api.valgrind): valgrind
# cannot run the AVX-512 code of -march=native, so the shared library is built for portable x86-64
# (RAILCONTACT_ARCH=OFF) in its own build directory (only that target: a few minutes on 2 cores).
VALGRIND_BUILD ?= build-valgrind
test-valgrind: deps
	cmake -S . -B $(VALGRIND_BUILD) -DCMAKE_BUILD_TYPE=Release -DRAILCONTACT_ARCH=OFF \
	  -DRAILCONTACT_BUILD_BENCHMARKS=OFF -DRAILCONTACT_BUILD_PYTHON=OFF
	cmake --build $(VALGRIND_BUILD) -j $(JOBS) --target railcontact_shared
	ctest --test-dir $(VALGRIND_BUILD) --output-on-failure -L valgrind

# libFuzzer on every fuzz target (fuzz/, docs/RELIABILITY.md "Fuzzing"): clang++ with
# -fsanitize=fuzzer,address,undefined in its own build directory, FUZZ_SECONDS per target, one
# target after the other (scripts/fuzz.sh; new inputs go to build-fuzz/corpus/, crashes and
# timeouts to fuzz/crashes/<target>/). Only this target needs clang: make test does not.
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_PACKAGES := clang libclang-rt-14-dev
FUZZ_FLAGS := -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
deps-fuzz: deps
	@$(MAKE) --no-print-directory deps DEBIAN_PACKAGES="$(FUZZ_PACKAGES)"

fuzz: deps-fuzz
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DRAILCONTACT_ARCH=OFF -DRAILCONTACT_BUILD_TESTS=OFF -DRAILCONTACT_BUILD_BENCHMARKS=OFF -DRAILCONTACT_FUZZ=ON \
	  -DCMAKE_CXX_FLAGS="$(FUZZ_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzzers
	scripts/fuzz.sh --build $(FUZZ_BUILD) --seconds $(FUZZ_SECONDS)

bench: build
	@for b in $(BUILD)/bench/*_bench; do echo "== $$b"; $$b --benchmark_min_time=0.2; done
	@if [ -d $(BUILD)/python/railcontact ]; then echo "== bench/python_overhead.py"; \
	  PYTHONPATH=$(BUILD)/python /usr/bin/python3 bench/python_overhead.py --build $(BUILD); fi

clean:
	rm -rf $(BUILD) $(PORTABLE_BUILD) $(SANITIZE_BUILD) $(FUZZ_BUILD) $(VALGRIND_BUILD)
