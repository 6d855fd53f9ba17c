"""`vgroove report` (python/vgroove/html_report.py): one self-contained HTML page of the reports in a
directory. Every report kind gets its section (the paper's figures beside ours, failing and worst
cases first, thresholds, seeds, plots); hostile names are escaped; damaged and foreign JSON files
are named with the reason they were skipped; an empty directory or a bad --out is a one-line error,
exit 2, nothing written; plots are embedded only when they decode, else drawn again or named."""

import json
import os
import shutil
import struct
import zlib

import pytest

from conftest import HAVE_MODULE, cli, write_json
from page_check import check_page, html_report

KINDS = ("brdf", "furnace", "table2", "table1", "table1_set", "sampling", "nonsymmetric_brdf", "profiles",
         "accuracy")
SUITE_NAMES = {"brdf": "tiny_brdf", "furnace": "tiny_furnace", "table2": "tiny_table2", "table1": "tiny_table1",
               "table1_set": "tiny_set", "sampling": "tiny_sampling", "nonsymmetric_brdf": "tiny_nonsymmetric_brdf",
               "profiles": "tiny_profiles", "accuracy": "tiny_table1"}


def load(path):
    with open(path) as f:
        return json.load(f)


@pytest.fixture(scope="module")
def run_dir(reports, tmp_path_factory):
    """The reports of every kind, as a run leaves them in results/ (without plots)."""
    d = tmp_path_factory.mktemp("run")
    for kind in KINDS:
        shutil.copy(reports[kind], d / f"{kind}.json")
    return d


def page_of(directory, tmp_path, draw=False):
    out = tmp_path / "page.html"
    info = html_report.write(str(directory), str(out), force=True, draw_missing=draw)
    return check_page(str(out)), info, out


def test_every_report_kind_has_its_section(run_dir, tmp_path):
    page, info, _ = page_of(run_dir, tmp_path)
    assert info["skipped"] == [] and sorted(info["reports"]) == sorted(f"{k}.json" for k in KINDS)
    overview = page.table("Reports")
    assert [r[-1] for r in overview["rows"][1:]] == sorted(f"{k}.json" for k in KINDS)
    text = page.text()
    for kind in KINDS:
        assert SUITE_NAMES[kind] in text
        # --no-draw: every plot `vgroove plot` would write is named, none embedded
    assert "no table2.png beside the report; not drawn (vgroove plot table2.json --force draws it)" in text
    assert "no brdf-ggx-3d.png beside the report" in text
    assert page.images == []
    # Version, git revision and seeds of every report; the tiny set's two suites have seeds 7 and 2018.
    rows = {r[-1]: r for r in overview["rows"][1:]}
    assert rows["table1_set.json"][7] == "7, 2018"
    assert rows["brdf.json"][5] == load(run_dir / "brdf.json")["version"]
    assert rows["brdf.json"][6] == load(run_dir / "brdf.json")["git"]
    assert rows["brdf.json"][2] == "PASS" and rows["table1_set.json"][2] == "FAIL"


def test_the_papers_figures_beside_ours(run_dir, tmp_path):
    page, _, _ = page_of(run_dir, tmp_path)
    r = load(run_dir / "table1.json")
    t = page.table("The paper's figures beside ours (made up)")
    head, row = t["rows"][0], t["rows"][1]
    assert head[:4] == ["suite", "paper max L1", "ours max L1", "threshold"]
    assert row[:4] == ["tiny_table1", "0.003", f"{r['summary']['max_l1']:.4g}", "0.5"]
    assert row[4:6] == ["0.0005", f"{r['summary']['mean_l1']:.4g}"]
    assert row[-1] == "PASS"
    # Table 2: paper / ours / traced per cell, the grid as the paper prints it.
    t2 = load(run_dir / "table2.json")
    grid = page.table("The paper's figures beside ours: paper / ours / traced")
    e = t2["entries"][0]
    cells = {(r[0], h): c for r in grid["rows"][1:] for h, c in zip(grid["rows"][0], r)}
    assert cells[(f"{e['percentile']:.4g} %", f"{e['ndf']} {e['alpha']:.4g}")] == \
        f"{e['paper']} / {e['ours']} / {e['traced_percentile_k']}"


