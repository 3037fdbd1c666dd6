"""Sphinx configuration of ropemodel's documentation site (``sphinx-build -W docs docs/_build/html``).

Sphinx, not MkDocs: the docstrings are numpydoc, which Sphinx's numpydoc extension renders as the API
reference; sphinx-gallery executes the worked examples at build time (as pvlib and PyBaMM do), myst-nb
executes the notebooks, and sphinx-argparse reads the command line from its parser.  Generated pages
(the gallery, the notebooks' outputs) live under ``docs/gallery`` and ``docs/_build``, never in git.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import ropemodel
from ropemodel import docs as tables

ROOT = Path(__file__).resolve().parents[1]
os.environ.setdefault("MPLBACKEND", "Agg")

project = "ropemodel"
author = "the ropemodel developers"
copyright = "ropemodel developers, MIT licence"
release = ropemodel.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinxarg.ext",
    "sphinx_gallery.gen_gallery",
    "myst_nb",
]

exclude_patterns = ["_build", "examples", "gallery/*.ipynb", "gallery/*.py", "gallery/*.zip", "**.ipynb_checkpoints",
                    "jupyter_execute"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
suppress_warnings = ["config.cache"]      # sphinx-gallery's settings hold a function (its sort key)

# --- the API reference: numpydoc docstrings, signatures as written (type hints in the signature) ---
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# --- Markdown pages (MyST) and the notebooks (myst-nb, executed at every build) ---
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 600
nb_execution_show_tb = True

# --- the gallery: every example runs at build time; an example that fails (a number no longer
# reproduced: each asserts it) fails the build ---
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "capture_repr": ("_repr_html_", "__repr__"),
    "image_scrapers": ("matplotlib",),
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "plot_gallery": "True",
}

html_theme = "pydata_sphinx_theme"
html_title = f"ropemodel {release}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2, "secondary_sidebar_items": ["page-toc"]}
html_static_path: list[str] = []
html_show_sourcelink = False


#: a repository file that is not a page of the site, but that a page includes: links to it go to that page
INCLUDED = {"studies/README.md": "studies.md"}
_LINK = re.compile(r"(!?)\[([^\]]*)\]\(([^)\s]+)\)")


def repository_paths(app, relative_path, parent_docname, content):
    """Links and images of a file included from outside ``docs/`` (studies/README.md) are
    relative to that file: point them at the site's pages (``/page.md``, relative to this folder) and
    the repository's pictures; a link to another repository file becomes its path as text."""
    src = Path(app.srcdir)
    base = (src / relative_path).resolve().parent

    def fix(m):
        image, label, target = m.groups()
        if re.match(r"^[a-z]+:|^#", target):
            return m.group(0)
        path, _, anchor = target.partition("#")
        full = (base / path).resolve()
        in_repo = full.relative_to(ROOT).as_posix()
        page = INCLUDED.get(in_repo) or (full.relative_to(src).as_posix() if full.is_relative_to(src) else None)
        if image:
            return f"![{label}](/{os.path.relpath(full, src)})"
        if page:
            return f"[{label}](/{page}{'#' + anchor if anchor else ''})"
        return label if label.strip("`") == in_repo else f"{label} (`{in_repo}`)"

    content[0] = _LINK.sub(fix, content[0])


def check_generated_tables(app, docname, source):
    """A page's generated tables must be the registry's: a stale one is a warning (so -W fails the build);
    ``python -m ropemodel.docs`` rewrites them."""
    if tables.update(source[0]) != source[0]:
        from sphinx.util import logging

        logging.getLogger(__name__).warning(f"{docname}: generated tables are stale; run python -m ropemodel.docs",
                                            location=docname)


def setup(app):
    app.connect("source-read", check_generated_tables)
    app.connect("include-read", repository_paths)
