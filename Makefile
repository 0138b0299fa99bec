# lieng: two commands on a fresh machine.
#   make demo   install what is missing, build, run the demo decks into out/
#   make test   the same build, then the test suite
PYTHON ?= python3
VENV   := .venv
VPY    := $(VENV)/bin/python
VPIP   := $(VPY) -m pip
LIENG  := $(VENV)/bin/lieng
SUDO   := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
STAMP  := $(VENV)/.lieng-installed
export PATH := $(CURDIR)/$(VENV)/bin:$(PATH)
SOURCES := pyproject.toml meson.build $(wildcard cards/*.dat cards/figures/*.dat) $(wildcard fortran/*.f90 fortran/*/*.f90) fortran/f2py_f2cmap $(wildcard python/lieng/*.py python/lieng/*/*.py python/lieng/*/*.md)

.PHONY: all demo test test-all bench bench-diagnose gfortran venv install dev clean distclean

all: install

gfortran:
	@command -v gfortran >/dev/null 2>&1 || { \
	  echo "gfortran not found: installing it with apt-get"; \
	  $(SUDO) apt-get update -qq && $(SUDO) DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gfortran; }

$(VENV)/.deps: Makefile | gfortran
	$(PYTHON) -m venv $(VENV)
	$(VPIP) install -q --upgrade pip
	$(VPIP) install -q "meson-python>=0.15" "meson>=1.1" ninja "numpy>=2.0" "scipy>=1.10" "matplotlib>=3.7" "pytest>=7" "hypothesis>=6.100" "dask[distributed]>=2024.1"
	touch $@

venv: $(VENV)/.deps

$(STAMP): $(VENV)/.deps $(SOURCES) | gfortran
	$(VPIP) install -q --no-build-isolation --no-deps .
	touch $@

install: $(STAMP)

# a developer's editable install: an edit under python/ takes effect at the next import, a Fortran edit is
# rebuilt then (no reinstall); run the tests with $(VPY) -m pytest (make test/install reinstall a regular copy)
dev: $(VENV)/.deps | gfortran
	$(VPIP) install -q --no-build-isolation --no-deps -e .
	rm -f $(STAMP)
	@echo "editable install in $(VENV): $(VPY) -m pytest -q -m 'not slow' tests"

demo: install
	rm -rf out
	$(LIENG) run lieng1 cards/lieng1_demo.dat -o out/lieng1
	$(LIENG) run mlien cards/mlien_a9_7.dat -o out/mlien
	$(LIENG) run trc cards/trc_demo.dat -o out/trc
	$(LIENG) figures -o out/figures
	$(LIENG) twodof --preload 80 -o out/twodof
	@echo "demo written to out/"

test: install
	$(VPY) -m pytest -q -m "not slow" tests

test-all: install
	$(VPY) -m pytest -q tests

bench: install
	$(VPY) tests/benchmarks/bench_point.py
	$(VPY) tests/benchmarks/bench_trc.py
	$(VPY) tests/benchmarks/bench_sweep.py
	$(VPY) tests/benchmarks/bench_twodof.py
	$(VPY) tests/benchmarks/bench_diagnose_scale.py
	$(VPY) tests/benchmarks/bench_map.py

bench-diagnose: install
	$(VPY) tests/benchmarks/bench_diagnose.py --seeds 8

clean:
	rm -rf build out .pytest_cache

distclean: clean
	rm -rf $(VENV)
