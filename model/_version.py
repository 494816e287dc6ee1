"""The package's version (``pyproject.toml`` states the same; ``tests/test_citation.py``)."""
__version__ = "0.1.0"
