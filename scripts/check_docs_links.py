#!/usr/bin/env python3
"""Checks the manual's links: README.md and every page of docs/ (run by scripts/build-docs.sh and the CTest label
docs). Usage: check_docs_links.py [REPO_ROOT]

- README.md: at most 400 lines, a '## Contents' heading followed by a list of links.
- Every relative link or image in README.md and docs/**/*.md (outside code) names a file or folder that exists,
  and its #anchor, in a Markdown file, is a heading of that file by GitHub's rule (lowercase; punctuation other
  than '-' and '_' dropped; each space to '-'; a repeated heading gets -1, -2, ...). A link to the same page is
  checked the same way.
- A docs/ page links only inside docs/ (mkdocs cannot follow a link out of docs_dir: mention such files as text).
- docs/index.md links every page of docs/, and mkdocs.yml's nav names every page.
Prints FILE:LINE: problem for each failure and exits 1; exits 0 with a one-line summary otherwise."""
import os
import re
import sys

MAX_README_LINES = 400
LINK = re.compile(r"!?\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFDEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s+<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")
ANCHOR_TAG = re.compile(r"<a\s+[^>]*(?:id|name)=\"([^\"]+)\"")


def github_slug(text):
    return re.sub(r"[^\w\- ]", "", text.strip().lower()).replace(" ", "-")


def heading_text(raw):
    """The text GitHub renders for a heading: links to their text, code spans and emphasis to their content."""
    t = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", raw)
    t = t.replace("`", "")
    t = re.sub(r"(\*\*|__)(.+?)\1", r"\2", t)
    t = re.sub(r"<[^>]+>", "", t)
    return t


def lines_outside_code(text, blank=True):
    """(line number, line) for lines outside fenced code blocks, with inline code spans blanked (blank=True)."""
    out, fence = [], None
    for n, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if m:
            if fence is None:
                fence = m.group(1)
            elif line.strip().startswith(fence):
                fence = None
            continue
        if fence is None:
            out.append((n, re.sub(r"`[^`]*`", lambda c: " " * len(c.group(0)), line) if blank else line))
    return out


def anchors_of(path, cache={}):
    if path not in cache:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        seen, anchors = {}, set()
        for _, line in lines_outside_code(text, blank=False):
            m = HEADING.match(line)
            if m:
                slug = github_slug(heading_text(m.group(2)))
                k = seen.get(slug, 0)
                seen[slug] = k + 1
                anchors.add(slug if k == 0 else f"{slug}-{k}")
            for a in ANCHOR_TAG.findall(line):
                anchors.add(a)
        cache[path] = anchors
    return cache[path]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    docs = os.path.join(root, "docs")
    problems, nlinks, nanchors = [], 0, 0

    def problem(path, line, msg):
        problems.append(f"{os.path.relpath(path, root)}:{line}: {msg}")

    pages = sorted(os.path.join(d, f) for d, _, fs in os.walk(docs) for f in fs if f.endswith(".md"))
    files = [os.path.join(root, "README.md")] + pages
    for path in files:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        in_docs = path.startswith(docs + os.sep)
        for n, line in lines_outside_code(text):
            urls = [m.group(2) for m in LINK.finditer(line)]
            m = REFDEF.match(line)
            if m:
                urls.append(m.group(1))
            for url in urls:
                if re.match(r"^[a-z][a-z0-9+.-]*:", url, re.I) or url.startswith("//"):
                    continue  # http:, https:, mailto:
                nlinks += 1
                target, _, anchor = url.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), target)) if target else path
                if target.startswith("/"):
                    problem(path, n, f"absolute link '{url}': use a relative one")
                    continue
                if not os.path.exists(dest):
                    problem(path, n, f"link '{url}': no such file {os.path.relpath(dest, root)}")
                    continue
                if in_docs and not (dest == docs or dest.startswith(docs + os.sep)):
                    problem(path, n, f"link '{url}' leaves docs/: the site cannot follow it; name the file as text")
                    continue
                if anchor:
                    if dest.endswith(".md") and os.path.isfile(dest):
                        nanchors += 1
                        if anchor not in anchors_of(dest):
                            problem(path, n, f"link '{url}': no heading with anchor #{anchor} in "
                                    f"{os.path.relpath(dest, root)}")
    # README: the front door
    readme = os.path.join(root, "README.md")
    with open(readme, encoding="utf-8") as f:
        rl = f.read().split("\n")
    count = len(rl) - (1 if rl and rl[-1] == "" else 0)
    if count > MAX_README_LINES:
        problem(readme, count, f"README.md has {count} lines, more than {MAX_README_LINES}")
    try:
        i = rl.index("## Contents")
        items = []
        for line in rl[i + 1:]:
            if line.startswith("#"):
                break
            if re.match(r"^\s*[-*] \[", line):
                items.append(line)
        if not items:
            problem(readme, i + 1, "'## Contents' is not followed by a list of links")
    except ValueError:
        problem(readme, 1, "README.md has no '## Contents' heading")
    # docs/index.md and mkdocs.yml list every page
    index = os.path.join(docs, "index.md")
    if not os.path.exists(index):
        problem(index, 1, "docs/index.md (the contents page) is missing")
    else:
        with open(index, encoding="utf-8") as f:
            linked = {os.path.normpath(os.path.join(docs, m.group(2).partition("#")[0]))
                      for m in LINK.finditer(f.read())}
        for p in pages:
            if p != index and p not in linked:
                problem(index, 1, f"the contents do not list {os.path.relpath(p, docs)}")
    yml = os.path.join(root, "mkdocs.yml")
    if os.path.exists(yml):
        with open(yml, encoding="utf-8") as f:
            nav = set(re.findall(r"^\s*-\s*(?:[^\n]*?:\s+)?\"?([\w./-]+\.md)\"?\s*$", f.read(), re.M))
        for p in pages:
            if os.path.relpath(p, docs) not in nav:
                problem(yml, 1, f"nav does not list {os.path.relpath(p, docs)}")
    for p in problems:
        print(p)
    if problems:
        print(f"check_docs_links: {len(problems)} problem(s)")
        return 1
    print(f"check_docs_links: {len(files)} files, {nlinks} relative links, {nanchors} anchors: all resolve; "
          f"README.md {count} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
