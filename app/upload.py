"""The bytes of a file uploaded to the page as text: refused, with a ``ValueError`` naming
the file and the fix, when empty, larger than the page reads, or not UTF-8 text. Each
reader (``app.histogram``, ``app.views.design_law``) parses the text in its own form."""
from __future__ import annotations


def upload_text(data: bytes | None, name: str, most: int, empty_hint: str,
                large_hint: str) -> str:
    """The UTF-8 text of ``data`` (a byte-order mark dropped); ``name`` says which file,
    ``most`` is the largest size read (bytes), the hints say what to do instead."""
    if data is None or len(data) == 0:
        raise ValueError(f"{name} is empty: {empty_hint}")
    if len(data) > most:
        raise ValueError(f"{name} is too large ({len(data):,} bytes, at most {most:,}): "
                         f"{large_hint}")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"{name} is not a text (UTF-8) CSV file") from None
