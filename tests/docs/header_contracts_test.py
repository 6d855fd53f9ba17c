#!/usr/bin/env python3
"""Headers state contracts (issue 31 item 6): every public header (not under a detail/ folder, not
under tests/) opens with at most 15 comment lines; every docs/derivations/*.md a header names exists
and is listed in docs/derivations/README.md; every test Suite.Name an opening comment names is a
TEST(Suite, Name) in tests/ (Suite.Prefix* names at least one). The checks run first on broken
headers made here, which must fail. Run by ctest: header_contracts_test.py SOURCE_DIR."""
import pathlib
import re
import sys

MAX_LINES = 15
MODULES = ("analytic", "sim", "validation", "scene", "support", "common", "optics", "app", "fuzz", "python")
DERIVATION = re.compile(r"docs/derivations/([\w.-]+\.md)")
TEST_NAME = re.compile(r"\b([A-Z][A-Za-z0-9]+)\.([A-Z][A-Za-z0-9]*\*?|\*)")
TEST_DEF = re.compile(r"^TEST(?:_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\)", re.M)


def opening_comment(text):
    """The header's opening // block, as lines: counted from line 1 (none if line 1 is not a comment)
    to the first line that is not a comment."""
    lines = text.split("\n")
    if not lines or not lines[0].startswith("//"):
        return []
    block = []
    for line in lines:
        if not line.startswith("//"):
            break
        block.append(line)
    return block


def check_header(name, text, derivations, tests):
    """The failures of one header: its opening comment's length, the derivation files and the test
    names it gives."""
    failures = []
    block = opening_comment(text)
    if len(block) > MAX_LINES:
        failures.append(f"{name}: opens with {len(block)} comment lines (at most {MAX_LINES}; "
                        "move the derivation to docs/derivations/)")
    for doc in DERIVATION.findall(text):
        if doc not in derivations:
            failures.append(f"{name}: names docs/derivations/{doc}, which does not exist")
    for suite, test in TEST_NAME.findall("\n".join(block)):
        if not (test.endswith("*") or re.match(r"[A-Z][a-z0-9]+[A-Z]", test)):
            continue  # one capitalized word (Boost.Math): not a test name
        if suite not in tests:
            failures.append(f"{name}: names the test {suite}.{test}, but tests/ has no TEST({suite}, ...)")
        elif test.endswith("*"):
            if not any(t.startswith(test[:-1]) for t in tests[suite]):
                failures.append(f"{name}: names the tests {suite}.{test}, but none matches")
        elif test not in tests[suite]:
            failures.append(f"{name}: names the test {suite}.{test}, which tests/ does not define")
    return failures


def main():
    src = pathlib.Path(sys.argv[1])
    derivations = {p.name for p in (src / "docs/derivations").glob("*.md")}
    tests = {}
    for path in (src / "tests").rglob("*.cpp"):
        for suite, test in TEST_DEF.findall(path.read_text(errors="replace")):
            tests.setdefault(suite, set()).add(test)

    # Broken headers made here: each must fail, or the checks prove nothing.
    good = "// vgroove x: what it computes.\n// Tests: tests/x_test.cpp (Brdf3d.CookTorranceIsTheK1Term).\n" \
           "// Derivation: docs/derivations/brdf_3d.md.\n#pragma once\n"
    broken = {
        "too long": "".join(f"// line {j}\n" for j in range(MAX_LINES + 1)) + "#pragma once\n",
        "missing derivation": good.replace("brdf_3d.md", "no_such_topic.md"),
        "unknown test": good.replace("CookTorranceIsTheK1Term", "NoSuchTest"),
        "unknown suite": good.replace("Brdf3d.", "NoSuchSuite."),
    }
    self_failures = [f"the check passes a good header: {f}" for f in check_header("good", good, derivations, tests)]
    for what, text in broken.items():
        if not check_header(what, text, derivations, tests):
            self_failures.append(f"the check passes a broken header ({what})")

    failures = []
    headers = sorted(p for m in MODULES for p in (src / m).rglob("*.h"))
    for path in headers:
        rel = path.relative_to(src).as_posix()
        text = path.read_text(errors="replace")
        if "detail" in path.relative_to(src).parts:
            # Internal headers: no length rule, but the derivations they name must exist.
            failures += [f for f in check_header(rel, text, derivations, tests) if "docs/derivations" in f]
        else:
            failures += check_header(rel, text, derivations, tests)

    index = (src / "docs/derivations/README.md").read_text() if "README.md" in derivations else ""
    for doc in sorted(derivations - {"README.md"}):
        if f"({doc})" not in index and f"`{doc}`" not in index:
            failures.append(f"docs/derivations/README.md does not list {doc}")

    for f in self_failures + failures:
        print(f)
    print(f"{len(headers)} headers, {len(derivations)} derivation files: "
          f"{len(self_failures) + len(failures)} failures")
    return 1 if self_failures or failures else 0


if __name__ == "__main__":
    sys.exit(main())
