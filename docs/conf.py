"""Sphinx configuration of the documentation site (``python -m sphinx -b html docs OUT``).

Pages are Markdown (MyST); the API reference is generated from the numpydoc docstrings
of the installed ``model`` package, and their examples run as doctests
(``python -m sphinx -b doctest docs OUT``; both builds run in tests/test_docs_build.py).
"""
import model

project = "micropillar-friction"
author = "The micropillar-friction developers"
copyright = "The micropillar-friction developers"
release = model.__version__
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.doctest",
    "sphinx.ext.mathjax",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
#: docs/upstream holds plain-Panel reproducers of library bugs (scripts, not pages).
exclude_patterns = ["_build", "upstream", "api/generated/*.md",
                    "performance-latest.md"]  # written by benchmarks/run_all.py, included

# MyST: anchors for ## and ### headings, so pages can link to sections (page.md#anchor).
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

# API reference: one page per public object, written from the docstrings at build time.
autosummary_generate = True
autodoc_typehints = "none"  # the numpydoc Parameters sections carry the types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# Doctests: each example block runs as written; numbers are printed rounded in the
# docstrings, so the comparison is exact.
doctest_global_setup = "import numpy as np"
doctest_test_doctest_blocks = "default"

html_theme = "pydata_sphinx_theme"
html_title = "micropillar-friction"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
}
html_static_path = []
