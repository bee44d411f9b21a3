"""The parse cache: stored units read back whole, planted entries never trusted."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from lightrocks.app import checkstore, cli
from lightrocks.app.parsestore import DiskStore, dumps, read
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench import checkcache, parsecache
from lightrocks.workbench.cachestore import LEDGER
from lightrocks.workbench.languages import language_for

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
MODELS = sorted(p for p in EXAMPLES.rglob("*") if p.suffix in (".lr", ".lrd"))


@pytest.fixture
def store(tmp_path: Path):
    store = DiskStore(tmp_path / "parse")
    parsecache.use_store(store)
    parsecache._memory.clear()
    yield store
    parsecache.use_store(None)
    parsecache._memory.clear()


@pytest.mark.parametrize("path", MODELS, ids=lambda p: p.name)
def test_a_stored_unit_reads_back_with_its_positions(path: Path) -> None:
    unit = language_for(path.suffix).parse(path.read_text(encoding="utf-8"), str(path))
    again = read(dumps(unit))
    assert again == unit
    assert dumps(again) == dumps(unit)  # positions take no part in equality


def test_a_syntax_problem_is_stored_too(store: DiskStore) -> None:
    language = language_for(".lr")
    with pytest.raises(SyntaxProblem) as first:
        parsecache.parse(language, "statechart {", "Broken.lr")
    parsecache._memory.clear()
    with pytest.raises(SyntaxProblem) as second:
        parsecache.parse(language, "statechart {", "Broken.lr")
    assert (second.value.line, second.value.column) == (first.value.line, first.value.column)
    assert len([p for p in store.folder.rglob("*") if p.name != LEDGER]) == 2  # folder, entry


@pytest.mark.parametrize(
    "planted",
    [
        '{"$": "Popen", "args": ["true"]}',
        '{"$": "__class__"}',
        '{"$": "Name"}',
        "not json",
        '{"$": "Name", "name": "x", "position": {"$": "Position", "file": 1}}',
        '{"$": "Name", "name": "x", "position": {"$": "Position", "file": "A.lr", "line": 1, '
        '"column": 1, "extra": 2}}',
        '{"$": "Name", "name": "x", "position": {"$": "Position", "file": "A.lr", "line": 1, '
        '"column": 1}}',
        "[1, 2]",
    ],
)
def test_a_planted_or_corrupt_entry_is_parsed_again(store: DiskStore, planted: str) -> None:
    language, text = language_for(".lr"), (EXAMPLES / "plain" / "Turnstile.lr").read_text()
    expected = language.parse(text, "Turnstile.lr")
    key = parsecache._key(language, text, "Turnstile.lr")
    (store.folder / key[:2]).mkdir(parents=True)
    (store.folder / key[:2] / key).write_text(planted, encoding="utf-8")
    assert store.get(key) is None
    assert parsecache.parse(language, text, "Turnstile.lr") == expected
    assert read((store.folder / key[:2] / key).read_text()) == expected


def test_the_key_covers_grammar_text_and_file(monkeypatch: pytest.MonkeyPatch) -> None:
    language = language_for(".lr")
    key = parsecache._key(language, "text", "A.lr")
    assert key != parsecache._key(language, "text ", "A.lr")
    assert key != parsecache._key(language, "text", "B.lr")
    monkeypatch.setattr(parsecache, "extensions_digest", lambda language: "an extension")
    extended = parsecache._key(language, "text", "A.lr")
    assert extended != key  # the syntax of installed extensions
    monkeypatch.setattr(parsecache, "grammar_digest", lambda module: "another grammar")
    assert parsecache._key(language, "text", "A.lr") not in (key, extended)


def test_a_second_check_reads_every_file_from_the_store(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture
) -> None:
    shutil.copytree(EXAMPLES / "screwing", tmp_path / "models" / "screwing")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setattr(checkstore.DiskStore, "get", lambda self, key: None)  # check again
    hits = []
    read = DiskStore.get
    monkeypatch.setattr(DiskStore, "get", lambda self, key: hits.append(read(self, key)))
    parsecache._memory.clear()
    checkcache._memory.clear()
    first = cli.main(["check", str(tmp_path / "models")]), capsys.readouterr().out
    assert hits and not any(hits)
    monkeypatch.setattr(
        DiskStore, "get", lambda self, key: hits.append(read(self, key)) or hits[-1]
    )
    hits.clear()
    parsecache._memory.clear()
    checkcache._memory.clear()
    second = cli.main(["check", str(tmp_path / "models")]), capsys.readouterr().out
    assert hits and all(hits)
    assert second == first
    parsecache.use_store(None)
    checkcache.use_store(None)
