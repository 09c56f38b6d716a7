"""mkdocs hook (mkdocs.yml, hooks:): heading anchors as GitHub makes them, so that one link, e.g.
solvers.md#adaptive-patching---refine-tol, works on GitHub and in the site built by scripts/build-docs.sh."""
import re


def github_slug(value, separator="-"):
    """GitHub's rule: lowercase, drop punctuation except '-' and '_', each space to '-' (runs are kept)."""
    return re.sub(r"[^\w\- ]", "", value.strip().lower()).replace(" ", separator)


def on_config(config, **kwargs):
    config["mdx_configs"].setdefault("toc", {})["slugify"] = github_slug
    return config
