# Entry points: `make lessons` renders every lesson into outputs/ (executed notebooks, HTML pages,
# figures, tables, the course book outputs/index.html), `make test` runs the suite, `make notebook`
# opens the lessons as notebooks in JupyterLab. Each creates .venv and installs the project into
# it when needed (only python3 is required).
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
DEV_STAMP := $(VENV)/.installed-dev

.PHONY: lessons notebook test test-suite test-bounds lint format docs bench wheel clean

# the project with what the tests and `make lessons` need (the `test` extra)
$(STAMP): pyproject.toml setup.py
	$(PY) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $(STAMP)

# everything a developer uses: tests, ruff, the docs site, building the wheel (the `dev` extra)
$(DEV_STAMP): $(STAMP)
	$(BIN)/python -m pip install -q -e '.[dev]'
	touch $(DEV_STAMP)

lessons: $(STAMP)
	$(BIN)/sandbox lessons

# JupyterLab on the executed notebooks (made first if missing); the explorer cells have sliders
notebook: $(VENV)/.installed-notebook
	test -f outputs/index.html || $(BIN)/sandbox lessons
	$(BIN)/jupyter lab outputs

$(VENV)/.installed-notebook: $(STAMP)
	$(BIN)/python -m pip install -q -e '.[test,notebook]'
	touch $(VENV)/.installed-notebook

# the suite and the bounds-checked world tests side by side, one per core (each target's output
# shows when it ends): together they take about as long as the suite alone. The engine is
# compiled first, on both cores (`sandbox warmup`); only then do the bounds-checked tests
# compile their own copy, beside the suite (compiling both at once, the warmup took half as
# long again)
test: $(STAMP)
	@echo "the test suite and the bounds-checked world tests, side by side (a few minutes)"
	$(BIN)/sandbox warmup --quiet
	@$(MAKE) --no-print-directory -j2 --output-sync=target test-suite test-bounds

test-suite: $(STAMP)
	$(BIN)/sandbox warmup --quiet
	$(BIN)/python -m pytest -q

# the world tests again with numba's array bounds checks on (its own compile cache): an
# out-of-bounds index in a kernel fails a test instead of corrupting memory
test-bounds: $(STAMP)
	NUMBA_BOUNDSCHECK=1 NUMBA_CACHE_DIR=$(CURDIR)/.numba-boundscheck \
		$(BIN)/python -m pytest -q -p no:cacheprovider tests/test_settings_change.py \
		tests/test_contact_robustness.py tests/test_joint_direct.py tests/test_soft_mass_ratio.py \
		tests/test_toi.py tests/test_ccd_positions.py tests/test_kept_pairs.py \
		tests/test_shock_warm_start.py tests/test_speculative.py tests/test_wide_sweeps.py \
		tests/test_wide_positions.py tests/test_sap_bands.py tests/test_sleep.py \
		tests/test_narrowphase.py

lint: $(DEV_STAMP)
	$(BIN)/ruff check . && $(BIN)/ruff format --check .

format: $(DEV_STAMP)
	$(BIN)/ruff format . && $(BIN)/ruff check --fix .

# the user reference into site/ (warnings are errors)
docs: $(DEV_STAMP)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --site-dir site

# a wheel for a class (dist/): the engine compiled ahead inside it for x86-64 processors with
# AVX2 (sandbox/prebuilt.py, one to two minutes), so that a student's first run loads it
# (the archive is removed from the checkout afterwards: there it would stand in for the engine
# compiled for this processor until `sandbox warmup`)
wheel: $(DEV_STAMP)
	$(BIN)/python -m sandbox.prebuilt
	$(BIN)/python -m build --wheel --outdir dist; status=$$?; rm -f sandbox/prebuilt_kernels.zip; exit $$status

# the benchmarks against pymunk and Box2D 2.3 (the `bench` extra adds the box2d package)
bench: $(VENV)/.installed-bench
	$(BIN)/python benchmarks/run.py

$(VENV)/.installed-bench: $(STAMP)
	$(BIN)/python -m pip install -q -e '.[test,bench]'
	touch $(VENV)/.installed-bench

clean:
	rm -rf $(VENV) outputs/*/ outputs/index.html .pytest_cache site build dist sandbox/prebuilt_kernels.zip
