"""The caches' bounded stores: least recently used entries go first, in memory and on disk,
and whatever another process did to an entry is at worst a miss."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
from lsprotocol import types as lsp
from pytest_lsp import ClientServerConfig, LanguageClient

from lightrocks.app.parsestore import DiskStore
from lightrocks.workbench import cachestore, parsecache
from lightrocks.workbench.cachestore import LEDGER, Folder, Memory
from lightrocks.workbench.languages import language_for

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ENTRY = "x" * 1000


def keys(count: int) -> list[str]:
    """Keys spread over several sub-folders, as digests are."""
    return [f"{index:02x}{index:038x}" for index in range(count)]


def age(folder: Folder, key: str, seconds_ago: float) -> None:
    """Set the last use of an entry, so that the order of uses does not depend on the
    resolution of the file system's clock."""
    moment = time.time() - seconds_ago
    os.utime(folder.folder / key[:2] / key, (moment, moment))


def stored_bytes(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file() and p.name != LEDGER)


def test_the_memory_keeps_the_most_recently_used_entries() -> None:
    memory: Memory[int] = Memory(3)
    for number, key in enumerate("abc"):
        memory.put(key, number)
    assert memory.get("a") == 0  # now the most recently used
    memory.put("d", 3)
    assert len(memory) == 3
    assert memory.get("b") is None
    assert [memory.get(key) for key in "acd"] == [0, 2, 3]


