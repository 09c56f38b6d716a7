"""The six walk-method names are spelled in one file only, the method table src/walk/walk_method.h: every other
source of the program and the module (src/, apps/, python/) takes them from it (method_name, kWalkMethods), so a
renamed method cannot leave a stale spelling in a message, a default or a docstring. Comments may name them."""
import re

from conftest import SOURCE

TABLE = SOURCE / "src" / "walk" / "walk_method.h"
NAMES = ("gather-absorption", "gather-collision", "gather-expected-value", "shoot-collision", "shoot-absorption",
         "shoot-survival")


def code_without_comments(text):
    """The text without // comments (outside string literals is enough here: no name follows a '//' in a string)."""
    return "\n".join(re.sub(r"(^|\s)//.*$", "", line) for line in text.splitlines())


def spellings(root_dirs):
    found = []
    for d in root_dirs:
        for path in sorted((SOURCE / d).rglob("*")):
            if path.suffix not in (".cpp", ".h") or path == TABLE:
                continue
            code = code_without_comments(path.read_text(errors="replace"))
            for name in NAMES:
                if re.search(r"(?<![\w-])" + re.escape(name) + r"(?![\w-])", code):
                    found.append(f"{path.relative_to(SOURCE)}: {name}")
    return found


def test_the_method_table_is_the_only_file_that_spells_the_method_names():
    table = TABLE.read_text()
    for name in NAMES:
        assert f'"{name}"' in table, name
    found = spellings(["src", "apps", "python"])
    assert not found, "walk-method names spelled outside src/walk/walk_method.h: " + "; ".join(found)


def test_the_check_finds_a_planted_spelling(tmp_path, monkeypatch):
    """A test that cannot fail is a defect: a copy of a source that spells a name is found."""
    import test_method_names as t
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "x.cpp").write_text('const char* m = "gather-collision";  // a default\n// gather-absorption\n')
    monkeypatch.setattr(t, "SOURCE", tmp_path)
    assert t.spellings(["src"]) == ["src/x.cpp: gather-collision"]
