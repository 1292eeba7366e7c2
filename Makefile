# Two entry points: `make lessons` renders every lesson into outputs/, `make test` runs the suite.
# Each creates .venv and installs the project into it when needed (only python3 is required).
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: lessons test test-bounds lint format bench clean

$(STAMP): pyproject.toml
	$(PY) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $(STAMP)

lessons: $(STAMP)
	$(BIN)/sandbox lessons

test: $(STAMP)
	$(BIN)/python -m pytest -q
	$(MAKE) test-bounds

# the world tests again with numba's array bounds checks on (its own compile cache): an
# out-of-bounds index in a kernel fails a test instead of corrupting memory
test-bounds: $(STAMP)
	NUMBA_BOUNDSCHECK=1 NUMBA_CACHE_DIR=$(CURDIR)/.numba-boundscheck \
		$(BIN)/python -m pytest -q -p no:cacheprovider tests/test_settings_change.py

lint: $(STAMP)
	$(BIN)/ruff check . && $(BIN)/ruff format --check .

format: $(STAMP)
	$(BIN)/ruff format . && $(BIN)/ruff check --fix .

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

clean:
	rm -rf $(VENV) outputs/*/ .pytest_cache
