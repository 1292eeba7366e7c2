# Entry points: `make lessons` renders every lesson into outputs/ (executed notebooks, HTML pages,
# figures, tables, the course book outputs/index.html), `make test` runs the suite, `make notebook`
# opens the lessons as notebooks in JupyterLab. Each creates .venv and installs the project into
# it when needed (only python3 is required).
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: lessons notebook test lint format bench clean

$(STAMP): pyproject.toml setup.py
	$(PY) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $(STAMP)

lessons: $(STAMP)
	$(BIN)/sandbox lessons

# JupyterLab on the executed notebooks (made first if missing); the explorer cells have sliders
notebook: $(VENV)/.notebook
	test -f outputs/index.html || $(BIN)/sandbox lessons
	$(BIN)/jupyter lab outputs

$(VENV)/.notebook: $(STAMP)
	$(BIN)/python -m pip install -q -e '.[test,notebook]'
	touch $(VENV)/.notebook

test: $(STAMP)
	$(BIN)/python -m pytest -q

lint: $(STAMP)
	$(BIN)/ruff check . && $(BIN)/ruff format --check .

format: $(STAMP)
	$(BIN)/ruff format . && $(BIN)/ruff check --fix .

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

clean:
	rm -rf $(VENV) outputs/*/ outputs/index.html .pytest_cache build
