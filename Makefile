# mpbench - the front door. CMake does the building; this file names the
# everyday commands:
#   make deps   install the Debian packages mpbench needs, the PyPI lcm
#               package into .venv for the Python planner, and three.js and
#               playwright-core from npm into .cache/web with Debian's
#               chromium for the HTML views, and the robots and
#               MotionBenchMaker problems of PyPI's vamp-planner 0.6.4
#               into .cache/robots (tools/robot_data.sh), and OMPL's
#               ompl_benchmark_statistics.py from Debian's source package
#               of the installed OMPL into .cache/ompl-peer, which the
#               import parity test runs (bench/ompl_peer.sh), and the peer
#               planners' libraries (planners/peers/requirements: OMPL 2,
#               roboplan, MPLib, pybullet-planning, Klampt, srmp,
#               Tesseract, Drake), each pinned by hash into its own
#               environment under .cache/peers (tools/peers_env.sh)
#               (idempotent)
#   make        build everything into build/
#   make test   deps, build, run every test (unit and integration)
#   make demo   deps, build, run the demo benchmark, print its report
#   make bench  deps, then the benchmark of the benchmark (bench/run.sh;
#               root, about 15 minutes): docs/performance.md
#   make clean  remove build/
#   make install  build, then install into PREFIX (default /usr/local; DESTDIR
#               for staging): libmpbench, headers, pkg-config and CMake
#               files, mpbenchd, the planners, mpb, mpb_types.jar, man pages
BUILD ?= build
CMAKE_FLAGS ?=
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX ?= /usr/local
DESTDIR ?=

.PHONY: all deps configure test demo clean bench install

all: configure
	cmake --build $(BUILD) -j $(JOBS)

configure:
	@test -f $(BUILD)/CMakeCache.txt || cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

deps:
	@sh tools/deps.sh
	@sh tools/python_env.sh
	@sh tools/web_env.sh
	@sh tools/robot_data.sh >/dev/null
	@sh bench/ompl_peer.sh >/dev/null
	@sh tools/peers_env.sh

# Each test runs once: a test that fails only sometimes is a race to
# find, not a reason to run it again.
CTEST_FLAGS ?= --output-on-failure

test: deps
	$(MAKE) all
	cd $(BUILD) && ctest $(CTEST_FLAGS)

demo: deps
	$(MAKE) all
	sh tools/demo.sh

clean:
	rm -rf $(BUILD)

bench: deps
	MPB_BUILD=$(BUILD) sh bench/run.sh $(BENCH_FLAGS)

# The prefix goes into the build too (CMAKE_INSTALL_PREFIX), so that what
# is built and what is installed agree.
install:
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DCMAKE_INSTALL_PREFIX=$(PREFIX)
	cmake --build $(BUILD) -j $(JOBS)
	DESTDIR="$(DESTDIR)" cmake --install $(BUILD) --prefix $(PREFIX)
