"""Writing result files safely (a reader sees the old file or the complete new one), and
reading a user's text file with one clear error."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

__all__ = ["write_atomic", "write_text_atomic", "read_user_text"]


def write_atomic(path, write) -> None:
    """``write(temporary_path)`` into a new file beside ``path``, then moved onto ``path``
    in one step (``os.replace``): readers see the old file or the complete new one, never
    a partial file, and a failed or interrupted write leaves ``path`` as it was."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # the mode open() would give a new file
        write(Path(tmp))
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text_atomic(path, text: str) -> None:
    """``Path.write_text`` (UTF-8), atomically as ``write_atomic``."""
    write_atomic(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def read_user_text(path, kind: str) -> str:
    """The UTF-8 text of the file ``path`` (a byte-order mark dropped); ``ValueError``
    naming the file when it cannot be read or is not text (``kind``: e.g. ``"CSV"``)."""
    try:
        return Path(path).read_text(encoding="utf-8-sig")
    except OSError as error:
        raise ValueError(f"{path}: cannot read it ({error.strerror or error})") from None
    except UnicodeDecodeError:
        raise ValueError(f"{Path(path).name}: not a text file (expected UTF-8 {kind})") from None