def test_failing_cases_come_first(run_dir, tmp_path):
    d = tmp_path / "run"
    d.mkdir()
    r = load(run_dir / "brdf.json")
    r["cases"][2]["pass"] = False
    r["cases"][2]["l1"] = 0.9
    r["pass"] = False
    write_json(d / "brdf.json", r)
    page, _, _ = page_of(d, tmp_path)
    t = page.table("Worst cases by L1 / threshold (4 cases, 1 failing)")
    assert t["rows"][1][4] == "0.9" and t["rows"][1][-1] == "FAIL"
    assert [row[-1] for row in t["rows"][2:]] == ["PASS"] * 3
    # Then by L1 / threshold, largest first.
    ratios = [float(row[8]) for row in t["rows"][2:]]
    assert ratios == sorted(ratios, reverse=True)
    assert page.table("Reports")["rows"][1][2] == "FAIL"
    assert "1 failing" in page.text()
    # Single-groove cases carry no verdict: those beyond the suite's max L1 are the failing ones.
    t1 = load(run_dir / "table1.json")
    l1 = sorted(c["l1"] for c in t1["cases"])
    t1["thresholds"]["max_l1"] = l1[-4]  # three cases above it
    write_json(d / "table1.json", t1)
    page, _, _ = page_of(d, tmp_path)
    t = page.table(f"tiny_table1: largest L1 ({len(l1)} cases, 3 failing; threshold max L1 {l1[-4]:.4g})")
    assert [float(r[2]) for r in t["rows"][1:4]] == [float(f"{x:.4g}") for x in l1[:-4:-1]]


HOSTILE = ["<script>alert('x')</script>", '"><img src=x onerror=alert(1)>', "a\x1b[31mred\x00nul", "line\nbreak\r",
           "\u202eevil\u202c bidi \ufeff", "\ud800 lone surrogate", "x" * 5000, "]]>&amp;&#0;<!--", "</table></td>"]


def test_hostile_names_are_escaped(run_dir, tmp_path):
    d = tmp_path / "run"
    d.mkdir()
    s = load(run_dir / "table1_set.json")
    s["suite"], s["version"], s["git"] = HOSTILE[0], HOSTILE[1], HOSTILE[2]
    s["suites"][0]["suite"], s["suites"][1]["suite"] = HOSTILE[3], HOSTILE[4]
    s["suites"][0]["paper"]["source"] = HOSTILE[7]
    s["suites"][0]["thresholds"][HOSTILE[8]] = HOSTILE[5]
    write_json(d / "table1_set.json", s)
    b = load(run_dir / "brdf.json")
    b["suite"], b["description"], b["suite_file"] = HOSTILE[5], HOSTILE[6], HOSTILE[1]
    b["cases"][0]["ndf"] = HOSTILE[0]
    b["summary"][HOSTILE[0]] = HOSTILE[3]
    # A file name that is not UTF-8 and holds markup.
    with open(os.path.join(os.fsencode(d), b"<b onclick=x>\xff\xfe.json"), "w") as f:
        json.dump(b, f)
    with open(d / "table2.json", "w") as f:
        t2 = load(run_dir / "table2.json")
        t2["entries"][0]["ndf"], t2["source"] = HOSTILE[0], HOSTILE[1]
        t2["assumptions"][HOSTILE[4]] = HOSTILE[0]
        json.dump(t2, f)
    page, info, out = page_of(d, tmp_path)
    assert info["skipped"] == []
    text = page.text()
    # The markup is text: shown, never parsed (check_page found no script, handler or foreign tag).
    assert "<script>alert('x')</script>" in text
    assert '"><img src=x onerror=alert(1)>' in text
    assert "<b onclick=x>\\xff\\xfe.json" in text  # the bytes that are not UTF-8 as escapes
    assert "a\\u001b[31mred\\u0000nul" in text
    assert "line\\u000abreak\\u000d" in text
    assert "\\u202eevil\\u202c bidi \\ufeff" in text and "\u202e" not in text
    assert "\\ud800 lone surrogate" in text
    assert "x" * 397 + "..." in text and "x" * 398 not in text  # a description: 400 characters at most
    assert "]]>&amp;&#0;<!--" in text and "</table></td>" in text
    raw = out.read_bytes()
    assert b"<script" not in raw and b"onerror=" not in raw.replace(b"onerror=alert(1)&gt;", b"")
    # The CLI takes such a directory as well.
    r = cli("report", d, "--out", tmp_path / "cli.html", "--no-draw")
    assert r.returncode == 0, r.stderr
    check_page(str(tmp_path / "cli.html"))


