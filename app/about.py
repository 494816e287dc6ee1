"""What the software is and how to cite it, for the page and for every exported file.

The version is the package's (``model.__version__``, the one ``pyproject.toml`` and
``CITATION.cff`` carry); the paper is the one whose model this implements.
"""
from __future__ import annotations

from model import __version__

__all__ = ["NAME", "PAPER", "PAPER_DOI", "version_text", "citation_text"]

NAME = "micropillar-friction"
PAPER = ("N. Menga, F. Bottiglione, G. Carbone, Dynamically induced friction reduction in "
         "micro-structured interfaces, Sci. Rep. 11, 8093 (2021)")
PAPER_DOI = "10.1038/s41598-021-87484-5"


def version_text() -> str:
    """``micropillar-friction 0.1.0``: the name and version, for a page footer or a file."""
    return f"{NAME} {__version__}"


def citation_text() -> str:
    """One line saying what to cite (the software, and the paper it implements)."""
    return (f"{version_text()} (see CITATION.cff), implementing {PAPER}, "
            f"doi:{PAPER_DOI}")
