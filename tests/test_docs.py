#!/usr/bin/env python3
"""Docs a test keeps true (issue 41): every repository path, C++ type and function that the
Markdown files (README.md, BENCHMARKS.md, docs/, spec/, …) name in backquotes exists.

* A path is a backquoted word starting with a top folder of the repository (`lib/…`, `spec/…`);
  a `:LINE` or `:FIRST-LAST` suffix is ignored, `*` and `<placeholder>` match any name. A path
  in the prose (spec/RUN.md, lib/core/src/verify.cpp) must exist too.
* A qualified name (`mosb::load`, `Store::references`, `SolutionReader::verify_payload()`): its
  last part is a word of some source file.
* A CamelCase type (`GraphReader`) or a call (`write_graph()`): a word of some source file.

Things outside the repository (a CLI11 option type, a command's output) are neither, so they are
not checked. Run: /usr/bin/python3 tests/test_docs.py."""
import fnmatch
import os
import re
import sys
import unittest

ROOT = os.path.realpath(os.path.join(os.path.dirname(__file__), ".."))
SKIPPED_DIRS = {".git", "build", ".venv", "__pycache__", "node_modules"}
TOP_FOLDERS = ("lib/", "tools/", "converters/", "report/", "format/", "spec/", "docs/", "tests/",
               "examples/", "profiles/", "python/", "capi/", "cmake/", ".ci/")
SOURCE = re.compile(r"\.(cpp|hpp|h|c|py|cmake|sh|toml|in)$|(^|/)CMakeLists\.txt$")


def tree(root):
    """The repository's files and folders, relative to `root`, without build outputs."""
    files, folders = set(), set()
    for directory, subdirs, names in os.walk(root):
        subdirs[:] = [d for d in subdirs if d not in SKIPPED_DIRS]
        relative = os.path.relpath(directory, root)
        if relative != ".":
            folders.add(relative)
        for name in names:
            files.add(name if relative == "." else relative + "/" + name)
    return files, folders


def source_words(root, files):
    words = set()
    for f in files:
        if SOURCE.search(f):
            with open(os.path.join(root, f), encoding="utf-8", errors="replace") as text:
                words.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text.read()))
    return words


PROSE_PATH = re.compile(r"(?<![\w/.`<*-])((?:%s)[\w./-]*\w\.(?:md|cpp|hpp|h|c|py|sh|toml|json|txt))"
                        r"(?![\w/*-])" % "|".join(re.escape(t) for t in TOP_FOLDERS if t != ".ci/"))


def problems(name, text, files, folders, words):
    """(name, line, token, why) for each backquoted token of `text`, and each file path in its
    prose, that names nothing here."""
    found = []
    for m in PROSE_PATH.finditer(text):
        if m.group(1) not in files:
            found.append((name, text.count("\n", 0, m.start()) + 1, m.group(1),
                          "no such file"))
    for m in re.finditer(r"`([^`\n]+)`", text):
        token = m.group(1).strip()
        line = text.count("\n", 0, m.start()) + 1
        if token.startswith(TOP_FOLDERS) and " " not in token:
            path = re.sub(r":[0-9,\-]+$", "", token).rstrip("/").rstrip(",.")
            pattern = re.sub(r"<[^>/]+>", "*", path)
            if any(c in pattern for c in "*?["):
                if not any(fnmatch.fnmatch(f, pattern) for f in files | folders):
                    found.append((name, line, token, "no file matches"))
            elif path not in files and path not in folders:
                found.append((name, line, token, "no such file or folder"))
        elif re.fullmatch(r"(?:[A-Za-z_]\w*::)+~?[A-Za-z_]\w*(?:\(\))?", token):
            last = token.replace("()", "").split("::")[-1].lstrip("~")
            if last not in words:
                found.append((name, line, token, "no source names " + last))
        elif re.fullmatch(r"[A-Z][a-z0-9]+(?:[A-Z][a-z0-9]*)+", token):
            if token not in words:
                found.append((name, line, token, "no source names it"))
        elif re.fullmatch(r"[a-z_][a-z0-9_]*\(\)", token):
            if token[:-2] not in words:
                found.append((name, line, token, "no source names it"))
    return found


class DocsTest(unittest.TestCase):
    def test_every_path_type_and_function_the_docs_name_exists(self):
        files, folders = tree(ROOT)
        words = source_words(ROOT, files)
        docs = sorted(f for f in files if f.endswith(".md"))
        self.assertIn("docs/ARCHITECTURE.md", docs)
        found = []
        for name in docs:
            with open(os.path.join(ROOT, name), encoding="utf-8", errors="replace") as f:
                found += problems(name, f.read(), files, folders, words)
        self.assertEqual([], ["%s:%d: `%s`: %s" % p for p in found])

    def test_the_check_finds_what_is_missing(self):
        files = {"lib/core/src/a.cpp", "profiles/apex.toml"}
        folders = {"lib", "lib/core", "lib/core/src", "profiles"}
        words = {"GraphReader", "load", "references"}
        text = ("`lib/core/src/a.cpp:12-30` `profiles/<name>.toml` `mosb::load` `GraphReader`\n"
                "`lib/core/src/gone.cpp` `profiles/*.json` `Store::gone` `InstanceEditor` "
                "`gone()` `--not-a-path` `a value`\n"
                "As lib/core/src/a.cpp says (and lib/core/src/b.cpp, which is gone).\n")
        self.assertEqual([(t, why) for _, _, t, why in problems("x.md", text, files, folders, words)],
                         [("lib/core/src/b.cpp", "no such file"),
                          ("lib/core/src/gone.cpp", "no such file or folder"),
                          ("profiles/*.json", "no file matches"),
                          ("Store::gone", "no source names gone"),
                          ("InstanceEditor", "no source names it"),
                          ("gone()", "no source names it")])


if __name__ == "__main__":
    unittest.main(verbosity=2)
