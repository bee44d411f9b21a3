PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
# setuptools announces every editable install with an information-only notice, not a
# warning about the project; it is filtered by its text and nothing else is.
INSTALL := PYTHONWARNINGS="ignore:Editable installation" $(BIN)/python -m pip install --quiet

.PHONY: demo test test-franka judges lint format bench pictures vsix clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(INSTALL) -e '.[dev,panda]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/lightrocks check examples
	$(BIN)/lightrocks run examples/screwing/tasks/ScrewTask.lr --adapter mujoco

test: $(STAMP)
	$(BIN)/python -m pytest -n auto --dist worksteal --ignore=tests/franka

# The Franka adapter judged by the protocol simulators (franky-sim, franka-sim from
# make judges): every test talks to a simulated arm over libfranka's network protocol.
test-franka: $(STAMP)
	$(BIN)/python -m pytest -n auto --dist worksteal tests/franka

# The outside judges of the suite (MatIEC, Beremiz, Chromium, the extension's node tooling),
# made present as CI makes them; ../shared/tools must be beside the clone.
judges:
	bash .ci/judges

bench: $(STAMP)
	$(INSTALL) -e '.[dev,bench]'
	$(BIN)/python benchmarks/bench_check.py
	$(BIN)/python benchmarks/bench_generate.py
	$(BIN)/python benchmarks/bench_runtime.py
	$(BIN)/python benchmarks/bench_adapters.py
	$(BIN)/python benchmarks/bench_case_studies.py
	$(BIN)/python benchmarks/bench_sweep.py
	$(BIN)/python benchmarks/bench_incremental.py
	$(BIN)/python benchmarks/bench_monitor.py
	$(BIN)/python benchmarks/bench_verify.py
	$(BIN)/python benchmarks/bench_studio.py
	@if $(BIN)/python -c "import importlib.util as u, sys; sys.exit(not (u.find_spec('pylibfranka') and u.find_spec('franky_sim')))"; \
		then $(BIN)/python benchmarks/bench_franka.py; \
		else echo "bench_franka: skipped, the franka extra is missing (pip install 'lightrocks[franka]')"; fi

PICTURES := examples/screwing/skills/ScrewIn.lr examples/screwing/tasks/ScrewTask.lr \
	examples/din_rail/tasks/AssembleRail.lr examples/din_rail_ahead/tasks/PlugTerminalAhead.lr

pictures: $(STAMP)
	$(BIN)/lightrocks generate $(PICTURES) --path examples --target dot --option render=png -o docs/images

# The VS Code extension: node tooling stays in vscode/node_modules (npm ci from the lock file).
vsix:
	cd vscode && npm ci --no-audit --no-fund && npx --no-install vsce package --skip-license --out lightrocks.vsix

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

format: $(STAMP)
	$(BIN)/ruff format .
	$(BIN)/ruff check --fix .

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