def test_the_parse_cache_in_memory_is_bounded(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(parsecache, "_memory", Memory(5))
    language = language_for(".lr")
    for state in range(20):
        parsecache.parse(language, f"statechart S{state} {{ initial state A; }}", "S.lr")
    assert len(parsecache._memory) == 5


def test_eviction_keeps_the_most_recently_used_entries(tmp_path: Path) -> None:
    folder = Folder(tmp_path, limit=10 * len(ENTRY))
    written = keys(10)
    for index, key in enumerate(written):
        folder.put(key, ENTRY)
        age(folder, key, (100 - index) * cachestore.TOUCH_AFTER)  # the first is the oldest
    assert folder.get(written[0]) == ENTRY  # used now: the most recently used
    newest = keys(11)[10]
    folder.put(newest, ENTRY)  # past the limit: down to three quarters of it, 7 entries
    kept = {key for key in [*written, newest] if folder.get(key) is not None}
    assert kept == {written[0], *written[5:], newest}


def test_a_read_marks_only_entries_not_marked_lately(tmp_path: Path) -> None:
    folder = Folder(tmp_path, limit=10 * len(ENTRY))
    recent, old = keys(2)
    for key in (recent, old):
        folder.put(key, ENTRY)
    age(folder, recent, cachestore.TOUCH_AFTER / 2)
    age(folder, old, cachestore.TOUCH_AFTER * 2)
    before = {key: (tmp_path / key[:2] / key).stat().st_mtime for key in (recent, old)}
    assert folder.get(recent) == ENTRY and folder.get(old) == ENTRY
    assert (tmp_path / recent[:2] / recent).stat().st_mtime == before[recent]
    assert (tmp_path / old[:2] / old).stat().st_mtime > before[old] + cachestore.TOUCH_AFTER


def test_the_folder_stays_within_its_limit(tmp_path: Path) -> None:
    limit = 20_000
    folder = Folder(tmp_path, limit)
    for index, key in enumerate(keys(200)):
        folder.put(key, "y" * (100 + 37 * (index % 50)))
        assert stored_bytes(tmp_path) <= limit
    assert stored_bytes(tmp_path) > limit // 2


def test_the_limit_is_shared_by_processes_through_the_ledger(tmp_path: Path) -> None:
    first, second = Folder(tmp_path, limit=4 * len(ENTRY)), Folder(tmp_path, limit=4 * len(ENTRY))
    for key in keys(3):
        first.put(key, ENTRY)
    second.put(keys(4)[3], ENTRY)
    second.put(keys(5)[4], ENTRY)
    assert stored_bytes(tmp_path) <= 4 * len(ENTRY)


WRITER = """
import sys
from pathlib import Path
from lightrocks.workbench.cachestore import Folder
folder = Folder(Path(sys.argv[1]), limit=int(sys.argv[2]))
for index in range(300):
    key = f"{index % 256:02x}{sys.argv[3]}{index:030x}"
    folder.put(key, key * 25)
    folder.get(f"{(index * 7) % 256:02x}{sys.argv[3]}{(index // 2):030x}")
"""


def test_processes_writing_at_once_keep_whole_entries_within_the_limit(tmp_path: Path) -> None:
    limit = 50_000
    writers = [
        subprocess.Popen([sys.executable, "-c", WRITER, str(tmp_path), str(limit), f"{n:08x}"])
        for n in range(4)
    ]
    assert [writer.wait() for writer in writers] == [0] * 4
    entries = [p for p in tmp_path.rglob("*") if p.is_file() and p.name != LEDGER]
    assert all(p.read_text(encoding="utf-8") == p.name * 25 for p in entries)
    assert limit // 2 < stored_bytes(tmp_path) <= limit * 5 // 4  # a lost ledger line or two


def test_a_folder_without_ledger_is_measured(tmp_path: Path) -> None:
    """Entries written before the folder had a ledger count, and the oldest of them go."""
    for key in keys(10):
        (tmp_path / key[:2]).mkdir()
        (tmp_path / key[:2] / key).write_text(ENTRY, encoding="utf-8")
    Folder(tmp_path, limit=5 * len(ENTRY)).put("ff" + "0" * 38, ENTRY)
    assert stored_bytes(tmp_path) <= 5 * len(ENTRY)


def test_the_limit_is_read_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(cachestore.LIMIT_VARIABLE, "12345")
    assert Folder(Path("unused")).limit == 12345
    monkeypatch.setenv(cachestore.LIMIT_VARIABLE, "a lot")
    assert Folder(Path("unused")).limit == cachestore.DEFAULT_LIMIT


def test_a_vanished_entry_is_a_miss(tmp_path: Path) -> None:
    folder = Folder(tmp_path, limit=10 * len(ENTRY))
    [key] = keys(1)
    folder.put(key, ENTRY)
    (tmp_path / key[:2] / key).unlink()
    assert folder.get(key) is None
    shutil.rmtree(tmp_path)
    assert folder.get(key) is None
    folder.put(key, ENTRY)  # the folder and its ledger come back
    assert folder.get(key) == ENTRY


def test_a_corrupt_entry_or_ledger_is_a_miss_never_an_error(tmp_path: Path) -> None:
    store = DiskStore(tmp_path, limit=1_000_000)
    language, text = language_for(".lr"), (EXAMPLES / "plain" / "Turnstile.lr").read_text()
    key = parsecache._key(language, text, "Turnstile.lr")
    store.put(key, language.parse(text, "Turnstile.lr"))
    (tmp_path / key[:2] / key).write_bytes(b"\xff\xfe not text")
    assert store.get(key) is None
    (tmp_path / LEDGER).write_bytes(b"\xff 12 garbage\n")
    store.put(key, language.parse(text, "Turnstile.lr"))
    assert store.get(key) == language.parse(text, "Turnstile.lr")


def test_an_entry_larger_than_the_limit_is_not_kept(tmp_path: Path) -> None:
    [key] = keys(1)
    Folder(tmp_path, limit=100).put(key, "z" * 101)
    Folder(tmp_path / "nothing", limit=0).put(key, "z")
    assert not [p for p in tmp_path.rglob("*") if p.is_file() and p.name != LEDGER]


@pytest.mark.asyncio
async def test_the_language_server_writes_nothing_to_the_disk_cache(tmp_path: Path) -> None:
    """Every state of a file being typed would be an entry: the server keeps its parses in
    memory (and findings of editor buffers are never stored)."""
    examples = tmp_path / "examples"
    shutil.copytree(EXAMPLES, examples)
    cache = tmp_path / "cache"
    config = ClientServerConfig(
        server_command=[sys.executable, "-m", "lightrocks.app.cli", "lsp"],
        server_env={**os.environ, "XDG_CACHE_HOME": str(cache)},
    )
    client: LanguageClient = await config.start()
    await client.initialize_session(
        lsp.InitializeParams(capabilities=lsp.ClientCapabilities(), root_uri=examples.as_uri())
    )
    edited = examples / "screwing" / "skills" / "Retreat.lr"
    uri, text = edited.as_uri(), edited.read_text(encoding="utf-8")
    client.text_document_did_open(
        lsp.DidOpenTextDocumentParams(lsp.TextDocumentItem(uri, "lightrocks", 1, text))
    )
    for version in range(2, 6):
        typed = text.replace("retreated lifted;", "retreated lifted;" + " " * version)
        client.text_document_did_change(
            lsp.DidChangeTextDocumentParams(
                lsp.VersionedTextDocumentIdentifier(version=version, uri=uri),
                [lsp.TextDocumentContentChangeWholeDocument(typed)],
            )
        )
    symbols = await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(lsp.TextDocumentIdentifier(uri))
    )  # answered after every change before it
    await client.shutdown_session()
    await client.stop()
    assert symbols
    assert not [p for p in cache.rglob("*") if p.is_file()]
