"""``micropillar pack``: the offline explorer's file (its size bound, what it holds, the
CLI's errors). The page itself is tested in tests/browser/test_offline_pack.py."""
from __future__ import annotations

import json
import re

from app.offline.pack import MAX_BYTES
from model.cli import main
from model.controls import CONTROLS


def test_pack_writes_one_self_contained_file_within_the_bound(tmp_path, capsys):
    import panel  # noqa: F401  -- registers models whose scripts Bokeh would add by address
    out = tmp_path / "explorer.html"
    assert main(["pack", "--out", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    html = out.read_text(encoding="utf-8")
    assert 0 < out.stat().st_size <= MAX_BYTES
    # Nothing loaded from elsewhere: no script, link or image by address (in the markup;
    # the scripts' own text is theirs).
    markup = re.sub(r"(<script[^>]*>).*?</script>", r"\1</script>", html, flags=re.S | re.I)
    assert not re.search(r"<(script|link|img|iframe)[^>]+(src|href)=", markup, re.I)
    assert "connect-src" not in html and "default-src 'none'" in html  # requests refused
    assert 'id="mp-kernel"' in html and "MicropillarKernel" in html
    config = json.loads(re.search(r'<script id="mp-config" type="application/json">\n(.*?)\n'
                                  r'</script>', html, re.S).group(1))
    assert config["controls"]["k_r"]["lo"] == CONTROLS["k_r"].interval.lo
    assert config["controls"]["F_N"]["default"] == CONTROLS["F_N"].default


def test_pack_refuses_a_missing_folder(tmp_path, capsys):
    assert main(["pack", "--out", str(tmp_path / "no" / "explorer.html")]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "does not exist" in err
    assert main(["pack", "--out", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err


def test_the_offline_explorers_modules_are_small():
    """Each module of the offline explorer (its page scripts, the kernel and the Python
    that packs them) stays within the project's 400 lines, one concept each."""
    from importlib import resources

    here = resources.files("app.offline")
    sizes = {p.name: len(p.read_text(encoding="utf-8").splitlines())
             for p in here.iterdir() if p.name.endswith((".js", ".py"))}
    assert {"page.js", "kernel.js", "pack.py"} <= set(sizes)
    assert {name: n for name, n in sizes.items() if n > 400} == {}
