# mpbench - the front door. CMake does the building; this file names the
# everyday commands:
#   make deps   install the Debian packages mpbench needs (idempotent)
#   make        build everything into build/
#   make test   deps, build, run every test (unit and integration)
#   make demo   deps, build, run the demo benchmark, print its report
#   make clean  remove build/
BUILD ?= build
CMAKE_FLAGS ?=
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps configure test demo clean bench

all: configure
	cmake --build $(BUILD) -j $(JOBS)

configure:
	@test -f $(BUILD)/CMakeCache.txt || cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

deps:
	@sh tools/deps.sh

test: deps
	$(MAKE) all
	cd $(BUILD) && ctest --output-on-failure

demo: deps
	$(MAKE) all
	sh tools/demo.sh

clean:
	rm -rf $(BUILD)

bench:
	MPB_BUILD=$(BUILD) sh bench/run.sh $(BENCH_FLAGS)
