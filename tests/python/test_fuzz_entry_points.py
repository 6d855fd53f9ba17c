"""The Python module's entry points under an address-space limit: every call of the fuzz corpus
(tests/fuzz/corpus/python_entry/, grown by scripts/fuzz_python.py, which scripts/fuzz.sh runs as the
target python_entry) replayed in a child process limited to 2 GiB (RLIMIT_AS, as `ulimit -v`) and
20 s a call: each returns, or raises ValueError, TypeError or the module's one-line MemoryError;
none crashes, hangs, warns or raises anything else."""

import os
import subprocess
import sys

import pytest

from conftest import HAVE_MODULE, SOURCE

FUZZ = os.path.join(SOURCE, "scripts", "fuzz_python.py")
CORPUS = os.path.join(SOURCE, "tests", "fuzz", "corpus", "python_entry")


@pytest.mark.skipif(not HAVE_MODULE, reason="built without the Python module")
def test_the_corpus_replays_without_a_finding():
    r = subprocess.run([sys.executable, FUZZ, "--replay", "--corpus", CORPUS, "--memory-mib", "2048"],
                       capture_output=True, text=True, timeout=280)
    assert r.returncode == 0, r.stderr
    assert f"replayed {len(os.listdir(CORPUS))} entries, 0 findings" in r.stderr


@pytest.mark.skipif(not HAVE_MODULE, reason="built without the Python module")
def test_a_finding_fails_the_replay(tmp_path):
    # The replay's power: an entry the harness cannot run as a clean call is a finding, exit 1.
    corpus = tmp_path / "corpus"
    corpus.mkdir()
    (corpus / "a.json").write_text('{"call": "uniforms", "args": [3]}')
    (corpus / "b.json").write_text('{"call": "no_such_entry_point", "args": []}')
    r = subprocess.run([sys.executable, FUZZ, "--replay", "--corpus", str(corpus)], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 1
    assert "b.json: no_such_entry_point: no entry point 'no_such_entry_point'" in r.stderr, r.stderr
    assert "replayed 2 entries, 1 findings" in r.stderr, r.stderr