def test_damaged_and_foreign_json_are_named(run_dir, tmp_path, reports, suites):
    d = tmp_path / "run"
    d.mkdir()
    shutil.copy(run_dir / "table2.json", d / "table2.json")
    good = (d / "table2.json").read_text()
    (d / "broken.json").write_text(good[: len(good) // 2])
    (d / "empty.json").write_text("")
    (d / "array.json").write_text("[1, 2]")
    (d / "nan.json").write_text('{"tool": "vgroove", "x": NaN}')
    (d / "latin1.json").write_bytes(b'{"tool": "vgroove", "suite": "caf\xe9"}')
    (d / "foreign.json").write_text('{"name": "left-pad", "version": "1.3.0"}')
    shutil.copy(suites["table2"], d / "suite.json")
    (d / "dir.json").mkdir()
    part = tmp_path / "part.json"
    cli("validate", suites["table2"], "--shard", "1/2", "--out", part)
    shutil.copy(part, d / "part.json")
    page, info, _ = page_of(d, tmp_path)
    assert info["reports"] == ["table2.json"]
    reasons = dict(info["skipped"])
    assert reasons["broken.json"].startswith("not JSON: ") and "line" in reasons["broken.json"]
    assert reasons["empty.json"].startswith("not JSON: Expecting value at line 1 column 1")
    assert reasons["array.json"].startswith("JSON a list, not a vgroove report")
    assert reasons["nan.json"] == "NaN is not JSON"
    assert reasons["latin1.json"].startswith("not UTF-8 text (byte ")
    assert reasons["foreign.json"] == 'not a vgroove report (no "tool": "vgroove")'
    assert reasons["suite.json"].startswith("a suite, not a report")
    assert reasons["dir.json"] == "not a regular file"
    assert reasons["part.json"] == ("a partial report (shard 1 of 2): join the parts with vgroove merge, then report "
                                    "the merged file")
    skipped = page.table("Files skipped")
    assert sorted(r[0] for r in skipped["rows"][1:]) == sorted(reasons)
    # The command line names them too (stdout), and succeeds.
    r = cli("report", d, "--out", tmp_path / "cli.html", "--no-draw")
    assert r.returncode == 0, r.stderr
    assert "report: skipped broken.json: not JSON: " in r.stdout
    assert r.stdout.strip().splitlines()[-1] == f"report: {tmp_path}/cli.html (1 reports, 0 plots, 9 files skipped)"


def test_damaged_fields_never_end_the_page(run_dir, tmp_path):
    # Reports of every kind with 1-3 values or whole objects replaced by values of other types
    # (deterministic, 400 of them): each gives a section or is skipped with its reason.
    import random
    rng = random.Random(2018)
    values = [None, "x", "<b>", [], {}, [1, 2], {"a": 1}, -1, 0, 1e308, -1e308, True, 10**30, 1.5]

    def paths(v, p=()):
        if p:
            yield p
        items = v.items() if isinstance(v, dict) else enumerate(v[:3]) if isinstance(v, list) else []
        for k, x in items:
            yield from paths(x, p + (k,))

    originals = {kind: load(run_dir / f"{kind}.json") for kind in KINDS}
    d = tmp_path / "run"
    d.mkdir()
    outcomes = {"section": 0, "skipped": 0}
    for _ in range(400):
        kind = rng.choice(KINDS)
        r = json.loads(json.dumps(originals[kind]))
        all_paths = list(paths(r))
        for _ in range(rng.randint(1, 3)):
            path = rng.choice(all_paths)
            obj = r
            try:
                for p in path[:-1]:
                    obj = obj[p]
                obj[path[-1]] = json.loads(json.dumps(rng.choice(values)))
            except (KeyError, IndexError, TypeError):
                pass  # an earlier replacement removed this path
        write_json(d / "r.json", r)
        try:
            page, info = html_report.render(str(d), draw_missing=False)
            outcomes["section" if info["reports"] else "skipped"] += 1
        except html_report.ReportError as e:  # the one report skipped, with its reason
            assert "none of its 1 .json files is a vgroove report (r.json: " in str(e)
            outcomes["skipped"] += 1
    assert outcomes["section"] > 300, outcomes


def one_line_error(*args):
    r = cli("report", *args, check=False)
    assert r.returncode == 2, (r.returncode, r.stdout, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("vgroove: error: "), r.stderr
    assert r.stdout == ""
    return lines[0][len("vgroove: error: "):]


def test_empty_or_reportless_directory_is_an_error(tmp_path):
    d = tmp_path / "empty"
    d.mkdir()
    assert one_line_error(d) == (f"{d}: holds no report (*.json); vgroove validate SUITE --out {d}/NAME.json "
                                 "writes one")
    (d / "x.txt").write_text("not json")
    assert one_line_error(d).startswith(f"{d}: holds no report")
    (d / "a.json").write_text("{}")
    (d / "b.json").write_text("[")
    assert one_line_error(d) == (f"{d}: none of its 2 .json files is a vgroove report (a.json: not a vgroove "
                                 'report (no "tool": "vgroove"))')
    assert one_line_error(tmp_path / "missing") == f"{tmp_path}/missing: no such directory"
    assert one_line_error(d / "x.txt").startswith(f"{d}/x.txt: is not a directory")
    assert sorted(os.listdir(d)) == ["a.json", "b.json", "x.txt"]  # nothing written


def test_bad_output_is_an_error_and_writes_nothing(run_dir, tmp_path):
    d = tmp_path / "run"
    d.mkdir()
    shutil.copy(run_dir / "table2.json", d / "table2.json")
    page = d / "index.html"
    page.write_text("old")
    assert one_line_error(d) == f"{page}: exists already; pass --force to overwrite it, or choose another name"
    assert page.read_text() == "old"
    assert one_line_error(d, "--out", tmp_path / "no" / "p.html") == \
        f"{tmp_path}/no/p.html: the directory {tmp_path}/no does not exist"
    assert one_line_error(d, "--out", tmp_path) == f"{tmp_path}: is a directory"
    assert one_line_error(d, "--out", d / "table2.json", "--force") == \
        f"{d}/table2.json: is the input file {d}/table2.json; the page would replace it (choose another name)"
    assert one_line_error(d, "--out", "-") == \
        '--out = "-": the page goes to a file; give a file name, or ./- for a file named "-"'
    assert one_line_error(d, "--out", "") == '--out = "" is empty'
    assert sorted(os.listdir(d)) == ["index.html", "table2.json"]
    r = cli("report", d, "--force", "--no-draw")
    assert r.returncode == 0 and page.read_text().startswith("<!DOCTYPE html>")
    assert sorted(os.listdir(d)) == ["index.html", "table2.json"]  # no temporary left


def test_interrupted_or_failed_write_leaves_nothing(run_dir, tmp_path, monkeypatch, capsys):
    d = tmp_path / "run"
    d.mkdir()
    shutil.copy(run_dir / "table2.json", d / "table2.json")

    def interrupt(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(html_report.os, "replace", interrupt)
    assert html_report.main([str(d), "--no-draw"]) == 130
    assert capsys.readouterr().err == "\nvgroove: interrupted; no report written\n"

    def full(*a, **k):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(html_report.os, "replace", full)
    assert html_report.main([str(d), "--no-draw"]) == 2
    assert capsys.readouterr().err == f"vgroove: error: {d}/index.html: cannot write: No space left on device\n"
    assert os.listdir(d) == ["table2.json"]


def test_the_same_directory_gives_the_same_bytes(run_dir, tmp_path):
    a = tmp_path / "a.html"
    b = tmp_path / "b.html"
    html_report.write(str(run_dir), str(a), draw_missing=False)
    html_report.write(str(run_dir), str(b), draw_missing=False)
    assert a.read_bytes() == b.read_bytes()


def png_chunks(data):
    pos, out = 8, []
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        out.append((data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]))
        pos += 12 + n
    return out


def png_of(chunks):
    return html_report.PNG_SIGNATURE + b"".join(struct.pack(">I", len(body)) + kind + body +
                                                struct.pack(">I", zlib.crc32(kind + body)) for kind, body in chunks)


@pytest.fixture(scope="module")
def table2_png(run_dir, tmp_path_factory):
    """The PNG `vgroove plot` writes for the table2 report."""
    out = tmp_path_factory.mktemp("png") / "table2.png"
    r = cli("plot", run_dir / "table2.json", "--out", out)
    assert r.returncode == 0, r.stderr
    return out.read_bytes()


def test_png_check_finds_every_damage(table2_png):
    assert html_report.png_problem(table2_png) is None
    assert html_report.png_problem(b"GIF89a...") == "not a PNG (no PNG signature)"
    assert html_report.png_problem(table2_png[: len(table2_png) // 2]).startswith("truncated")
    flipped = bytearray(table2_png)
    flipped[len(flipped) // 2] ^= 1
    assert "CRC mismatch" in html_report.png_problem(bytes(flipped))
    chunks = png_chunks(table2_png)
    # Image data that inflates to fewer rows than IHDR announces, with every CRC right.
    pixels = zlib.decompress(b"".join(b for k, b in chunks if k == b"IDAT"))
    short = [c for c in chunks if c[0] not in (b"IDAT", b"IEND")] + [(b"IDAT", zlib.compress(pixels[:-100])),
                                                                      (b"IEND", b"")]
    assert "image data holds" in html_report.png_problem(png_of(short))
    no_end = [c for c in chunks if c[0] != b"IEND"]
    assert html_report.png_problem(png_of(no_end)) == "no IEND chunk (truncated)"
    bad_filter = bytearray(pixels)
    bad_filter[0] = 9
    filt = [c for c in chunks if c[0] not in (b"IDAT", b"IEND")] + [(b"IDAT", zlib.compress(bytes(bad_filter))),
                                                                    (b"IEND", b"")]
    assert html_report.png_problem(png_of(filt)) == "a row with an unknown filter type"


def test_plots_embedded_only_when_fresh_and_whole(run_dir, tmp_path, table2_png):
    d = tmp_path / "run"
    d.mkdir()
    shutil.copy(run_dir / "table2.json", d / "table2.json")
    png = d / "table2.png"
    png.write_bytes(table2_png)
    page, info, _ = page_of(d, tmp_path)
    assert info["plots"] == 1 and len(page.images) == 1
    assert "table2.png" in page.text() and "drawn for this page" not in page.text()
    # A damaged plot is not embedded: named, or drawn again for the page.
    png.write_bytes(table2_png[:-20])
    page, info, _ = page_of(d, tmp_path)
    assert info["plots"] == 0 and page.images == []
    assert "table2.png: table2.png is damaged (truncated" in page.text()
    page, info, _ = page_of(d, tmp_path, draw=True)
    assert info["plots"] == 1 and len(page.images) == 1
    assert "drawn for this page: table2.png is damaged" in page.text()
    assert png.read_bytes() == table2_png[:-20]  # nothing written beside the report
    # A plot older than its report is stale.
    png.write_bytes(table2_png)
    st = os.stat(d / "table2.json")
    os.utime(png, (st.st_atime - 10, st.st_mtime - 10))
    page, info, _ = page_of(d, tmp_path)
    assert "table2.png is older than its report" in page.text() and page.images == []


@pytest.mark.skipif(not HAVE_MODULE, reason="built without the Python module")
def test_reachable_from_the_module(run_dir, tmp_path):
    import vgroove.html_report
    info = vgroove.html_report.write(str(run_dir), str(tmp_path / "m.html"), draw_missing=False)
    assert len(info["reports"]) == len(KINDS)
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="holds no report"):
        vgroove.html_report.write(str(tmp_path / "empty"))


def test_the_installed_command_line_finds_its_script(run_dir, tmp_path):
    # cmake --install puts html_report.py beside plot.py in the prefix's Python package, where the
    # installed vgroove looks for it (nothing of the build tree on the path).
    import subprocess
    from conftest import BIN
    build = os.path.dirname(BIN)
    cmake = shutil.which("cmake")
    if cmake is None or not os.path.exists(os.path.join(build, "cmake_install.cmake")):
        pytest.skip("no cmake or no build tree beside VGROOVE_BIN")
    prefix = tmp_path / "prefix"
    r = subprocess.run([cmake, "--install", build, "--prefix", str(prefix)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert len(list(prefix.rglob("vgroove/html_report.py"))) == 1
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VGROOVE_PLOT")}
    out = tmp_path / "page.html"
    r = subprocess.run([str(prefix / "bin" / "vgroove"), "report", str(run_dir), "--out", str(out), "--no-draw"],
                       capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert len(check_page(str(out)).table("Reports")["rows"]) == len(KINDS) + 1
